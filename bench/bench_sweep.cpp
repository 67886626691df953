// STE, samples visited and time per culling method as the blur grows, on
// single-triangle cases (docs/benchmarks.md, "Sweeps").
//
//   build/bench/bench_sweep [--configs 40] [--spp 16] [--footprint 4] [--block 16] [--csv out.csv]
//
// Each case is one random triangle (16 to 32 pixels across on a 1024x1024
// screen, depths 2 to 4) with screen motion of L pixels (a common direction,
// each vertex within 25 % of it) and a circle of confusion of C pixels (per
// vertex within 25 % of C, all behind the focal plane), for three sweeps:
// motion (C = 0), defocus (L = 0) and both (L = C), at 0, 1, 2, 4, 8, 16, 32
// and 64 pixels. The triangle is rasterized like the CPU backend does it:
// blocks of --block pixels over its screen box, each bounded first (skipped
// when empty), then footprints of --footprint pixels in them bounded by
// sample_bounds_in_tile (0 or a block <= the footprint: no blocks), then per
// sample the renderer's culls (sample_culled), covers on
// what passed (kernel in double, the renderer's default sample pattern).
// Per method and blur: STE = covered / tested, samples visited per pixel of
// the box (every sample of a non-empty footprint, or, where its shutter
// interval sample_time_range is shorter than 0.5, only those inside it, as
// the CPU backend visits time-sorted samples), samples tested per pixel, and
// nanoseconds per pixel of the whole loop (bounds, culls and exact tests):
// the thread's CPU time, so preemption on a loaded machine does not count,
// the least of 3 runs of each case; still, only the ratios between methods
// in one run mean anything.
#include "kernel_generators.hpp"

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace blurcull;
using namespace blurcull::testing;

constexpr int kScreen = 1024;
constexpr double kPixel = 2.0 / kScreen;

struct Sample {
    Kd::vec2 ndc, lens;
    double time;
};

struct Case {
    Kd::MovingTriangle tri;
    glm::ivec4 rect;              // the pixels its blurred screen box touches (inclusive)
    std::vector<Sample> samples;  // spp per pixel of rect, row by row: made before timing, as a renderer does
    int width = 0;                // of rect
};

// A triangle of the sweep: motion of `motion_px` and CoC of `coc_px` pixels.
Case make_case(Rng& rng, double motion_px, double coc_px) {
    Case c;
    const Kd::vec2 centre(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5));
    const double size = rng.uniform(16.0, 32.0) * kPixel;
    const double angle = rng.uniform(0.0, 6.283185307179586);
    const Kd::vec2 direction(std::cos(angle), std::sin(angle));
    for (int i = 0; i < 3; ++i) {
        const double a = angle + 2.0943951023931953 * i + rng.uniform(-0.5, 0.5);
        const Kd::vec2 s = centre + 0.5 * size * Kd::vec2(std::cos(a), std::sin(a));
        const Kd::vec2 moved = s + direction * (motion_px * kPixel * rng.uniform(0.75, 1.25));
        const double w0 = rng.uniform(2.0, 4.0), w1 = w0 * rng.uniform(0.95, 1.05);
        const double c0 = coc_px * kPixel * rng.uniform(0.75, 1.25), c1 = c0 * rng.uniform(0.9, 1.1);
        // Clip (x, y, w) of a screen position at depth w; the CoC in clip units is c_screen w.
        c.tri.p[i] = Kd::vec3(s.x * w0, s.y * w0, w0);
        c.tri.p[i + 3] = Kd::vec3(moved.x * w1, moved.y * w1, w1);
        c.tri.c[i] = Kd::vec2(c0 * w0);
        c.tri.c[i + 3] = Kd::vec2(c1 * w1);
    }
    const Kd::ScreenBound box = Kd::screen_bound(c.tri, 0.05, BC_CULL_BBOX);
    c.rect = Kd::box_cell_rect(box.lo, box.hi, Kd::vec2(kScreen));
    return c;
}

