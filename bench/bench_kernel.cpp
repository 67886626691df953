// Micro-benchmarks of the culling kernel (docs/benchmarks.md, "Micro-benchmarks").
//
// Every benchmark iteration is one operation on one element of a seeded batch
// (generated once, outside the timed loop), so the reported time is the time
// per operation:
//   screen_bound/<precision>/<method>/<workload>   per-triangle setup
//   sample_bounds/<precision>/<method>/<workload>  per-footprint setup (one pixel)
//   (fixed mode only) tile_bounds/..., footprint_in_tile/...: a 16x16 block's bounds
//   and a 4x4 footprint's from them, as the CPU backend bounds (fixed_tile_setup)
//   sample_test/<precision>/<method>/<workload>    screen_contains + sample_passes_at, one sample
//   covers/<precision>/<workload>                  the exact test, one sample
//   pixel/<precision>/<method>/<workload>          one pixel of 16 samples: the per-footprint
//                                                  setup, the sample test, the exact test on
//                                                  the samples that pass
//   pixel_and_triangle/<precision>/<method>/<workload>  the same plus the per-triangle setup
// <method> is bbox, hull, dualspace, clip2, edges (the pixel benchmarks also have none:
// the exact test on every sample); <workload> is motion, defocus, both or
// adversarial (the other generator families, mixed).
//
// BLURCULL_BENCH_FIXED=1 instead runs every workload once on a fixed small
// batch without the benchmark framework, for reproducible instruction counts:
// under callgrind each workload is dumped separately, named
// "<benchmark name> <operations>".
#include "kernel_generators.hpp"

#include <benchmark/benchmark.h>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define BLURCULL_BENCH_HAVE_CALLGRIND 1
#else
#define BLURCULL_BENCH_HAVE_CALLGRIND 0
#endif

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace blurcull;
using namespace blurcull::testing;

constexpr std::size_t kBatchConfigs = 4096;  // configurations per benchmark batch
constexpr std::size_t kFixedConfigs = 256;   // configurations per fixed (callgrind) workload
constexpr std::size_t kSamplesPerPixel = 16;
constexpr double kPixelWidth = 2.0 / 1024.0;  // one pixel of a 1024-wide screen, in NDC
constexpr int kNoCull = -1;                   // pixel baseline: exact test on every sample
constexpr std::array<int, 6> kPixelMethods{kNoCull,           BC_CULL_BBOX,      BC_CULL_HULL,
                                          BC_CULL_DUALSPACE, BC_CULL_TWO_STAGE, BC_CULL_EDGES};

enum class Workload { motion, defocus, both, adversarial };
constexpr std::array<Workload, 4> kWorkloads{Workload::motion, Workload::defocus, Workload::both,
                                             Workload::adversarial};

const char* workload_name(Workload w) {
    switch (w) {
        case Workload::motion: return "motion";
        case Workload::defocus: return "defocus";
        case Workload::both: return "both";
        case Workload::adversarial: return "adversarial";
    }
    return "?";
}

// The generator families whose only purpose is to stress the bounds.
std::vector<Family> adversarial_families() {
    return {Family::focal_plane, Family::near_crossing, Family::tiny_w,     Family::tiny_coc,     Family::huge_motion,
            Family::ray_parallel, Family::degenerate,   Family::extreme_scale, Family::controlled};
}

const char* cull_name(int method) { return method == kNoCull ? "none" : method_name(method); }

template <class Real>
const char* precision_name() {
    return sizeof(Real) == sizeof(float) ? "float" : "double";
}

// Triangles, one-pixel footprints and kSamplesPerPixel samples per footprint,
// rounded to Real.
template <class Real>
struct Batch {
    using K = kernel<Real>;
    std::vector<typename K::MovingTriangle> tris;
    std::vector<Real> nears;
    std::vector<typename K::vec2> lo, hi;
    std::vector<typename K::vec2> s, uv;  // sample k of configuration i at i * kSamplesPerPixel + k
    std::vector<Real> t;

    std::size_t configs() const { return tris.size(); }
    std::size_t samples() const { return t.size(); }
};

