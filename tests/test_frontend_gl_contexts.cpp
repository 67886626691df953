// Headless GL contexts in one process (frontend/render/gl/gl_context.hpp):
// several alive at once with interleaved lifetimes, each used (a compute
// dispatch read back) and destroyed in any order, on the process's one EGL
// display; a render makes exactly one context (the `blurcull render`
// command's probe is the render's context); and a context left to the
// statics' destructors does not crash the exit. ctest checks that this
// executable exits 0: under NVIDIA's driver, GL objects destroyed after its
// exit handlers made four test executables die with SIGSEGV at exit (issue 22).
// No GL context: SKIPPED, or a failure when CI=true.
#include "gl_parity_helpers.hpp"

#include "render/gl/gl_backend.hpp"

#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gl = blurcull::gl;
using namespace blurcull::frontend;
using namespace blurcull::frontend::test;

namespace {

constexpr std::uint32_t slots = 256;

constexpr const char* fill_source = R"glsl(#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer Out { uint values[]; };
uniform uint key;
void main() { values[gl_GlobalInvocationID.x] = gl_GlobalInvocationID.x * 3u + key; }
)glsl";

// A context with its own compute program and buffer: use(key) fills the
// buffer with slot * 3 + key on the GPU and checks every slot read back.
struct Worker {
    gl::HeadlessContext context;
    gl::Program program;
    gl::Buffer buffer;

    explicit Worker(gl::HeadlessContext&& made)
        : context(std::move(made)),
          program(context.gl(), {gl::ShaderStage{GL_COMPUTE_SHADER, {fill_source}}}),
          buffer(context.gl(), GL_SHADER_STORAGE_BUFFER, slots * sizeof(std::uint32_t)) {}
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;
    // Its program and buffer are deleted on its own context.
    ~Worker() { context.make_current_for_release(); }

    // `make_current` false: on whatever context is current (it must be this one).
    void use(std::uint32_t key, bool make_current = true) const {
        if (make_current) context.make_current();
        const gl::Functions& f = context.gl();
        f.UseProgram(program.id());
        f.Uniform1ui(f.GetUniformLocation(program.id(), "key"), key);
        buffer.bind_base(0);
        f.DispatchCompute(slots / 64, 1, 1);
        f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<std::uint32_t> values(slots, 0xFFFFFFFFu);
        buffer.read(values.data(), values.size() * sizeof(std::uint32_t));
        gl::check_gl(f, "the fill dispatch");
        std::size_t wrong = 0;
        for (std::uint32_t i = 0; i < slots; ++i) wrong += values[i] != i * 3u + key ? 1 : 0;
        CHECK_MESSAGE(wrong == 0, "key " << key << ": " << wrong << " of " << slots << " slots wrong");
    }
};

gl::HeadlessContext make(std::optional<gl::ContextKind> kind) {
    return kind ? gl::HeadlessContext::create(*kind) : gl::HeadlessContext::create();
}

// A made, B made, A used, B used, a bare context made and destroyed while B
// is current (B stays current), A destroyed (the display stays for B), B
// used, C made and used, B used, C destroyed, B used, B destroyed; then,
// with every context gone, a new one made and used.
void interleaved_lifetimes(gl::HeadlessContext&& first, std::optional<gl::ContextKind> kind) {
    const std::size_t made_before = gl::HeadlessContext::contexts_made();
    auto a = std::make_unique<Worker>(std::move(first));
    a->use(1);
    auto b = std::make_unique<Worker>(make(kind));
    b->use(2);
    a->use(3);  // A's objects survive B's making
    b->use(4);
    {
        const gl::HeadlessContext bare = make(kind);  // current now
        b->context.make_current();
    }  // destroyed while B is current
    b->use(5, false);  // B is still current
    a.reset();
    b->use(6);  // the display survives A
    auto c = std::make_unique<Worker>(make(kind));
    c->use(7);
    b->use(8);
    c.reset();
    b->use(9);
    b.reset();
    Worker again(make(kind));  // the display initialised again after the last went
    again.use(10);
    CHECK(gl::HeadlessContext::contexts_made() - made_before == 4);  // b, bare, c, again
}

}  // namespace

TEST_CASE("headless contexts with interleaved lifetimes, each used and destroyed in any order") {
    std::optional<gl::HeadlessContext> first = context_or_skip();
    if (!first) return;
    MESSAGE("GL: " << std::string(gl::context_kind_name(first->kind())) << ", " << first->renderer());
    interleaved_lifetimes(std::move(*first), std::nullopt);
}

