// `blurcull view` as CI runs it: on a virtual X server (Xvfb), a few frames
// with --frames and the window's contents with --screenshot; and its one-line
// refusal when there is no display. BLURCULL_CLI is the path of the built
// executable. Without Xvfb the window tests are skipped, unless CI=true (then
// they fail).
#include "cli_runner.hpp"
#include "frontend_test_helpers.hpp"
#include "render/common/image.hpp"

#include <doctest/doctest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

using blurcull::frontend::Image;
using blurcull::frontend::test::is_ci;

namespace {

namespace fs = std::filesystem;

using Run = blurcull::frontend::test::CliRun;

// One folder per run (runs of this test from other builds may share the
// machine), removed when the test exits.
struct ScratchFolder {
    fs::path path = fs::temp_directory_path() / ("blurcull_view_test_" + std::to_string(getpid()));
    ScratchFolder() { fs::create_directories(path); }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    ~ScratchFolder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

const fs::path& scratch() {
    static const ScratchFolder folder;
    return folder.path;
}

// Runs `prefix BLURCULL_CLI arguments` in the scratch folder.
Run run_cli(const std::string& arguments, const std::string& prefix = "") {
    return blurcull::frontend::test::run_cli_in(scratch(), arguments, prefix);
}

// One Xvfb for the whole test process, started on first use and stopped at
// exit; each window test runs the command with its DISPLAY. Not xvfb-run per
// command: its clean-up races the SIGUSR1 that Xvfb sends its parent on every
// server reset (a client leaving), and under load it then exits 5 with a line
// of its own after the command's (seen twice in CI). Started without
// SIGUSR1 ignored, Xvfb sends none; -displayfd picks a free display and says
// which once it accepts connections.
class VirtualDisplay {
public:
    VirtualDisplay() {
        int ready[2];
        if (pipe(ready) != 0) return;
        pid_ = fork();
        if (pid_ == 0) {
            close(ready[0]);
            const int null_fd = open("/dev/null", O_RDWR);
            dup2(null_fd, STDIN_FILENO);
            dup2(null_fd, STDOUT_FILENO);
            dup2(null_fd, STDERR_FILENO);
            const std::string fd = std::to_string(ready[1]);
            execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-nolisten", "tcp", "-screen", "0", "1280x1024x24",
                   static_cast<char*>(nullptr));
            _exit(127);
        }
        close(ready[1]);
        std::string number;
        char c = 0;
        while (pid_ > 0 && read(ready[0], &c, 1) == 1 && c != '\n') number += c;
        close(ready[0]);
        if (!number.empty()) display_ = ":" + number;
    }
    VirtualDisplay(const VirtualDisplay&) = delete;
    VirtualDisplay& operator=(const VirtualDisplay&) = delete;
    ~VirtualDisplay() {
        if (pid_ <= 0) return;
        kill(pid_, SIGTERM);
        waitpid(pid_, nullptr, 0);
    }
    // ":N", or empty when Xvfb is missing or did not start.
    const std::string& display() const { return display_; }

private:
    pid_t pid_ = -1;
    std::string display_;
};

const VirtualDisplay& virtual_display() {
    static const VirtualDisplay display;
    return display;
}

bool xvfb_or_skip() {
    if (!virtual_display().display().empty()) return true;
    if (is_ci()) FAIL("Xvfb did not start in CI (install xvfb: scripts/install-deps.sh)");
    MESSAGE("SKIPPED: Xvfb is missing or did not start (install xvfb); CI=true makes this a failure");
    return false;
}

// The prefix that runs a command on the virtual display (xvfb_or_skip first).
std::string on_display() { return "env -u WAYLAND_DISPLAY DISPLAY=" + virtual_display().display(); }

std::size_t count_lines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

float max_channel(glm::vec3 v) { return std::max({v.x, v.y, v.z}); }

// The overlay's text colour, linear (1, 0.95, 0.6), as it reads back from an 8-bit sRGB PNG.
bool is_text_colour(glm::vec3 c) {
    return c.r > 0.97f && c.g > 0.90f && c.g < 0.99f && c.b > 0.55f && c.b < 0.65f;
}

// Top-left overlay panel (scale 1 at this size): four lines of text; below it only the scene.
constexpr int panel_bottom = 70;
// dof-secondary's panel has a fifth line (rays, clusters, bounce time).
constexpr int panel_bottom_bounce = 84;
const std::string data_dir = std::string(BLURCULL_SOURCE_DIR) + "/tests/data/gltf";
const std::string view_args = "view --scene hand --size 160x120 --spp 4 --cull clip2 -q";
// Under the sanitizer build llvmpipe leaves 112 bytes from its unloaded
// driver after a headless draw (Mesa's, not ours; .ci/run), which
// LeakSanitizer would turn into a failing exit status.
const std::string no_leak_check = "ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:detect_leaks=0\"";

// The largest channel difference of two images of one size in rows [first_row, height).
float worst_difference_below(const Image& a, const Image& b, int first_row) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    float worst = 0.0f;
    for (int y = first_row; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) worst = std::max(worst, max_channel(glm::abs(a.at(x, y) - b.at(x, y))));
    }
    return worst;
}