// The renderer's default samples of every pixel of c.rect.
void make_samples(Case& c, int spp) {
    c.width = c.rect.z - c.rect.x + 1;
    for (int py = c.rect.y; py <= c.rect.w; ++py)
        for (int px = c.rect.x; px <= c.rect.z; ++px)
            for (int j = 0; j < spp; ++j) {
                const Kd::PixelSample s =
                    Kd::pixel_sample(std::uint32_t(px), std::uint32_t(py), std::uint32_t(j), std::uint32_t(spp), 7u);
                c.samples.push_back({Kd::pixel_sample_ndc(glm::ivec2(px, py), s.offset, Kd::vec2(kScreen)), s.lens,
                                     s.time});
            }
}

struct Tally {
    double covered = 0, tested = 0, visited = 0, pixels = 0, ns = 0;
};

double thread_ns() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e9 + double(now.tv_nsec);
}

// One method over one case: blocks, footprints, bounds, the per-sample culls
// and covers, counted into tally; returns the thread CPU time it took (ns).
double rasterize_once(const Case& c, int method, int spp, int footprint, int block, Tally& tally) {
    const Kd::vec2 size(kScreen);
    const double start = thread_ns();
    const Kd::ScreenBound screen = Kd::screen_bound(c.tri, 0.05, method);
    // Like the CPU backend: a triangle with no blur gets no lens/time bounds.
    const bool needs_bounds = Kd::classify(c.tri) != 0;
    double covered = 0, tested = 0, visited = 0;
    const bool blocks = block > footprint;
    const int step = blocks ? block : footprint;
    for (int by = c.rect.y; by <= c.rect.w; by += step) {
      for (int bx = c.rect.x; bx <= c.rect.z; bx += step) {
        const glm::ivec4 tile(bx, by, std::min(bx + step - 1, c.rect.z), std::min(by + step - 1, c.rect.w));
        Kd::SampleBounds tile_bounds = Kd::no_sample_bounds();
        if (blocks && needs_bounds) {
            const Kd::vec4 box = Kd::pixel_rect_ndc(tile, size);
            tile_bounds = Kd::sample_bounds(c.tri, Kd::vec2(box.x, box.y), Kd::vec2(box.z, box.w), method);
            if (tile_bounds.empty) continue;
        }
        for (int fy = tile.y; fy <= tile.w; fy += footprint) {
          for (int fx = tile.x; fx <= tile.z; fx += footprint) {
            const glm::ivec4 f(fx, fy, std::min(fx + footprint - 1, tile.z), std::min(fy + footprint - 1, tile.w));
            const Kd::vec4 box = Kd::pixel_rect_ndc(f, size);
            const Kd::vec2 lo(box.x, box.y), hi(box.z, box.w);
            Kd::SampleBounds b = Kd::no_sample_bounds();
            if (needs_bounds)
                b = blocks ? Kd::sample_bounds_in_tile(c.tri, lo, hi, method, tile_bounds)
                           : Kd::sample_bounds(c.tri, lo, hi, method);
            if (b.empty) continue;
            const Kd::vec2 range = Kd::sample_time_range(b);
            double in_range = 0, all = 0;
            for (int py = f.y; py <= f.w; ++py) {
                for (int px = f.x; px <= f.z; ++px) {
                    const std::size_t first =
                        (std::size_t(py - c.rect.y) * std::size_t(c.width) + std::size_t(px - c.rect.x)) *
                        std::size_t(spp);
                    for (int j = 0; j < spp; ++j) {
                        const Sample& s = c.samples[first + std::size_t(j)];
                        ++all;
                        if (s.time < range.x || s.time > range.y) continue;
                        ++in_range;
                        if (Kd::sample_culled(screen, true, b, s.ndc, s.lens, s.time)) continue;
                        ++tested;
                        double depth = 0;
                        covered += Kd::covers(c.tri, s.ndc, s.lens, s.time, 0.05, depth);
                    }
                }
            }
            // The CPU backend visits a footprint in time order only when that skips half its shutter.
            visited += range.y - range.x < 0.5 ? in_range : all;
          }
        }
      }
    }
    const double took = thread_ns() - start;
    tally.covered += covered;
    tally.tested += tested;
    tally.visited += visited;
    tally.pixels += double(c.rect.z - c.rect.x + 1) * double(c.rect.w - c.rect.y + 1);
    return took;
}

