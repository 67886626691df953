// Micro-benchmarks of the secondary-ray kernel (docs/secondary-rays.md,
// "Cost"). Each iteration is one operation on one element of a seeded batch
// generated outside the timed loop:
//   facet/<precision>/classifier    dodecahedron_facet, one direction
//   facet/<precision>/brute_force   argmax of the 12 dot products, one direction
//   cluster/<precision>/sphere      cluster_reflector_pixels on the 4824 pixels of a mirror sphere
//   viewpoint/<precision>/cluster   fit_virtual_view on one cluster of 1 to 300 pixels
//   trace/<precision>/ray           layer_segment + trace_layers through two 64^2 layers, one ray
//
// BLURCULL_BENCH_FIXED=1 instead runs the two facet classifiers once over the
// 65536 directions, without the framework, in functions named
// fixed_classifier and fixed_brute_force, for instruction counts:
//   valgrind --tool=callgrind --toggle-collect='*fixed_classifier*' bench_secondary
#include "secondary_generators.hpp"

#include <blurcull/layer_trace.hpp>
#include <blurcull/secondary_clusters.hpp>

#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using namespace blurcull;
using namespace blurcull::testing;

template <class Real>
typename kernel<Real>::vec3 to_vec3(dvec3 d) {
    return typename kernel<Real>::vec3(static_cast<Real>(d.x), static_cast<Real>(d.y), static_cast<Real>(d.z));
}

template <class Real>
std::vector<typename kernel<Real>::vec3> directions() {
    std::vector<typename kernel<Real>::vec3> out;
    for (const dvec3& d : facet_test_directions(0xbe7c4ull, 1 << 16)) out.push_back(to_vec3<Real>(d));
    return out;
}

template <class Real>
void facet_classifier(benchmark::State& state) {
    using K = kernel<Real>;
    auto d = directions<Real>();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(K::dodecahedron_facet(d[i]));
        i = (i + 1) & (d.size() - 1);
    }
}

// The facet by 12 dot products: what the classifier replaces.
template <class Real>
int brute_force_facet(const typename kernel<Real>::vec3 n[12], typename kernel<Real>::vec3 d) {
    using K = kernel<Real>;
    int best = 0;
    Real best_dot = K::bc_dot3(n[0], d);
    for (int f = 1; f < 12; ++f) {
        Real dot = K::bc_dot3(n[f], d);
        if (dot > best_dot) {
            best = f;
            best_dot = dot;
        }
    }
    return best;
}

template <class Real>
void facet_brute_force(benchmark::State& state) {
    using K = kernel<Real>;
    auto d = directions<Real>();
    typename K::vec3 n[12];
    for (int f = 0; f < 12; ++f) n[f] = K::dodecahedron_normal(f);
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(brute_force_facet<Real>(n, d[i]));
        i = (i + 1) & (d.size() - 1);
    }
}

__attribute__((noinline)) long fixed_classifier(const std::vector<kernel<float>::vec3>& d) {
    long sum = 0;
    for (const auto& x : d) sum += kernel<float>::dodecahedron_facet(x);
    return sum;
}

__attribute__((noinline)) long fixed_brute_force(const std::vector<kernel<float>::vec3>& d) {
    kernel<float>::vec3 n[12];
    for (int f = 0; f < 12; ++f) n[f] = kernel<float>::dodecahedron_normal(f);
    long sum = 0;
    for (const auto& x : d) sum += brute_force_facet<float>(n, x);
    return sum;
}

template <class Real>
void cluster_sphere(benchmark::State& state) {
    std::vector<dvec3> dp, dd;
    mirror_sphere_pixels(dp, dd);
    std::vector<typename kernel<Real>::vec3> p, d;
    for (std::size_t i = 0; i < dp.size(); ++i) {
        p.push_back(to_vec3<Real>(dp[i]));
        d.push_back(to_vec3<Real>(dd[i]));
    }
    for (auto _ : state) benchmark::DoNotOptimize(cluster_reflector_pixels<Real>(p, d).clusters.size());
    state.counters["pixels"] = static_cast<double>(p.size());
}