// The first line of `text` that is not empty.
std::string first_line(const std::string& text) {
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        if (!line.empty()) return line;
    }
    return "";
}

}  // namespace

TEST_CASE("blurcull view renders frames under Xvfb and writes the window's contents") {
    if (!xvfb_or_skip()) return;
    const fs::path shot = scratch() / "view_three.png";
    fs::remove(shot);
    // One animated triangle: milliseconds a frame on llvmpipe, where the hand takes seconds.
    Run run = run_cli("view --backend gl --scene '" + data_dir +
                          "/triangle_animated.gltf' --size 160x120 --frames 3 --screenshot '" +
                          shot.string() + "'",
                      on_display());
    INFO("stdout: " << run.out << "\nstderr: " << run.err);
    REQUIRE(run.status == 0);
    // One line per frame, the cull method cycling so both the per-triangle and
    // the per-cell bounds ran, each with an STE in (0, 1].
    REQUIRE(count_lines(run.out) == 3);
    std::istringstream lines(run.out);
    std::string line;
    const char* expected[] = {"cull bbox", "cull hull", "cull dualspace"};
    for (const char* method : expected) {
        std::getline(lines, line);
        CHECK(line.find(method) != std::string::npos);
        const std::size_t at = line.find("STE ");
        REQUIRE(at != std::string::npos);
        const double ste = std::stod(line.substr(at + 4));
        CHECK(ste > 0.0);
        CHECK(ste <= 1.0);
        // Software GL timings are labelled as such.
        const bool llvmpipe = line.find("llvmpipe") != std::string::npos;
        CHECK(llvmpipe == (line.find("software") != std::string::npos));
    }
    REQUIRE(fs::exists(shot));
    const Image image = blurcull::frontend::read_png(shot.string());
    REQUIRE(image.width == 160);
    REQUIRE(image.height == 120);
    std::size_t text_pixels = 0;
    for (int y = 0; y < panel_bottom; ++y) {
        for (int x = 0; x < image.width; ++x) text_pixels += is_text_colour(image.at(x, y)) ? 1 : 0;
    }
    CHECK(text_pixels > 200);  // the overlay's four lines of text
    // The scene below the panel: not one colour (the triangle over the background).
    glm::vec3 low(1.0f), high(0.0f);
    for (int y = panel_bottom; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            low = glm::min(low, image.at(x, y));
            high = glm::max(high, image.at(x, y));
        }
    }
    CHECK(max_channel(high - low) > 0.2f);
}

TEST_CASE("blurcull view shows the GL backend's image: one frame matches blurcull render --backend gl") {
    if (!xvfb_or_skip()) return;
    const fs::path shot = scratch() / "view_one.png";
    const fs::path rendered = scratch() / "render_gl.png";
    Run view = run_cli(view_args + " --backend gl --frames 1 --screenshot '" + shot.string() + "'", on_display());
    INFO("view stderr: " << view.err);
    REQUIRE(view.status == 0);
    // Under the sanitizer build llvmpipe leaves 112 bytes from its unloaded
    // driver after a headless draw (Mesa's, not ours; .ci/run), which
    // LeakSanitizer would turn into a failing exit status.
    Run render = run_cli("render --backend gl --scene hand --size 160x120 --spp 4 --cull clip2 -q -o '" +
                             rendered.string() + "'",
                         "ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:detect_leaks=0\"");
    if (render.status != 0) {
        if (is_ci()) FAIL("render --backend gl failed in CI: " << render.err);
        MESSAGE("SKIPPED the comparison: no headless GL context for render --backend gl (" << render.err << ")");
        return;
    }
    const Image window = blurcull::frontend::read_png(shot.string());
    const Image image = blurcull::frontend::read_png(rendered.string());
    REQUIRE(window.width == image.width);
    REQUIRE(window.height == image.height);
    // Same pipeline, samples and seed: the window (not flipped, not scaled)
    // holds the same pixels wherever the overlay does not cover them.
    float worst = 0.0f;
    for (int y = panel_bottom; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) worst = std::max(worst, max_channel(glm::abs(window.at(x, y) - image.at(x, y))));
    }
    CHECK(worst < 0.01f);
}

