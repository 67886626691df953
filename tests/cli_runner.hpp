// Runs the built `blurcull` command (BLURCULL_CLI, defined for the tests that
// use it in tests/CMakeLists.txt) as a user would: in a folder, its exit
// status, standard output and standard error. Shared by test_frontend_cli,
// test_frontend_view and test_frontend_gl_compute.
#pragma once

#include <doctest/doctest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace blurcull::frontend::test {

struct CliRun {
    int status = -1;
    std::string out;
    std::string err;
};

// `cd folder && prefix BLURCULL_CLI arguments`, standard error to
// folder/stderr.txt; `prefix` sets the environment or wraps the command.
inline CliRun run_cli_in(const std::filesystem::path& folder, const std::string& arguments,
                         const std::string& prefix = "") {
    std::filesystem::create_directories(folder);
    const std::filesystem::path err_file = folder / "stderr.txt";
    const std::string command = "cd '" + folder.string() + "' && " + prefix + " '" + BLURCULL_CLI + "' " +
                                arguments + " 2>'" + err_file.string() + "'";
    CliRun run;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::array<char, 4096> buffer{};
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) run.out.append(buffer.data(), n);
    const int raw = pclose(pipe);
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    if (FILE* f = std::fopen(err_file.string().c_str(), "r")) {
        while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), f)) run.err.append(buffer.data(), n);
        std::fclose(f);
    }
    return run;
}

}  // namespace blurcull::frontend::test
