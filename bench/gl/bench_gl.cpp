// GL backend frame times on llvmpipe (or whatever context EGL/OSMesa gives):
//
//   bench_gl static  [--scene forest] [--size 96x72] [--spp 16] [--cull clip2] [--frames 3]
//       the scene made 90% static (make_mostly_static(scene, 10)), rendered
//       with the static path and with the full path forced on every triangle
//       (GlOptions::force_full_path), alternating, after one warm-up frame
//       each; medians of whole render() calls (setup + passes + readback) and
//       their ratio; then one frame of each with GlOptions::time_steps for
//       where the time goes.
//   bench_gl methods [--scenes hand,car,dragonfly,forest] [--size 64x48] [--spp 16] [--frames 3]
//       each built-in scene with every culling method, after one warm-up
//       frame per scene, methods interleaved frame by frame; medians of the
//       raster+resolve phase, as ratios to bbox within the run.
//
// Only ratios within one run mean something on a shared machine; software
// GL (llvmpipe) timings are not GPU timings.
#include "bench_common.hpp"
#include "render/common/render_types.hpp"
#include "render/gl/gl_backend.hpp"
#include "scene/builtin_scenes.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using blurcull::bench::median;

namespace {

struct Arguments {
    std::string mode;
    std::string scene = "forest";
    std::vector<std::string> scenes = builtin_scene_names();
    std::string cull = "clip2";
    int width = 0, height = 0;
    int spp = 16;
    int frames = 3;
};

Arguments parse(int argc, char** argv) {
    if (argc < 2) throw std::runtime_error("usage: bench_gl static|methods [options]");
    Arguments a;
    a.mode = argv[1];
    if (a.mode != "static" && a.mode != "methods") throw std::runtime_error("mode '" + a.mode + "': static or methods");
    a.width = a.mode == "static" ? 96 : 64;
    a.height = a.mode == "static" ? 72 : 48;
    for (int i = 2; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc) throw std::runtime_error(flag + ": needs a value");
        const std::string value = argv[++i];
        if (flag == "--scene") {
            a.scene = value;
        } else if (flag == "--scenes") {
            a.scenes = blurcull::bench::split(value);
        } else if (flag == "--cull") {
            a.cull = value;
        } else if (flag == "--size") {
            if (std::sscanf(value.c_str(), "%dx%d", &a.width, &a.height) != 2 || a.width < 1 || a.height < 1)
                throw std::runtime_error("--size: WxH, e.g. 96x72");
        } else if (flag == "--spp") {
            a.spp = std::atoi(value.c_str());
        } else if (flag == "--frames") {
            a.frames = std::atoi(value.c_str());
            if (a.frames < 1) throw std::runtime_error("--frames: at least 1");
        } else {
            throw std::runtime_error("unknown option " + flag);
        }
    }
    return a;
}

RenderSettings settings_for(const Arguments& a, const std::string& cull) {
    RenderSettings settings;
    settings.width = a.width;
    settings.height = a.height;
    settings.spp = a.spp;
    settings.seed = 3;
    settings.cull = parse_cull_method(cull);
    settings.progress = false;
    return settings;
}

double wall_ms(GlRenderer& gl, const Scene& scene, const RenderSettings& settings, const GlOptions& options,
               RenderResult* result = nullptr) {
    const auto start = std::chrono::steady_clock::now();
    RenderResult r = gl.render(scene, settings, options);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (result != nullptr) *result = std::move(r);
    return ms;
}

double phase_ms(const RenderResult& result, const std::string& name) {
    for (const auto& [phase, ms] : result.stats.ms_per_phase)
        if (phase == name) return ms;
    return 0.0;
}

void run_static(GlRenderer& gl, const Arguments& a) {
    SceneOptions options;
    options.aspect = static_cast<float>(a.width) / static_cast<float>(a.height);
    const Scene scene = make_mostly_static(make_builtin_scene(a.scene, options), 10);
    const RenderSettings settings = settings_for(a, a.cull);
    GlOptions fast, full;
    full.force_full_path = true;
    wall_ms(gl, scene, settings, fast);
    wall_ms(gl, scene, settings, full);
    std::vector<double> fast_ms, full_ms;
    RenderResult fast_result, full_result;
    for (int f = 0; f < a.frames; ++f) {
        fast_ms.push_back(wall_ms(gl, scene, settings, fast, &fast_result));
        full_ms.push_back(wall_ms(gl, scene, settings, full, &full_result));
        std::printf("frame %d: static path %.0f ms, full path %.0f ms\n", f, fast_ms.back(), full_ms.back());
        std::fflush(stdout);
    }
    const double fast_median = median(fast_ms), full_median = median(full_ms);
    std::printf("%s made 90%% static, %dx%d, %d spp, %s, %s: static path %.0f ms, full path forced %.0f ms "
                "(medians of %d), speed-up %.2fx; hits %llu / %llu\n",
                a.scene.c_str(), a.width, a.height, a.spp, a.cull.c_str(), gl.description().c_str(), fast_median,
                full_median, a.frames, full_median / fast_median,
                static_cast<unsigned long long>(fast_result.stats.samples_hit),
                static_cast<unsigned long long>(full_result.stats.samples_hit));
    for (GlOptions* o : {&fast, &full}) {
        o->time_steps = true;
        RenderResult r;
        wall_ms(gl, scene, settings, *o, &r);
        std::printf("  %s, steps (glFinish after each):", o->force_full_path ? "full path  " : "static path");
        for (const auto& [phase, ms] : r.stats.ms_per_phase) std::printf(" %s %.0f", phase.c_str(), ms);
        std::printf(" ms\n");
    }
}

void run_methods(GlRenderer& gl, const Arguments& a) {
    const std::vector<std::string> culls = {"bbox", "hull", "dualspace", "clip2"};
    std::printf("| scene | bbox | hull | dualspace | clip2 | STE bbox / clip2 |\n|---|---|---|---|---|---|\n");
    for (const std::string& name : a.scenes) {
        SceneOptions options;
        options.aspect = static_cast<float>(a.width) / static_cast<float>(a.height);
        const Scene scene = make_builtin_scene(name, options);
        wall_ms(gl, scene, settings_for(a, "bbox"), GlOptions{});
        std::vector<std::vector<double>> ms(culls.size());
        std::vector<double> ste(culls.size());
        for (int f = 0; f < a.frames; ++f) {
            for (std::size_t m = 0; m < culls.size(); ++m) {
                RenderResult r;
                wall_ms(gl, scene, settings_for(a, culls[m]), GlOptions{}, &r);
                ms[m].push_back(phase_ms(r, "raster+resolve"));
                ste[m] = r.stats.ste();
            }
        }
        const double bbox = median(ms[0]);
        std::printf("| %s | %.2f s (1.00) | %.2f | %.2f | %.2f | %.1f%% / %.1f%% |\n", name.c_str(), bbox / 1000.0,
                    median(ms[1]) / bbox, median(ms[2]) / bbox, median(ms[3]) / bbox, 100.0 * ste[0], 100.0 * ste[3]);
        std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Arguments a = parse(argc, argv);
        GlRenderer gl;
        if (a.mode == "static") {
            run_static(gl, a);
        } else {
            run_methods(gl, a);
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_gl: %s\n", e.what());
        return 1;
    }
}