namespace {

// One line of `view --backend cpu --frames N`: "frame F pass P: cull C, S/T spp[ (preview 1/K)], STE ...".
struct PassLine {
    int frame = 0, pass = 0, samples = 0, target = 0;
    bool preview = false;
    std::string line;
};

std::vector<PassLine> pass_lines(const std::string& out) {
    std::vector<PassLine> lines;
    std::istringstream in(out);
    std::string line;
    while (std::getline(in, line)) {
        PassLine pass;
        pass.line = line;
        REQUIRE_MESSAGE(std::sscanf(line.c_str(), "frame %d pass %d", &pass.frame, &pass.pass) == 2, line);
        const std::size_t spp = line.find(" spp");
        REQUIRE_MESSAGE(spp != std::string::npos, line);
        const std::size_t start = line.rfind(' ', spp - 1) + 1;
        REQUIRE_MESSAGE(std::sscanf(line.c_str() + start, "%d/%d", &pass.samples, &pass.target) == 2, line);
        pass.preview = line.find("(preview 1/") != std::string::npos;
        lines.push_back(pass);
    }
    return lines;
}

// The largest channel difference below the overlay's panel.
float worst_below_panel(const Image& a, const Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    float worst = 0.0f;
    for (int y = panel_bottom; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) worst = std::max(worst, max_channel(glm::abs(a.at(x, y) - b.at(x, y))));
    }
    return worst;
}

}  // namespace

TEST_CASE("blurcull view --backend cpu refines progressively to the image of blurcull render --backend cpu") {
    if (!xvfb_or_skip()) return;
    const fs::path shot = scratch() / "view_cpu.png";
    const fs::path rendered = scratch() / "render_cpu.png";
    fs::remove(shot);
    // Two views: the second after a turn of the orbit and the next cull
    // method, so the accumulation restarts from 1 spp.
    Run view = run_cli("view --backend cpu --scene hand --size 160x120 --spp 8 --cull bbox --frames 2 --screenshot '" +
                           shot.string() + "'",
                       on_display());
    INFO("view stdout: " << view.out << "\nstderr: " << view.err);
    REQUIRE(view.status == 0);
    const std::vector<PassLine> lines = pass_lines(view.out);
    REQUIRE(!lines.empty());
    for (int frame : {1, 2}) {
        std::vector<PassLine> passes;
        for (const PassLine& line : lines) {
            if (line.frame == frame) passes.push_back(line);
        }
        REQUIRE(passes.size() >= 2);
        // First a 1-spp image (a scaled preview, or the accumulation's first pass).
        CHECK(passes.front().pass == 1);
        CHECK(passes.front().samples == 1);
        int previous = 0;
        for (const PassLine& pass : passes) {
            INFO(pass.line);
            CHECK(pass.target == 8);
            CHECK(pass.line.find("cpu backend") != std::string::npos);
            CHECK(pass.line.find(frame == 1 ? "cull bbox," : "cull hull,") != std::string::npos);
            if (pass.preview) continue;
            // The accumulation only grows: never a restart within a view.
            CHECK(pass.samples > previous);
            previous = pass.samples;
        }
        CHECK(passes.back().samples == 8);
        CHECK(!passes.back().preview);
    }
    // The window after the second view's last pass: turned, so unlike the
    // render of the first view's camera (the next test compares a converged
    // view with its render).
    Run render = run_cli("render --backend cpu --scene hand --size 160x120 --spp 8 --cull hull -q -o '" +
                         rendered.string() + "'");
    REQUIRE(render.status == 0);
    const Image window = blurcull::frontend::read_png(shot.string());
    const Image first_view = blurcull::frontend::read_png(rendered.string());
    CHECK(worst_below_panel(window, first_view) > 0.1f);
}

