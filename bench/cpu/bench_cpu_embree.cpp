// The CPU rasterizer against the tuned Embree ray tracer on the built-in
// scenes (docs/benchmarks.md, "CPU backend against Embree"): per scene and
// blur scale, Embree (its defaults: packets of 16, ROBUST) and the CPU
// backend with every cull that takes it, interleaved across repeats so
// drifting load hits all alike. Prints the median wall time, the median
// process CPU time (user + system of all threads: what the render cost,
// nearly independent of other load on the machine), both as ratios to
// Embree's, samples visited / tested / hit per pixel, the CPU backend's
// phases, and whether the image equals the bbox render (every cull must give
// the same image) and its RMSE against Embree's.
//
// --size, --spp and --threads take lists too (every combination runs, the
// sweeps behind docs/benchmarks.md's plots of time against spp, resolution
// and threads); --csv FILE also writes every row, with the phases as
// columns, for bench/cpu/plot_cpu_embree.py.
//
//   bench_cpu_embree [--scenes hand,car,dragonfly,forest] [--size 1024x768[,WxH...]] [--spp 16[,N...]]
//                    [--blur 1,2] [--repeat 3] [--threads 0[,N...]] [--culls bbox,hull,dualspace,twostage]
//   (a cull may carry its CPU time strata: bbox:1 is bbox without its shutter strata;
//    and :noocc, occlusion culling off: bbox:4:noocc)
//                    [--csv FILE]
#include "render/cpu/cpu_backend.hpp"
#include "render/embree/embree_backend.hpp"
#include "scene/builtin_scenes.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace blurcull::frontend;

namespace {

double cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream stream(text);
    for (std::string item; std::getline(stream, item, ',');) out.push_back(item);
    return out;
}

// One renderer of a row: its label and how it renders.
struct Contender {
    std::string label;
    std::function<RenderResult(const Scene&, const RenderSettings&)> render;
    std::vector<double> wall_ms, cpu_s;
    RenderResult last;
};

std::string phases(const RenderStats& stats) {
    std::string out;
    for (const auto& [name, ms] : stats.ms_per_phase) {
        char part[64];
        std::snprintf(part, sizeof part, "%s%s %.0f", out.empty() ? "" : ", ", name.c_str(), ms);
        out += part;
    }
    return out;
}

// The CPU backend's phases as CSV columns (setup, binning, raster, resolve);
// Embree's are summed into "raster" apart from its BVH build ("setup").
std::string phase_columns(const RenderStats& stats, bool cpu) {
    double setup = 0.0, binning = 0.0, raster = 0.0, resolve = 0.0;
    for (const auto& [name, ms] : stats.ms_per_phase) {
        if (name == "setup" || name == "build BVH") setup += ms;
        else if (name == "binning") binning += ms;
        else if (name == "resolve" && cpu) resolve += ms;
        else raster += ms;
    }
    char out[128];
    std::snprintf(out, sizeof out, "%.1f,%.1f,%.1f,%.1f", setup, binning, raster, resolve);
    return out;
}

void run_scene(const std::string& name, float blur, const RenderSettings& base, int repeat,
               const std::vector<std::string>& culls, std::FILE* csv) {
    SceneOptions scene_options;
    scene_options.blur_scale = blur;
    scene_options.aspect = float(base.width) / float(base.height);
    const Scene scene = make_builtin_scene(name, scene_options);
    std::vector<Contender> all;
    all.push_back({"embree", [](const Scene& s, const RenderSettings& r) { return render_embree(s, r); }, {}, {}, {}});
    for (const std::string& cull : culls) {
        // "bbox:1": the cull with CpuOptions::time_strata 1 (without its
        // shutter strata); "bbox:4:noocc": with 4 and occlusion culling off.
        const std::size_t colon = cull.find(':');
        const CullMethod method = parse_cull_method(cull.substr(0, colon));
        CpuOptions options;
        if (colon != std::string::npos) options.time_strata = std::atoi(cull.c_str() + colon + 1);
        if (cull.find(":noocc") != std::string::npos) options.occlusion = false;
        all.push_back({"cpu " + cull,
                       [method, options](const Scene& s, RenderSettings r) {
                           r.cull = method;
                           return render_cpu(s, r, options);
                       },
                       {}, {}, {}});
    }
    // Each repeat starts one contender later: the one that runs right after
    // another's large frees pays for faulting in fresh memory (the allocator
    // returns big blocks to the system), so every contender takes each place.
    for (int r = 0; r < repeat; ++r) {
        for (std::size_t k = 0; k < all.size(); ++k) {
            Contender& c = all[(k + static_cast<std::size_t>(r)) % all.size()];
            const double cpu_before = cpu_seconds();
            c.last = c.render(scene, base);
            c.cpu_s.push_back(cpu_seconds() - cpu_before);
            c.wall_ms.push_back(c.last.stats.ms_total);
        }
    }
    const double pixels = double(base.width) * base.height;
    const double embree_wall = median(all[0].wall_ms), embree_cpu = median(all[0].cpu_s);
    for (const Contender& c : all) {
        const RenderStats& s = c.last.stats;
        const bool cpu = c.label != "embree";
        const std::string same = !cpu ? "-" : c.last.image.pixels == all[1].last.image.pixels ? "same" : "DIFFERS";
        std::printf("%-7s %4g %-14s %9.0f %7.2f %6.2f %6.2f %8.2f %8.2f %7.2f %-7s %9.2e  %s\n", name.c_str(),
                    double(blur), c.label.c_str(), median(c.wall_ms), median(c.cpu_s), median(c.wall_ms) / embree_wall,
                    median(c.cpu_s) / embree_cpu, cpu ? double(s.samples_visited) / pixels : 0.0,
                    double(s.samples_tested) / pixels, double(s.samples_hit) / pixels, same.c_str(),
                    rmse(c.last.image, all[0].last.image), phases(s).c_str());
        if (csv != nullptr)
            std::fprintf(csv, "%s,%g,%d,%d,%d,%d,%s,%.1f,%.3f,%.4f,%.4f,%.2f,%.2f,%.2f,%s,%s\n", name.c_str(),
                         double(blur), base.width, base.height, base.spp, base.threads, c.label.c_str(),
                         median(c.wall_ms), median(c.cpu_s), median(c.wall_ms) / embree_wall,
                         median(c.cpu_s) / embree_cpu, cpu ? double(s.samples_visited) / pixels : 0.0,
                         double(s.samples_tested) / pixels, double(s.samples_hit) / pixels, same.c_str(),
                         phase_columns(s, cpu).c_str());
    }
}