// The first n configurations of a workload do not depend on the batch size,
// so the fixed mode measures a prefix of what the benchmarks time.
template <class Real>
Batch<Real> make_batch(Workload workload, std::size_t n) {
    using K = kernel<Real>;
    Batch<Real> batch;
    Rng rng(0xBE7C4000u + static_cast<std::uint64_t>(workload));
    const std::vector<Family> adversarial = adversarial_families();
    for (std::size_t i = 0; i < n; ++i) {
        Family family = Family::motion;
        switch (workload) {
            case Workload::motion: family = Family::motion; break;
            case Workload::defocus: family = Family::defocus; break;
            case Workload::both: family = Family::both; break;
            case Workload::adversarial: family = adversarial[i % adversarial.size()]; break;
        }
        Config cfg = make_config(rng, family);
        // One pixel around the anchor (the generator sometimes makes tiles).
        Kd::vec2 offset(rng.uniform(), rng.uniform());
        cfg.s_lo = cfg.anchor - offset * kPixelWidth;
        cfg.s_hi = cfg.s_lo + Kd::vec2(kPixelWidth);
        typename K::vec2 lo(cfg.s_lo), hi(cfg.s_hi);
        batch.tris.push_back(to_real<Real>(cfg.tri));
        batch.nears.push_back(static_cast<Real>(cfg.near));
        batch.lo.push_back(lo);
        batch.hi.push_back(hi);
        for (std::size_t k = 0; k < kSamplesPerPixel; ++k) {
            Sample5 smp = make_sample(rng, cfg);
            // Rounding may push a sample out of the rounded footprint.
            batch.s.push_back(glm::clamp(typename K::vec2(smp.s), lo, hi));
            batch.uv.push_back(typename K::vec2(smp.uv));
            batch.t.push_back(static_cast<Real>(smp.t));
        }
    }
    return batch;
}

// Benchmark batches, built on first use and kept for the whole run.
template <class Real>
const Batch<Real>& benchmark_batch(Workload workload) {
    static std::array<std::unique_ptr<Batch<Real>>, kWorkloads.size()> cache;
    std::unique_ptr<Batch<Real>>& slot = cache[static_cast<std::size_t>(workload)];
    if (!slot) slot = std::make_unique<Batch<Real>>(make_batch<Real>(workload, kBatchConfigs));
    return *slot;
}

// A batch with one method's per-triangle and per-footprint bounds computed
// ahead, for the per-sample benchmarks.
template <class Real>
struct Prepared {
    using K = kernel<Real>;
    const Batch<Real>& batch;
    int method;
    std::vector<typename K::ScreenBound> screens;
    std::vector<typename K::SampleBounds> bounds;

    Prepared(const Batch<Real>& b, int m) : batch(b), method(m) {
        screens.reserve(b.configs());
        bounds.reserve(b.configs());
        for (std::size_t i = 0; i < b.configs(); ++i) {
            screens.push_back(K::screen_bound(b.tris[i], b.nears[i], m));
            bounds.push_back(K::sample_bounds(b.tris[i], b.lo[i], b.hi[i], m));
        }
    }
};

struct PixelCount {
    int tested = 0;   // samples that reached the exact test
    int covered = 0;  // samples the exact test found covered
};

// ---- the operations: one call is one timed unit ----------------------------------
// Each returns a small value that the callers accumulate, and hides its result
// from the optimiser.

template <class Real>
struct Ops {
    using K = kernel<Real>;

    static int screen_bound(const Batch<Real>& b, int method, std::size_t i) {
        typename K::ScreenBound bound = K::screen_bound(b.tris[i], b.nears[i], method);
        benchmark::DoNotOptimize(bound);
        return bound.hull_count;
    }

    static int sample_bounds(const Batch<Real>& b, int method, std::size_t i) {
        typename K::SampleBounds bounds = K::sample_bounds(b.tris[i], b.lo[i], b.hi[i], method);
        benchmark::DoNotOptimize(bounds);
        return bounds.empty ? 0 : 1;
    }

    static int sample_test(const Prepared<Real>& p, std::size_t j) {
        std::size_t i = j / kSamplesPerPixel;
        bool pass = K::screen_contains(p.screens[i], p.batch.s[j]) &&
                    K::sample_passes_at(p.bounds[i], p.batch.s[j], p.batch.uv[j], p.batch.t[j]);
        benchmark::DoNotOptimize(pass);
        return pass ? 1 : 0;
    }

    static int covers(const Batch<Real>& b, std::size_t j) {
        std::size_t i = j / kSamplesPerPixel;
        Real depth = Real(0);
        bool hit = K::covers(b.tris[i], b.s[j], b.uv[j], b.t[j], b.nears[i], depth);
        benchmark::DoNotOptimize(depth);
        return hit ? 1 : 0;
    }