TEST_CASE("blurcull view --backend cpu, one view converged: the window equals blurcull render --backend cpu") {
    if (!xvfb_or_skip()) return;
    const fs::path shot = scratch() / "view_cpu_one.png";
    const fs::path rendered = scratch() / "render_cpu_one.png";
    fs::remove(shot);
    Run view = run_cli("view --backend cpu --scene hand --size 160x120 --spp 16 --cull clip2 -q --frames 1 "
                       "--screenshot '" + shot.string() + "'",
                       on_display());
    INFO("view stderr: " << view.err);
    REQUIRE(view.status == 0);
    Run render = run_cli("render --backend cpu --scene hand --size 160x120 --spp 16 --cull clip2 -q -o '" +
                         rendered.string() + "'");
    REQUIRE(render.status == 0);
    // The same samples summed in the same order: the same floats, so the same
    // 8-bit values (the window's texture and readback encode as the PNG
    // writer does). Tolerance 0.
    CHECK(worst_below_panel(blurcull::frontend::read_png(shot.string()),
                            blurcull::frontend::read_png(rendered.string())) == 0.0f);
}

TEST_CASE("blurcull view --backend auto draws with the cpu backend when the window's OpenGL is software") {
    if (!xvfb_or_skip()) return;
    Run view = run_cli("view --scene hand --size 64x48 --spp 2 --frames 1", on_display());
    INFO("view stdout: " << view.out << "\nstderr: " << view.err);
    REQUIRE(view.status == 0);
    // The start-up line names what draws: "on cpu backend; GL llvmpipe, software" or the GL renderer.
    const bool software = view.err.find("llvmpipe") != std::string::npos ||
                          view.err.find("softpipe") != std::string::npos ||
                          view.err.find("swrast") != std::string::npos;
    CHECK(software == (view.err.find("on cpu backend") != std::string::npos));
    if (software) CHECK(view.out.find("2/2 spp") != std::string::npos);
}

TEST_CASE("blurcull view refuses bad input with one line") {
    SUBCASE("no display") {
        Run run = run_cli(view_args + " --frames 1", "env -u DISPLAY -u WAYLAND_DISPLAY");
        CHECK(run.status == 1);
        CHECK(count_lines(run.err) == 1);
        CHECK(run.err.find("no display: set DISPLAY or run under xvfb-run") != std::string::npos);
    }
    SUBCASE("a display that cannot be opened") {
        Run run = run_cli(view_args + " --frames 1", "env -u WAYLAND_DISPLAY DISPLAY=:4321");
        CHECK(run.status == 1);
        CHECK(count_lines(run.err) == 1);
        CHECK(run.err.find("cannot open the display ':4321'") != std::string::npos);
    }
    SUBCASE("negative frame count") {
        Run run = run_cli(view_args + " --frames -1");
        CHECK(run.status == 2);
        CHECK(count_lines(run.err) == 1);
        CHECK(run.err.find("--frames") != std::string::npos);
        CHECK(run.err.find("blurcull view --help") != std::string::npos);
    }
    SUBCASE("bad size") {
        Run run = run_cli("view --size 0x10 --frames 1");
        CHECK(run.status == 1);
        CHECK(count_lines(run.err) == 1);
        CHECK(run.err.find("--size") != std::string::npos);
    }
    SUBCASE("dof-secondary on the cpu backend") {
        Run run = run_cli(view_args + " --backend cpu --method dof-secondary --frames 1");
        CHECK(run.status == 1);
        CHECK(count_lines(run.err) == 1);
        CHECK(run.err.find("--backend cpu: the view draws --method stochastic only") != std::string::npos);
    }
    SUBCASE("screenshot folder not writable") {
        Run run = run_cli(view_args + " --frames 1 --screenshot /nonexistent/folder/shot.png");
        CHECK(run.status == 1);
        CHECK(count_lines(run.err) == 1);
        CHECK(run.err.find("--screenshot") != std::string::npos);
    }
}

