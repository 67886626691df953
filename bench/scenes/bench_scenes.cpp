// The STE table: renders the built-in scenes at 1x and 2x blur with every
// culling method on the CPU backend and reports sample test efficiency and
// time, in the layout of the thesis's Table 4.1, next to its published numbers.
//
//   bench_scenes [--size 1024x768] [--spp 16] [--repeat 3] [--footprint 4]
//                [--scenes hand,car,dragonfly,forest] [--blurs 1,2] [--csv out.csv]
//                [--markdown docs/benchmarks.md] [--methods bbox,hull,dualspace,clip2,edges]
//                [--edge-min-samples N]
//
// --methods renders only those (the others' columns stay 0; ratios to bbox
// need bbox); with clip2 and edges both, each render's edges / clip2 CPU
// time is printed. --edge-min-samples sets CpuOptions::edge_min_samples
// (which blocks get edges' planes).
//
// --blurs takes any blur scales (the sweep of docs/benchmarks.md uses
// 0.25,0.5,1,2,4: a scene's blur scale must be > 0); the thesis's columns
// exist for 1 and 2 only.
//
// Times are medians over --repeat runs, given as ratios to bbox measured in
// the same run (same scene, same samples): on a noisy machine only ratios
// within one run mean something.
#include "bench_common.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "scene/builtin_scenes.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace blurcull::frontend;

namespace {

struct Published {
    const char* scene;
    const char* blur;
    const char* triangles;
    double bbox[2], dualspace[2], thesis[2];  // STE %, 1x and 2x
};

// Table 4.1 (16 spp, 1024x768) of the NCTU thesis of the same name behind Wu,
// Way, Tsai and Shih, "Clip Space Sample Culling for Motion Blur and Defocus
// Blur", JISE 31(3), 2015.
const Published published[] = {
    {"hand", "defocus", "15k", {12, 10}, {29, 28}, {29, 27}},
    {"car", "object motion", "54k", {9, 4}, {28, 25}, {27, 26}},
    {"dragonfly", "camera motion", "85k", {3, 1}, {23, 24}, {22, 24}},
    {"forest", "motion + defocus", "170k", {0.4, 0.2}, {5, 2}, {19, 13}},
};

const CullMethod methods[] = {CullMethod::bbox, CullMethod::hull, CullMethod::dualspace, CullMethod::two_stage,
                              CullMethod::edges, CullMethod::hyperplane};
constexpr int kMethods = static_cast<int>(std::size(methods));

struct Row {
    std::string scene;
    double blur = 1;
    std::size_t triangles = 0;
    double ste[kMethods] = {};
    double ms[kMethods] = {};      // median wall time
    double cpu_ms[kMethods] = {};  // median CPU time of the process over the render (all threads)
    // Per pixel: (sample, triangle) pairs looked at to decide (visited) and
    // pairs that reached the exact test (tested).
    double visited[kMethods] = {};
    double tested[kMethods] = {};
};

// CPU time of the process (every thread), in ms: unlike wall time it does
// not count the time other work on a loaded machine takes the cores away.
double process_cpu_ms() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

using blurcull::bench::median;
using blurcull::bench::split;

std::string markdown(const std::vector<Row>& rows, int width, int height, int spp, int repeat, int footprint) {
    std::ostringstream md;
    char line[512];
    md << "## STE table (CPU backend)\n\n";
    md << "Built-in scenes, " << width << "x" << height << ", " << spp
       << " spp, CPU backend, kernel in double, culling footprints of " << footprint << "x" << footprint
       << " pixels. STE = samples covered / samples tested (higher is better).\n"
       << "Time is the median of " << repeat
       << " renders as a ratio to bbox in the same run (lower is better); bbox's median is given in ms.\n"
       << "Reproduce: `./build/bench/bench_scenes --size " << width << "x" << height << " --spp " << spp
       << " --repeat " << repeat << " --footprint " << footprint << " --markdown docs/benchmarks.md --csv docs/ste_table.csv`.\n"
       << "The thesis columns are Table 4.1 of the clip-space sample culling thesis (GTX 580, its own scenes);\n"
       << "our scenes mirror its workloads procedurally, so compare trends, not digits.\n\n";
    md << "| scene | blur | STE bbox | STE hull | STE dualspace | STE clip2 | STE edges | STE hyperplane | time bbox |"
          " hull | dualspace | clip2 | edges | hyperplane | thesis STE bbox / dual-space / thesis |\n";
    md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows) {
        const Published* p = nullptr;
        for (const Published& q : published)
            if (r.scene == q.scene) p = &q;
        std::string thesis = "n/a";
        if (p && (r.blur == 1 || r.blur == 2)) {
            const int b = int(r.blur) - 1;
            std::snprintf(line, sizeof line, "%g%% / %g%% / %g%%", p->bbox[b], p->dualspace[b], p->thesis[b]);
            thesis = line;
        }
        std::snprintf(line, sizeof line,
                      "| %s (%zu) | x%g | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.0f ms | %.2f | %.2f | "
                      "%.2f | %.2f | %.2f | %s |\n",
                      r.scene.c_str(), r.triangles, r.blur, 100 * r.ste[0], 100 * r.ste[1], 100 * r.ste[2],
                      100 * r.ste[3], 100 * r.ste[4], 100 * r.ste[5], r.ms[0], r.ms[1] / r.ms[0], r.ms[2] / r.ms[0],
                      r.ms[3] / r.ms[0], r.ms[4] / r.ms[0], r.ms[5] / r.ms[0], thesis.c_str());
        md << line;
    }
    md << "\nCPU time of the process (all threads) over each render, median, as a ratio to bbox's (less "
          "sensitive to other load than wall time):\n\n| scene | blur | bbox | hull | dualspace | clip2 | edges | hyperplane |\n"
          "|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows) {
        std::snprintf(line, sizeof line, "| %s | x%g | %.0f ms | %.2f | %.2f | %.2f | %.2f | %.2f |\n", r.scene.c_str(),
                      r.blur, r.cpu_ms[0], r.cpu_ms[1] / r.cpu_ms[0], r.cpu_ms[2] / r.cpu_ms[0],
                      r.cpu_ms[3] / r.cpu_ms[0], r.cpu_ms[4] / r.cpu_ms[0], r.cpu_ms[5] / r.cpu_ms[0]);
        md << line;
    }
    md << "\nSamples visited per pixel (looked at by the per-sample cull; only a footprint's shutter interval when\n"
          "its samples are visited in time order) / samples tested per pixel (reached the exact test):\n\n";
    md << "| scene | blur |";
    for (CullMethod m : methods) md << " " << to_string(m) << " |";
    md << "\n|---|---|";
    for (int m = 0; m < kMethods; ++m) md << "---|";
    md << "\n";
    for (const Row& r : rows) {
        md << "| " << r.scene << " | x" << r.blur << " |";
        for (int m = 0; m < kMethods; ++m) {
            std::snprintf(line, sizeof line, " %.1f / %.1f |", r.visited[m], r.tested[m]);
            md << line;
        }
        md << "\n";
    }
    return md.str();
}

}  // namespace