    // One pixel: the per-footprint setup, the sample test on each sample and the
    // exact test on those that pass. `screens` holds the per-triangle bounds
    // computed ahead (a renderer computes them once per triangle, for all its
    // pixels); when null, this pixel pays for its triangle's setup too, as for
    // a triangle that touches only this pixel.
    static PixelCount pixel(const Batch<Real>& b, int method, const typename K::ScreenBound* screens, std::size_t i) {
        PixelCount count;
        const std::size_t first = i * kSamplesPerPixel;
        if (method == kNoCull) {
            for (std::size_t j = first; j < first + kSamplesPerPixel; ++j) {
                Real depth = Real(0);
                ++count.tested;
                if (K::covers(b.tris[i], b.s[j], b.uv[j], b.t[j], b.nears[i], depth)) ++count.covered;
                benchmark::DoNotOptimize(depth);
            }
            return count;
        }
        typename K::ScreenBound own_screen;
        if (!screens) own_screen = K::screen_bound(b.tris[i], b.nears[i], method);
        const typename K::ScreenBound& screen = screens ? screens[i] : own_screen;
        typename K::SampleBounds bounds = K::sample_bounds(b.tris[i], b.lo[i], b.hi[i], method);
        for (std::size_t j = first; j < first + kSamplesPerPixel; ++j) {
            if (!K::screen_contains(screen, b.s[j]) || !K::sample_passes_at(bounds, b.s[j], b.uv[j], b.t[j])) continue;
            Real depth = Real(0);
            ++count.tested;
            if (K::covers(b.tris[i], b.s[j], b.uv[j], b.t[j], b.nears[i], depth)) ++count.covered;
            benchmark::DoNotOptimize(depth);
        }
        return count;
    }
};

// ---- benchmarks --------------------------------------------------------------------

// Advances a batch index, wrapping at n.
inline void advance(std::size_t& i, std::size_t n) {
    if (++i == n) i = 0;
}

template <class Real>
void bm_screen_bound(benchmark::State& state, int method, Workload workload) {
    const Batch<Real>& b = benchmark_batch<Real>(workload);
    std::size_t i = 0;
    std::int64_t with_hull = 0;
    for (auto _ : state) {
        with_hull += Ops<Real>::screen_bound(b, method, i) > 0 ? 1 : 0;
        advance(i, b.configs());
    }
    state.SetItemsProcessed(state.iterations());
    state.counters["hull_share"] = benchmark::Counter(static_cast<double>(with_hull), benchmark::Counter::kAvgIterations);
}

template <class Real>
void bm_sample_bounds(benchmark::State& state, int method, Workload workload) {
    const Batch<Real>& b = benchmark_batch<Real>(workload);
    std::size_t i = 0;
    std::int64_t nonempty = 0;
    for (auto _ : state) {
        nonempty += Ops<Real>::sample_bounds(b, method, i);
        advance(i, b.configs());
    }
    state.SetItemsProcessed(state.iterations());
    state.counters["nonempty_share"] = benchmark::Counter(static_cast<double>(nonempty), benchmark::Counter::kAvgIterations);
}

template <class Real>
void bm_sample_test(benchmark::State& state, int method, Workload workload) {
    const Prepared<Real> p(benchmark_batch<Real>(workload), method);
    std::size_t j = 0;
    std::int64_t passed = 0;
    for (auto _ : state) {
        passed += Ops<Real>::sample_test(p, j);
        advance(j, p.batch.samples());
    }
    state.SetItemsProcessed(state.iterations());
    state.counters["pass_share"] = benchmark::Counter(static_cast<double>(passed), benchmark::Counter::kAvgIterations);
}

template <class Real>
void bm_covers(benchmark::State& state, Workload workload) {
    const Batch<Real>& b = benchmark_batch<Real>(workload);
    std::size_t j = 0;
    std::int64_t covered = 0;
    for (auto _ : state) {
        covered += Ops<Real>::covers(b, j);
        advance(j, b.samples());
    }
    state.SetItemsProcessed(state.iterations());
    state.counters["covered_share"] = benchmark::Counter(static_cast<double>(covered), benchmark::Counter::kAvgIterations);
}

