// The main of every test executable: doctest's run, then the cleanups of
// test_cleanup.hpp, before static destruction.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "test_cleanup.hpp"

#include <utility>
#include <vector>

namespace blurcull::frontend::test {
namespace {

std::vector<std::function<void()>>& cleanups() {
    static std::vector<std::function<void()>> registered;
    return registered;
}

}  // namespace

void at_end_of_main(std::function<void()> cleanup) { cleanups().push_back(std::move(cleanup)); }

void run_end_of_main_cleanups() {
    std::vector<std::function<void()>> pending;
    pending.swap(cleanups());
    for (auto it = pending.rbegin(); it != pending.rend(); ++it) (*it)();
}

}  // namespace blurcull::frontend::test

int main(int argc, char** argv) {
    doctest::Context context(argc, argv);
    const int result = context.run();
    blurcull::frontend::test::run_end_of_main_cleanups();
    return result;
}