int main(int argc, char** argv) {
    int width = 1024, height = 768, spp = 16, repeat = 3, footprint = 4;
    int edge_min_samples = CpuOptions{}.edge_min_samples;
    bool selected[kMethods];
    std::fill(selected, selected + kMethods, true);
    std::vector<std::string> scenes = builtin_scene_names();
    std::string csv_path, md_path;
    std::vector<double> blurs = {1, 2};
    try {
        for (int i = 1; i < argc; ++i) {
            std::string arg = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::invalid_argument(arg + ": missing value");
                return argv[++i];
            };
            if (arg == "--size") {
                std::string v = value();
                if (std::sscanf(v.c_str(), "%dx%d", &width, &height) != 2 || width < 1 || height < 1)
                    throw std::invalid_argument("--size: expected WxH, got '" + v + "'");
            } else if (arg == "--spp") {
                spp = std::atoi(value().c_str());
            } else if (arg == "--repeat") {
                repeat = std::max(1, std::atoi(value().c_str()));
            } else if (arg == "--footprint") {
                footprint = std::max(1, std::atoi(value().c_str()));
            } else if (arg == "--blurs") {
                blurs.clear();
                for (const std::string& b : split(value())) {
                    const double scale = std::atof(b.c_str());
                    if (!(scale > 0.0) || scale > 64.0)
                        throw std::invalid_argument("--blurs: expected scales in (0, 64], got '" + b + "'");
                    blurs.push_back(scale);
                }
                if (blurs.empty()) throw std::invalid_argument("--blurs: no scale given");
            } else if (arg == "--scenes") {
                scenes = split(value());
            } else if (arg == "--methods") {
                std::vector<CullMethod> wanted;
                for (const std::string& name : split(value())) wanted.push_back(parse_cull_method(name));
                for (int m = 0; m < kMethods; ++m)
                    selected[m] = std::find(wanted.begin(), wanted.end(), methods[m]) != wanted.end();
                if (std::find(selected, selected + kMethods, true) == selected + kMethods)
                    throw std::invalid_argument("--methods: none of bbox, hull, dualspace, clip2, edges, hyperplane given");
            } else if (arg == "--edge-min-samples") {
                edge_min_samples = std::max(0, std::atoi(value().c_str()));
            } else if (arg == "--csv") {
                csv_path = value();
            } else if (arg == "--markdown") {
                md_path = value();
            } else {
                throw std::invalid_argument("unknown option '" + arg + "'");
            }
        }
        std::vector<Row> rows;
        for (const std::string& name : scenes) {
            for (double blur : blurs) {
                SceneOptions options;
                options.blur_scale = float(blur);
                options.aspect = float(width) / float(height);
                Scene scene = make_builtin_scene(name, options);
                RenderSettings settings;
                settings.width = width;
                settings.height = height;
                settings.spp = spp;
                settings.progress = false;
                CpuOptions cpu;
                cpu.footprint = footprint;
                cpu.edge_min_samples = edge_min_samples;
                Row row;
                row.scene = name;
                row.blur = blur;
                row.triangles = scene.triangles.size();
                std::vector<double> times[kMethods], cpu_times[kMethods];
                // Interleave the methods across repeats so drifting load hits all alike.
                for (int r = 0; r < repeat; ++r) {
                    for (int m = 0; m < kMethods; ++m) {
                        if (!selected[m]) continue;
                        settings.cull = methods[m];
                        const double cpu_start = process_cpu_ms();
                        RenderResult result = render_cpu(scene, settings, cpu);
                        cpu_times[m].push_back(process_cpu_ms() - cpu_start);
                        row.ste[m] = result.stats.ste();
                        const double pixels = double(width) * double(height);
                        row.visited[m] = double(result.stats.samples_visited) / pixels;
                        row.tested[m] = double(result.stats.samples_tested) / pixels;
                        times[m].push_back(result.stats.ms_total);
                    }
                }
                for (int m = 0; m < kMethods; ++m) {
                    if (!selected[m]) continue;
                    row.ms[m] = median(times[m]);
                    row.cpu_ms[m] = median(cpu_times[m]);
                }
                // The time target: edges' CPU time against clip2's, each render.
                if (selected[3] && selected[4]) {
                    std::fprintf(stderr, "  cpu time edges / clip2 %.3f (renders:", row.cpu_ms[4] / row.cpu_ms[3]);
                    for (int r = 0; r < repeat; ++r) std::fprintf(stderr, " %.3f", cpu_times[4][r] / cpu_times[3][r]);
                    std::fprintf(stderr, ")\n");
                }
                std::fprintf(stderr,
                             "%s x%g: STE %.1f/%.1f/%.1f/%.1f/%.1f/%.1f%%, time %.0f ms, ratios %.2f/%.2f/%.2f/%.2f/%.2f\n",
                             name.c_str(), blur, 100 * row.ste[0], 100 * row.ste[1], 100 * row.ste[2],
                             100 * row.ste[3], 100 * row.ste[4], 100 * row.ste[5], row.ms[0], row.ms[1] / row.ms[0],
                             row.ms[2] / row.ms[0], row.ms[3] / row.ms[0], row.ms[4] / row.ms[0], row.ms[5] / row.ms[0]);
                std::fprintf(stderr, "  cpu time %.0f ms, ratios %.2f/%.2f/%.2f/%.2f/%.2f\n", row.cpu_ms[0],
                             row.cpu_ms[1] / row.cpu_ms[0], row.cpu_ms[2] / row.cpu_ms[0],
                             row.cpu_ms[3] / row.cpu_ms[0], row.cpu_ms[4] / row.cpu_ms[0], row.cpu_ms[5] / row.cpu_ms[0]);
                std::fprintf(stderr, "  visited/tested per pixel");
                for (int m = 0; m < kMethods; ++m) std::fprintf(stderr, " %.1f/%.1f", row.visited[m], row.tested[m]);
                std::fprintf(stderr, "\n");
                rows.push_back(row);
            }
        }
        std::string md = markdown(rows, width, height, spp, repeat, footprint);
        std::printf("%s", md.c_str());
        if (!md_path.empty()) blurcull::bench::write_doc_section(md_path, "ste-table", md);
        if (!csv_path.empty()) {
            std::ofstream csv(csv_path);
            if (!csv) throw std::runtime_error("cannot write '" + csv_path + "'");
            csv << "scene,blur,triangles,method,ste,ms_median,time_ratio_to_bbox,width,height,spp,footprint,"
                   "visited_per_pixel,tested_per_pixel,cpu_ms_median,cpu_ratio_to_bbox,cpu_ratio_to_clip2,edge_min_samples\n";
            for (const Row& r : rows)
                for (int m = 0; m < kMethods; ++m)
                    if (selected[m])
                    csv << r.scene << "," << r.blur << "," << r.triangles << "," << to_string(methods[m]) << ","
                        << r.ste[m] << "," << r.ms[m] << "," << r.ms[m] / r.ms[0] << "," << width << "," << height
                        << "," << spp << "," << footprint << "," << r.visited[m] << "," << r.tested[m] << "," << r.cpu_ms[m] << ","
                        << r.cpu_ms[m] / r.cpu_ms[0] << "," << r.cpu_ms[m] / r.cpu_ms[3] << "," << edge_min_samples
                        << "\n";
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_scenes: error: %s\n", error.what());
        return 1;
    }
    return 0;
}