// with_triangle_setup: every pixel also computes its triangle's screen bound.
template <class Real>
void bm_pixel(benchmark::State& state, int method, Workload workload, bool with_triangle_setup) {
    const Batch<Real>& b = benchmark_batch<Real>(workload);
    const Prepared<Real> p(b, method == kNoCull ? BC_CULL_BBOX : method);
    const typename kernel<Real>::ScreenBound* screens = with_triangle_setup ? nullptr : p.screens.data();
    std::size_t i = 0;
    std::int64_t tested = 0;
    std::int64_t covered = 0;
    for (auto _ : state) {
        PixelCount c = Ops<Real>::pixel(b, method, screens, i);
        tested += c.tested;
        covered += c.covered;
        advance(i, b.configs());
    }
    using benchmark::Counter;
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kSamplesPerPixel));
    state.counters["tested"] = Counter(static_cast<double>(tested), Counter::kAvgIterations);
    state.counters["covered"] = Counter(static_cast<double>(covered), Counter::kAvgIterations);
    // Sample test efficiency: the share of exact tests that found a hit.
    state.counters["STE"] = tested > 0 ? static_cast<double>(covered) / static_cast<double>(tested) : 0.0;
    // CPU seconds per covered sample; the console prints it with an SI prefix (n = ns).
    state.counters["time_per_covered"] = Counter(static_cast<double>(covered), Counter::kIsRate | Counter::kInvert);
}

template <class Real>
void register_precision() {
    const std::string precision = precision_name<Real>();
    auto name = [&](const char* op, const char* method, Workload w) {
        std::string n = std::string(op) + "/" + precision + "/";
        if (method) n += std::string(method) + "/";
        return n + workload_name(w);
    };
    for (Workload w : kWorkloads) {
        for (int m : all_methods)
            benchmark::RegisterBenchmark(name("screen_bound", cull_name(m), w).c_str(), bm_screen_bound<Real>, m, w);
    }
    for (Workload w : kWorkloads) {
        for (int m : all_methods)
            benchmark::RegisterBenchmark(name("sample_bounds", cull_name(m), w).c_str(), bm_sample_bounds<Real>, m, w);
    }
    for (Workload w : kWorkloads) {
        for (int m : all_methods)
            benchmark::RegisterBenchmark(name("sample_test", cull_name(m), w).c_str(), bm_sample_test<Real>, m, w);
    }
    for (Workload w : kWorkloads)
        benchmark::RegisterBenchmark(name("covers", nullptr, w).c_str(), bm_covers<Real>, w);
    for (bool with_triangle_setup : {false, true}) {
        const char* op = with_triangle_setup ? "pixel_and_triangle" : "pixel";
        for (Workload w : kWorkloads) {
            for (int m : kPixelMethods)
                benchmark::RegisterBenchmark(name(op, cull_name(m), w).c_str(), bm_pixel<Real>, m, w,
                                             with_triangle_setup);
        }
    }
}

// ---- fixed mode ---------------------------------------------------------------------

// What a fixed workload found, printed after the measured region.
struct FixedResult {
    const char* what;  // e.g. "passed"
    std::int64_t count;
    const char* what2 = nullptr;  // optional second count
    std::int64_t count2 = 0;
};

// Runs `ops` operations between zeroed and dumped callgrind counters (no-ops
// outside valgrind) and prints the name, the count and what the body found
// (so that runs can be compared).
template <class Body>
void fixed_run(const std::string& name, std::size_t ops, Body body) {
    const std::string label = name + " " + std::to_string(ops);
#if BLURCULL_BENCH_HAVE_CALLGRIND
    CALLGRIND_ZERO_STATS;
#endif
    const FixedResult result = body();
#if BLURCULL_BENCH_HAVE_CALLGRIND
    CALLGRIND_DUMP_STATS_AT(label.c_str());
#endif
    std::printf("%-44s %6zu ops  %s %lld", name.c_str(), ops, result.what, static_cast<long long>(result.count));
    if (result.what2) std::printf(" %s %lld", result.what2, static_cast<long long>(result.count2));
    std::printf("\n");
}

// The CPU backend's two levels (docs/cpu-renderer.md): a 16x16-pixel block's
// bounds (tile_bounds) and, from them, a 4x4-pixel footprint's
// (footprint_in_tile: sample_bounds_in_tile, which for edges reuses the
// block's planes), both around each configuration's pixel, so the setup per
// pixel of every method is tile / 256 + footprint / 16.
template <class Real>
void fixed_tile_setup(const Batch<Real>& b, int m, const std::string& name) {
    using K = kernel<Real>;
    const Real pixel = static_cast<Real>(kPixelWidth);
    std::vector<typename K::SampleBounds> tiles(b.configs());
    fixed_run("tile_bounds/" + name, b.configs(), [&] {
        std::int64_t nonempty = 0;
        for (std::size_t i = 0; i < b.configs(); ++i) {
            tiles[i] = K::sample_bounds(b.tris[i], b.lo[i] - Real(7) * pixel, b.hi[i] + Real(8) * pixel, m);
            nonempty += tiles[i].empty ? 0 : 1;
        }
        return FixedResult{"nonempty", nonempty};
    });
    fixed_run("footprint_in_tile/" + name, b.configs(), [&] {
        std::int64_t nonempty = 0;
        for (std::size_t i = 0; i < b.configs(); ++i) {
            const typename K::SampleBounds f = K::sample_bounds_in_tile(
                b.tris[i], b.lo[i] - Real(1) * pixel, b.hi[i] + Real(2) * pixel, m, tiles[i]);
            nonempty += f.empty ? 0 : 1;
        }
        return FixedResult{"nonempty", nonempty};
    });
}