TEST_CASE("the same on OSMesa contexts, where OSMesa is installed") {
    std::optional<gl::HeadlessContext> first;
    try {
        first.emplace(gl::HeadlessContext::create(gl::ContextKind::osmesa));
    } catch (const gl::GlError& e) {
        MESSAGE("SKIPPED: no OSMesa context (" << std::string(e.what()) << ")");
        return;
    }
    interleaved_lifetimes(std::move(*first), gl::ContextKind::osmesa);
}

TEST_CASE("a render makes one context, and a renderer on a context made before makes none") {
    std::optional<gl::HeadlessContext> probe = context_or_skip();
    if (!probe) return;
    const Scene scene = small_scene("car", 24, 16);
    RenderSettings settings;
    settings.width = 24;
    settings.height = 16;
    settings.spp = 4;
    settings.progress = false;
    std::size_t before = gl::HeadlessContext::contexts_made();
    const RenderResult alone = render_gl(scene, settings);
    CHECK(gl::HeadlessContext::contexts_made() - before == 1);

    before = gl::HeadlessContext::contexts_made();
    GlRenderer renderer(std::move(*probe));
    const RenderResult first = render_gl_frame(renderer, scene, settings);
    const RenderResult second = render_gl_frame(renderer, scene, settings);
    CHECK(gl::HeadlessContext::contexts_made() == before);
    CHECK(first.image.pixels == alone.image.pixels);
    CHECK(second.image.pixels == alone.image.pixels);
    CHECK(first.stats.samples_hit == alone.stats.samples_hit);
    CHECK(first.stats.ms_per_phase.front().first == "compile");
}

namespace {

struct Run {
    int status = -1;
    std::string err;
};

// `blurcull <arguments>` in a scratch folder with BLURCULL_GL_TRACE_CONTEXTS=1.
Run run_cli(const std::string& arguments) {
    namespace fs = std::filesystem;
    const fs::path folder = fs::temp_directory_path() / ("blurcull_gl_contexts_test_" + std::to_string(::getpid()));
    fs::create_directories(folder);
    const fs::path err_file = folder / "stderr.txt";
    const std::string command = "cd '" + folder.string() + "' && BLURCULL_GL_TRACE_CONTEXTS=1 '" + BLURCULL_CLI +
                                "' " + arguments + " >/dev/null 2>'" + err_file.string() + "'";
    Run run;
    const int raw = std::system(command.c_str());
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    if (FILE* f = std::fopen(err_file.string().c_str(), "r")) {
        std::array<char, 4096> buffer{};
        while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), f)) run.err.append(buffer.data(), n);
        std::fclose(f);
    }
    fs::remove_all(folder);
    return run;
}

std::size_t count_of(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("blurcull render makes one GL context: the probe's, for every method and every frame") {
    if (!context_or_skip()) return;
    const std::string trace = "blurcull gl: context ";
    for (const char* arguments : {
             "render --backend gl --scene car --size 24x16 --spp 4 -o car.png",
             "render --backend gl --method interleave --scene car --size 24x16 --spp 4 -o interleave.png",
             "render --backend gl --scene car --size 24x16 --spp 4 --frames 0:2 -o car_%04d.png",
             "render --backend gl --method dof-secondary --scene mirror-sphere --size 24x16 --spp 4 -o mirror.png",
         }) {
        CAPTURE(arguments);
        const Run run = run_cli(arguments);
        CHECK_MESSAGE(run.status == 0, run.err);
        CHECK_MESSAGE(count_of(run.err, trace) == 1, run.err);
    }
    // auto: a context only where a GPU device could drive one, and then the
    // render's own (here, on llvmpipe, usually none).
    const Run run = run_cli("render --backend auto --scene car --size 24x16 --spp 4 -o auto.png");
    CHECK_MESSAGE(run.status == 0, run.err);
    const bool gl_chosen = run.err.find("--backend auto: using gl") != std::string::npos;
    CHECK_MESSAGE(count_of(run.err, trace) <= 1, run.err);
    if (gl_chosen) CHECK_MESSAGE(count_of(run.err, trace) == 1, run.err);
    MESSAGE("--backend auto made " << count_of(run.err, trace) << " context(s); chose " << std::string(gl_chosen ? "gl" : "cpu"));
}

namespace {
// Deliberately left to the statics' destructors (constructed before main,
// so destroyed after every exit handler the drivers register while they
// initialise): the library must then release nothing rather than call into
// a driver that may be shut down (gl_context.hpp). The other tests release
// what they share at the end of main (test_cleanup.hpp), as code should.
std::optional<Worker> left_to_the_statics;
}  // namespace

TEST_CASE("a context and its objects left to the statics' destructors do not crash the exit") {
    std::optional<gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    left_to_the_statics.emplace(std::move(*context));
    left_to_the_statics->use(11);
    CHECK(gl::driver_usable());  // until exit begins
}