// dof-secondary in the window: the same GL passes as `render --backend gl
// --method dof-secondary` (GlDofSecondary), on the window's context.
TEST_CASE("blurcull view --method dof-secondary shows the image of blurcull render --method dof-secondary") {
    if (!xvfb_or_skip()) return;
    // 240x180: the lower half of the sphere lies below the panel.
    const std::string settings = "--scene mirror-sphere --size 240x180 --spp 4 --cull clip2 -q";
    const fs::path shot = scratch() / "view_dof_secondary.png";
    const fs::path rendered = scratch() / "render_dof_secondary.png";
    const fs::path direct = scratch() / "render_mirror_sphere_stochastic.png";
    fs::remove(shot);
    Run view = run_cli("view --method dof-secondary " + settings + " --frames 1 --screenshot '" + shot.string() + "'",
                       on_display());
    INFO("view stderr: " << view.err);
    REQUIRE(view.status == 0);
    Run render = run_cli("render --method dof-secondary --backend gl " + settings + " -o '" + rendered.string() + "'",
                         no_leak_check);
    // The directly seen image, to show the comparison can fail (cpu: the same
    // samples as gl, in a fraction of llvmpipe's time).
    Run stochastic = run_cli("render --backend cpu " + settings + " -o '" + direct.string() + "'");
    REQUIRE(stochastic.status == 0);
    if (render.status != 0) {
        if (is_ci()) FAIL("render --backend gl failed in CI: " << render.err);
        MESSAGE("SKIPPED the comparison: no headless GL context for render --backend gl (" << render.err << ")");
        return;
    }
    const Image window = blurcull::frontend::read_png(shot.string());
    const Image image = blurcull::frontend::read_png(rendered.string());
    const Image direct_image = blurcull::frontend::read_png(direct.string());
    // Same primary samples (GL rasterizer, seed, camera), same clusters,
    // layers and trace pass: the same pixels below the panel, up to the
    // 8-bit sRGB rounding of both PNGs (the window's read back through its
    // RGBA8 texture). Measured: identical.
    CHECK(worst_difference_below(window, image, panel_bottom_bounce) < 0.01f);
    // And not the directly seen image: in the sphere the bounce shows the
    // scene around it (measured: largest difference 0.82).
    CHECK(worst_difference_below(window, direct_image, panel_bottom_bounce) > 0.2f);
}

TEST_CASE("blurcull view --method dof-secondary takes bad input as render does") {
    SUBCASE("a scene without mirrors: the stochastic rasterizer's image") {
        if (!xvfb_or_skip()) return;
        const std::string settings = "--scene '" + data_dir + "/triangle_animated.gltf' --size 160x120 --spp 4 -q";
        const fs::path shot = scratch() / "view_dof_no_mirror.png";
        const fs::path rendered = scratch() / "render_no_mirror.png";
        Run view = run_cli("view --method dof-secondary " + settings + " --frames 1 --screenshot '" + shot.string() +
                               "'",
                           on_display());
        INFO("view stderr: " << view.err);
        REQUIRE(view.status == 0);
        Run render = run_cli("render --backend gl " + settings + " -o '" + rendered.string() + "'", no_leak_check);
        if (render.status != 0) {
            if (is_ci()) FAIL("render --backend gl failed in CI: " << render.err);
            MESSAGE("SKIPPED the comparison: no headless GL context (" << render.err << ")");
            return;
        }
        const Image window = blurcull::frontend::read_png(shot.string());
        const Image image = blurcull::frontend::read_png(rendered.string());
        CHECK(worst_difference_below(window, image, panel_bottom_bounce) < 0.01f);
    }
    SUBCASE("motion segments: refused in render's one line") {
        if (!xvfb_or_skip()) return;
        const std::string settings = "--scene '" + data_dir + "/triangle_animated.gltf' --size 160x120 --spp 4 "
                                     "--motion-segments 2 -q";
        Run view = run_cli("view --method dof-secondary " + settings + " --frames 1", on_display());
        Run render = run_cli("render --method dof-secondary --backend cpu " + settings + " -o refused.png");
        CHECK(view.status == 1);
        CHECK(render.status == 1);
        CHECK(count_lines(view.err) == 1);
        CHECK(view.err.find("motion segments (K > 1) are not supported") != std::string::npos);
        CHECK(first_line(view.err) == first_line(render.err));
        // And the stochastic method on gl refuses it as render --backend gl
        // does (the cpu backend's view draws motion segments).
        Run view_stochastic = run_cli("view --backend gl " + settings + " --frames 1", on_display());
        Run render_gl = run_cli("render --backend gl " + settings + " -o refused.png", no_leak_check);
        CHECK(view_stochastic.status == 1);
        CHECK(count_lines(view_stochastic.err) == 1);
        CHECK(view_stochastic.err.find("gl: 2 motion segments are not supported here") != std::string::npos);
        if (render_gl.status == 1) CHECK(first_line(view_stochastic.err) == first_line(render_gl.err));
    }
    SUBCASE("--secondary-* flags without --method dof-secondary") {
        Run run = run_cli(view_args + " --secondary-layers 4 --frames 1");
        CHECK(run.status == 1);
        CHECK(count_lines(run.err) == 1);
        CHECK(run.err.find("--secondary-layers: only --method dof-secondary takes it (method stochastic)") !=
              std::string::npos);
    }
    SUBCASE("a method the view does not show") {
        Run run = run_cli(view_args + " --method interleave --frames 1");
        CHECK(run.status == 2);
        CHECK(count_lines(run.err) == 1);
        CHECK(run.err.find("--method") != std::string::npos);
    }
}