template <class Real>
void viewpoint_cluster(benchmark::State& state) {
    using K = kernel<Real>;
    struct Input {
        typename K::ClusterSums sums;
        std::vector<typename K::vec3> p, d;
    };
    std::vector<Input> inputs;
    Rng rng(0x71e3ull);
    long pixels = 0;
    for (int c = 0; c < 256; ++c) {
        SyntheticCluster sc = make_cluster(rng, 30.0);
        Input in{K::cluster_sums_empty(Real(1)), {}, {}};
        for (std::size_t i = 0; i < sc.positions.size(); ++i) {
            in.p.push_back(to_vec3<Real>(sc.positions[i]));
            in.d.push_back(to_vec3<Real>(sc.directions[i]));
        }
        in.sums = cluster_sums_of<Real>(in.p, in.d);
        pixels += static_cast<long>(in.p.size());
        inputs.push_back(std::move(in));
    }
    std::size_t i = 0;
    for (auto _ : state) {
        const Input& in = inputs[i];
        benchmark::DoNotOptimize(fit_virtual_view<Real>(in.sums, in.p, in.d, Real(0.8391), Real(0.01)).backoff);
        i = (i + 1) & 255;
    }
    state.counters["pixels_per_cluster"] = static_cast<double>(pixels) / 256.0;
}

template <class Real>
void trace_ray(benchmark::State& state) {
    using K = kernel<Real>;
    Rng rng(0x7ace0ull);
    LayerScene s = make_layer_scene(rng);
    std::vector<Real> image[2];
    for (int l = 0; l < 2; ++l)
        for (double z : s.depth[l]) image[l].push_back(static_cast<Real>(z));
    typename K::LayerView v;
    v.eye = typename K::vec3(0);
    v.forward = typename K::vec3(0, 0, 1);
    v.right = typename K::vec3(1, 0, 0);
    v.up = typename K::vec3(0, 1, 0);
    v.tan_half_fov = static_cast<Real>(s.tan_half_fov);
    v.near = static_cast<Real>(s.near);
    v.far = static_cast<Real>(s.far);
    v.size = s.size;
    std::vector<typename K::vec3> o, d;
    for (int n = 0; n < 4096; ++n) {
        TraceRay r = make_trace_ray(rng, s);
        o.push_back(to_vec3<Real>(r.origin));
        d.push_back(to_vec3<Real>(r.direction));
    }
    auto fetch = [&](int layer, int x, int y) { return image[layer][static_cast<std::size_t>(y * s.size + x)]; };
    std::size_t i = 0;
    long steps = 0, rays = 0;
    for (auto _ : state) {
        typename K::LayerSegment seg = K::layer_segment(v, o[i], d[i], Real(1000), typename K::vec2(0, K::bc_huge()));
        typename K::LayerHit h = trace_layers<Real>(v, seg, 2, Real(0.5), fetch);
        benchmark::DoNotOptimize(h.s);
        steps += h.steps;
        ++rays;
        i = (i + 1) & 4095;
    }
    state.counters["steps_per_ray"] = rays ? static_cast<double>(steps) / static_cast<double>(rays) : 0.0;
}

BENCHMARK(facet_classifier<float>)->Name("facet/float/classifier");
BENCHMARK(facet_brute_force<float>)->Name("facet/float/brute_force");
BENCHMARK(facet_classifier<double>)->Name("facet/double/classifier");
BENCHMARK(facet_brute_force<double>)->Name("facet/double/brute_force");
BENCHMARK(cluster_sphere<float>)->Name("cluster/float/sphere")->Unit(benchmark::kMicrosecond);
BENCHMARK(viewpoint_cluster<float>)->Name("viewpoint/float/cluster")->Unit(benchmark::kMicrosecond);
BENCHMARK(trace_ray<float>)->Name("trace/float/ray");
BENCHMARK(trace_ray<double>)->Name("trace/double/ray");

}  // namespace

int main(int argc, char** argv) {
    if (const char* fixed = std::getenv("BLURCULL_BENCH_FIXED"); fixed && *fixed == '1') {
        auto d = directions<float>();
        long a = fixed_classifier(d);
        long b = fixed_brute_force(d);
        std::printf("%zu directions; facet sums %ld (classifier), %ld (brute force)\n", d.size(), a, b);
        return 0;
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