// rasterize_once counted once, timed as the least of 3 runs.
void rasterize(const Case& c, int method, int spp, int footprint, int block, Tally& tally) {
    Tally scratch;
    double best = rasterize_once(c, method, spp, footprint, block, tally);
    for (int run = 1; run < 3; ++run)
        best = std::min(best, rasterize_once(c, method, spp, footprint, block, scratch));
    tally.ns += best;
}

}  // namespace

int main(int argc, char** argv) {
    int configs = 40, spp = 16, footprint = 4, block = 16;
    std::string csv_path;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (i + 1 >= argc) {
            std::fprintf(stderr, "bench_sweep: error: %s: missing value\n", arg.c_str());
            return 1;
        }
        const std::string value = argv[++i];
        if (arg == "--configs") configs = std::max(1, std::atoi(value.c_str()));
        else if (arg == "--spp") spp = std::max(1, std::atoi(value.c_str()));
        else if (arg == "--footprint") footprint = std::max(1, std::atoi(value.c_str()));
        else if (arg == "--block") block = std::max(0, std::atoi(value.c_str()));
        else if (arg == "--csv") csv_path = value;
        else {
            std::fprintf(stderr, "bench_sweep: error: unknown option '%s'\n", arg.c_str());
            return 1;
        }
    }
    std::ofstream csv;
    if (!csv_path.empty()) {
        csv.open(csv_path);
        if (!csv) {
            std::fprintf(stderr, "bench_sweep: error: cannot write '%s'\n", csv_path.c_str());
            return 1;
        }
        csv << "sweep,blur_px,method,ste,visited_per_pixel,tested_per_pixel,ns_per_pixel,configs,spp,footprint,block\n";
    }
    const char* sweeps[] = {"motion", "defocus", "both"};
    const double blurs[] = {0, 1, 2, 4, 8, 16, 32, 64};
    std::printf("%-8s %5s", "sweep", "px");
    for (int m : all_methods) std::printf(" | %-9s STE  vis  tst    ns/px", method_name(m));
    std::printf("\n");
    for (int sweep = 0; sweep < 3; ++sweep) {
        for (double blur : blurs) {
            Tally tally[method_count];
            Rng rng(0x5eeb0000 + std::uint64_t(sweep) * 1000 + std::uint64_t(blur));
            for (int n = 0; n < configs; ++n) {
                const double motion = sweep != 1 ? blur : 0.0, coc = sweep != 0 ? blur : 0.0;
                Case c = make_case(rng, motion, coc);
                if (c.rect.x > c.rect.z || c.rect.y > c.rect.w) continue;
                make_samples(c, spp);
                for (int m : all_methods) rasterize(c, m, spp, footprint, block, tally[m]);
            }
            std::printf("%-8s %5.0f", sweeps[sweep], blur);
            for (int m : all_methods) {
                const Tally& t = tally[m];
                const double ste = t.tested > 0 ? t.covered / t.tested : 0.0;
                std::printf(" | %-9s %4.1f%% %4.1f %4.1f %8.0f", "", 100 * ste, t.visited / t.pixels,
                            t.tested / t.pixels, t.ns / t.pixels);
                if (csv)
                    csv << sweeps[sweep] << "," << blur << "," << method_name(m) << "," << ste << ","
                        << t.visited / t.pixels << "," << t.tested / t.pixels << "," << t.ns / t.pixels << ","
                        << configs << "," << spp << "," << footprint << "," << block << "\n";
            }
            std::printf("\n");
            std::fflush(stdout);
        }
    }
    return 0;
}