template <class Real>
void fixed_precision() {
    const std::string precision = precision_name<Real>();
    for (Workload w : kWorkloads) {
        const Batch<Real> b = make_batch<Real>(w, kFixedConfigs);
        const std::string suffix = std::string("/") + workload_name(w);
        for (int m : all_methods) {
            const std::string method = std::string("/") + cull_name(m);
            fixed_run("screen_bound/" + precision + method + suffix, b.configs(), [&] {
                std::int64_t sum = 0;
                for (std::size_t i = 0; i < b.configs(); ++i) sum += Ops<Real>::screen_bound(b, m, i) > 0 ? 1 : 0;
                return FixedResult{"with hull", sum};
            });
            fixed_run("sample_bounds/" + precision + method + suffix, b.configs(), [&] {
                std::int64_t sum = 0;
                for (std::size_t i = 0; i < b.configs(); ++i) sum += Ops<Real>::sample_bounds(b, m, i);
                return FixedResult{"nonempty", sum};
            });
            fixed_tile_setup(b, m, precision + method + suffix);
            const Prepared<Real> p(b, m);
            fixed_run("sample_test/" + precision + method + suffix, b.samples(), [&] {
                std::int64_t sum = 0;
                for (std::size_t j = 0; j < b.samples(); ++j) sum += Ops<Real>::sample_test(p, j);
                return FixedResult{"passed", sum};
            });
        }
        fixed_run("covers/" + precision + suffix, b.samples(), [&] {
            std::int64_t sum = 0;
            for (std::size_t j = 0; j < b.samples(); ++j) sum += Ops<Real>::covers(b, j);
            return FixedResult{"covered", sum};
        });
        for (bool with_triangle_setup : {false, true}) {
            const std::string op = with_triangle_setup ? "pixel_and_triangle/" : "pixel/";
            for (int m : kPixelMethods) {
                const Prepared<Real> p(b, m == kNoCull ? BC_CULL_BBOX : m);
                const typename kernel<Real>::ScreenBound* screens = with_triangle_setup ? nullptr : p.screens.data();
                fixed_run(op + precision + "/" + cull_name(m) + suffix, b.configs(), [&] {
                    std::int64_t tested = 0;
                    std::int64_t covered = 0;
                    for (std::size_t i = 0; i < b.configs(); ++i) {
                        PixelCount c = Ops<Real>::pixel(b, m, screens, i);
                        tested += c.tested;
                        covered += c.covered;
                    }
                    return FixedResult{"tested", tested, "covered", covered};
                });
            }
        }
    }
}

// BLURCULL_BENCH_FIXED: unset, empty or "0" = benchmark mode, "1" = fixed mode.
bool fixed_mode_requested() {
    const char* env = std::getenv("BLURCULL_BENCH_FIXED");
    if (!env || env[0] == '\0' || std::strcmp(env, "0") == 0) return false;
    if (std::strcmp(env, "1") == 0) return true;
    std::fprintf(stderr, "bench_kernel: BLURCULL_BENCH_FIXED must be 0 or 1, got \"%s\"\n", env);
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    if (fixed_mode_requested()) {
        if (argc > 1) {
            std::fprintf(stderr, "bench_kernel: BLURCULL_BENCH_FIXED=1 takes no arguments, got \"%s\"\n", argv[1]);
            return 2;
        }
        fixed_precision<float>();
        fixed_precision<double>();
        return 0;
    }
    register_precision<float>();
    register_precision<double>();
    // A short default run (about 150 benchmarks); an explicit
    // --benchmark_min_time on the command line wins.
    static char default_min_time[] = "--benchmark_min_time=0.01";
    std::vector<char*> args(argv, argv + argc);
    bool has_min_time = false;
    for (int k = 1; k < argc; ++k) {
        if (std::strncmp(argv[k], "--benchmark_min_time", 20) == 0) has_min_time = true;
    }
    if (!has_min_time && !args.empty()) args.insert(args.begin() + 1, default_min_time);
    int count = static_cast<int>(args.size());
    args.push_back(nullptr);
    benchmark::Initialize(&count, args.data());
    if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
