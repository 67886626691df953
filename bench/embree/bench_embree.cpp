// Rays per second of the Embree reference by tracing shape, scene flag and
// build quality (docs/benchmarks.md, "The Embree baseline"). Each
// configuration renders the same scene and settings; its image is compared
// with the first configuration's (one ray per call, ROBUST), so a speed-up
// that changes a pixel shows as "differs".
//
//   bench_embree [--scene forest] [--size 1024x768] [--spp 16] [--threads 1]
//                [--repeat 3] [--blur 0,1]
#include "render/embree/embree_backend.hpp"
#include "scene/builtin_scenes.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace blurcull::frontend;

namespace {

struct Config {
    EmbreeOptions options;
    std::string label() const {
        return std::string(tracing_name(options.tracing)) + (options.robust ? " robust" : " fast") + " " +
               build_quality_name(options.build_quality);
    }
};

std::vector<Config> configs() {
    std::vector<Config> all;
    // The reference first: every other image is compared with it.
    for (bool robust : {true, false}) {
        for (EmbreeTracing tracing : {EmbreeTracing::single, EmbreeTracing::packet4, EmbreeTracing::packet8,
                                      EmbreeTracing::packet16, EmbreeTracing::stream}) {
            Config c;
            c.options.tracing = tracing;
            c.options.robust = robust;
            all.push_back(c);
        }
    }
    for (EmbreeBuildQuality quality : {EmbreeBuildQuality::low, EmbreeBuildQuality::high}) {
        Config c;
        c.options.build_quality = quality;
        all.push_back(c);
    }
    return all;
}

double phase_ms(const RenderStats& stats, const std::string& name) {
    for (const auto& phase : stats.ms_per_phase)
        if (phase.first == name) return phase.second;
    return 0.0;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::vector<float> split_floats(const std::string& text) {
    std::vector<float> out;
    std::stringstream stream(text);
    for (std::string item; std::getline(stream, item, ',');) out.push_back(std::stof(item));
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene_name = "forest";
    int width = 1024, height = 768, spp = 16, threads = 1, repeat = 3;
    std::vector<float> blurs = {0.0f, 1.0f};
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::invalid_argument(arg + ": missing value");
                return argv[++i];
            };
            if (arg == "--scene") scene_name = value();
            else if (arg == "--size") {
                const std::string v = value();
                if (std::sscanf(v.c_str(), "%dx%d", &width, &height) != 2) throw std::invalid_argument("--size WxH");
            } else if (arg == "--spp") spp = std::atoi(value().c_str());
            else if (arg == "--threads") threads = std::max(1, std::atoi(value().c_str()));
            else if (arg == "--repeat") repeat = std::max(1, std::atoi(value().c_str()));
            else if (arg == "--blur") blurs = split_floats(value());
            else throw std::invalid_argument("unknown option '" + arg + "'");
        }
        std::printf("scene %s %dx%d %d spp, %d thread(s), median of %d\n", scene_name.c_str(), width, height, spp,
                    threads, repeat);
        std::printf("%-5s %-24s %10s %10s %14s %8s %s\n", "blur", "tracing flags quality", "build ms", "trace ms",
                    "Mrays/s/core", "x single", "image");
        for (float blur : blurs) {
            SceneOptions scene_options;
            scene_options.blur_scale = blur;
            scene_options.aspect = float(width) / float(height);
            const Scene scene = make_builtin_scene(scene_name, scene_options);
            RenderSettings settings;
            settings.width = width;
            settings.height = height;
            settings.spp = spp;
            settings.threads = threads;
            settings.progress = false;
            const std::vector<Config> all = configs();
            std::vector<std::vector<double>> trace(all.size()), build(all.size());
            std::vector<std::string> same(all.size(), "same");
            Image reference;
            // Configurations interleaved across repeats, so drifting load hits all alike.
            for (int r = 0; r < repeat; ++r) {
                for (std::size_t c = 0; c < all.size(); ++c) {
                    const RenderResult result = render_embree(scene, settings, all[c].options);
                    trace[c].push_back(phase_ms(result.stats, "trace"));
                    build[c].push_back(phase_ms(result.stats, "build BVH"));
                    if (r == 0 && c == 0) reference = result.image;
                    if (result.image.pixels != reference.pixels) same[c] = "differs";
                }
            }
            const double rays = double(width) * height * spp;
            const double single_ms = median(trace[0]);
            for (std::size_t c = 0; c < all.size(); ++c) {
                const double ms = median(trace[c]);
                std::printf("%-5g %-24s %10.1f %10.1f %14.2f %8.2f %s\n", double(blur), all[c].label().c_str(),
                            median(build[c]), ms, rays / (ms * 1e-3) / threads * 1e-6, single_ms / ms,
                            same[c].c_str());
            }
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_embree: %s\n", error.what());
        return 1;
    }
    return 0;
}