struct Size {
    int width, height;
};

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> scenes = {"forest", "car", "hand", "dragonfly"};
    std::vector<std::string> culls = {"bbox", "hull", "dualspace", "twostage"};
    std::vector<float> blurs = {1.0f, 2.0f};
    RenderSettings settings;
    settings.progress = false;
    std::vector<Size> sizes = {{settings.width, settings.height}};
    std::vector<int> spps = {settings.spp}, thread_counts = {settings.threads};
    std::string csv_path;
    int repeat = 3;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::invalid_argument(arg + ": missing value");
                return argv[++i];
            };
            if (arg == "--scenes") scenes = split(value());
            else if (arg == "--culls") culls = split(value());
            else if (arg == "--size") {
                sizes.clear();
                for (const std::string& v : split(value())) {
                    Size size{};
                    if (std::sscanf(v.c_str(), "%dx%d", &size.width, &size.height) != 2 || size.width < 1 ||
                        size.height < 1)
                        throw std::invalid_argument("--size: '" + v + "' is not WxH");
                    sizes.push_back(size);
                }
            } else if (arg == "--spp" || arg == "--threads") {
                std::vector<int>& list = arg == "--spp" ? spps : thread_counts;
                list.clear();
                for (const std::string& v : split(value())) list.push_back(std::max(0, std::atoi(v.c_str())));
            } else if (arg == "--csv") csv_path = value();
            else if (arg == "--repeat") repeat = std::max(1, std::atoi(value().c_str()));
            else if (arg == "--blur") {
                blurs.clear();
                for (const std::string& b : split(value())) blurs.push_back(std::stof(b));
            } else throw std::invalid_argument("unknown option '" + arg + "'");
        }
        std::FILE* csv = nullptr;
        if (!csv_path.empty()) {
            csv = std::fopen(csv_path.c_str(), "w");
            if (csv == nullptr) throw std::invalid_argument("--csv: cannot write '" + csv_path + "'");
            std::fprintf(csv, "scene,blur,width,height,spp,threads,renderer,wall_ms,cpu_s,xwall,xcpu,visited_px,"
                              "tested_px,hit_px,image,setup_ms,binning_ms,raster_ms,resolve_ms\n");
        }
        for (const Size& size : sizes) {
            for (int spp : spps) {
                for (int threads : thread_counts) {
                    settings.width = size.width;
                    settings.height = size.height;
                    settings.spp = spp;
                    settings.threads = threads;
                    std::printf("%dx%d, %d spp, threads %d (0 = all), median of %d; ratios against embree in the "
                                "same run\n",
                                settings.width, settings.height, settings.spp, settings.threads, repeat);
                    std::printf("%-7s %4s %-14s %9s %7s %6s %6s %8s %8s %7s %-7s %9s  %s\n", "scene", "blur",
                                "renderer", "wall ms", "cpu s", "xwall", "xcpu", "visit/px", "test/px", "hit/px",
                                "image", "rmse emb", "phases (ms)");
                    for (const std::string& scene : scenes)
                        for (float blur : blurs) run_scene(scene, blur, settings, repeat, culls, csv);
                    std::fflush(stdout);
                }
            }
        }
        if (csv != nullptr) std::fclose(csv);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_cpu_embree: %s\n", error.what());
        return 1;
    }
    return 0;
}
