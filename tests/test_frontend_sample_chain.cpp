// The CPU backend's many-sample chain (render/cpu/sample_chain.hpp) against
// the kernel's sample_culled one sample at a time: on the property
// generators' triangles and footprints, every culling method, samples drawn
// at random and samples placed on the bounds' own edges (a bound's value
// rounded to float and its neighbours), the masks must be equal bit for bit.
#include "kernel_generators.hpp"
#include "render/cpu/sample_chain.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

// A value next to `edge`: the float nearest it or one of its neighbours.
float near_edge(Rng& rng, double edge) {
    float f = static_cast<float>(edge);
    const int steps = static_cast<int>(rng.uniform(0.0, 3.0)) - 1;
    for (int i = 0; i < std::abs(steps); ++i) f = std::nextafter(f, steps > 0 ? 2.0f : -2.0f);
    return f;
}

// edges: a time next to the end of one of the planes' shutter pieces
// (where the piece lookup changes), else t.
template <class Bounds>
float near_piece_end(Rng& rng, const Bounds& edges, float t) {
    if (edges.piece[0].mode == BC_EDGE_NONE) return t;
    const int q = static_cast<int>(rng.uniform(0.0, double(edges.pieces) + 1.0));
    if (q == 0) return near_edge(rng, double(edges.piece[0].time.x));
    return near_edge(rng, double(edges.piece[std::min(q, edges.pieces) - 1].time.y));
}

// edges: the lens u (next to the value) where one edge plane of t's piece
// is zero at the sample (its hi or, two-sided, its lo side), else u.
template <class Bounds>
float on_edge_plane(Rng& rng, const Bounds& edges, float sx, float sy, float u, float v, float t) {
    if (edges.piece[0].mode == BC_EDGE_NONE) return u;
    int q = 0;
    while (q + 1 < edges.pieces && double(t) > double(edges.piece[q].time.y)) ++q;
    const auto& p = edges.piece[q];
    const int e = static_cast<int>(rng.uniform(0.0, 3.0)) % 3;
    if (p.du[e] == 0) return u;
    const double side = rng.uniform(0.0, 1.0) < 0.5 ? double(p.hi[e]) : double(p.lo[e]);
    const double rest = double(p.dv[e]) * v + double(p.dt[e]) * t + double(p.dx[e]) * sx + double(p.dy[e]) * sy + side;
    const double at = -rest / double(p.du[e]);
    return std::isfinite(at) && std::abs(at) <= 1.0 ? near_edge(rng, at) : u;
}

struct Counts {
    std::uint64_t samples = 0, passed = 0, mismatches = 0;
};

template <class Real>
void check_config(const Config& cfg, int method, Rng& rng, Counts& counts) {
    using K = kernel<Real>;
    const typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
    const typename K::ScreenBound screen = K::screen_bound(tri, static_cast<Real>(cfg.near), method);
    const typename K::vec2 lo(cfg.s_lo), hi(cfg.s_hi);
    const typename K::SampleBounds bounds = K::sample_bounds(tri, lo, hi, method);
    frontend::SampleLanes lanes(32);
    for (int i = 0; i < 32; ++i) {
        const Sample5 s = make_sample(rng, cfg);
        float sx = float(s.s.x), sy = float(s.s.y), u = float(s.uv.x), v = float(s.uv.y), t = float(s.t);
        // Two thirds of the samples sit on an edge of the bounds (edges: on a
        // plane or at a piece's end).
        switch (static_cast<int>(rng.uniform(0.0, 12.0))) {
            case 0: u = near_edge(rng, double(bounds.u_range.x)); break;
            case 1: v = near_edge(rng, double(bounds.v_range.y)); break;
            case 2: t = near_edge(rng, double(bounds.u_time_a.x + bounds.u_time_a.y * Real(u))); break;
            case 3: t = near_edge(rng, double(bounds.v_time_b.z + bounds.v_time_b.w * Real(v))); break;
            case 4: sx = near_edge(rng, double(screen.lo.x)); break;
            case 5: sy = near_edge(rng, double(screen.hi.y)); break;
            case 6: t = near_piece_end(rng, bounds.edges, t); break;
            case 7: u = on_edge_plane(rng, bounds.edges, sx, sy, u, v, t); break;
            default: break;
        }
        lanes.set(static_cast<std::size_t>(i), sx, sy, u, v, t);
    }
    for (bool check_screen : {true, false}) {
        const int count = 1 + static_cast<int>(rng.uniform(0.0, 32.0)) % 32;
        const std::uint32_t fast = frontend::samples_passing<Real>(screen, check_screen, bounds, lanes, 0, count);
        const std::uint32_t one = frontend::samples_passing_scalar<Real>(screen, check_screen, bounds, lanes, 0, count);
        counts.samples += static_cast<std::uint64_t>(count);
        counts.passed += static_cast<std::uint64_t>(__builtin_popcount(one));
        if (fast != one) ++counts.mismatches;
        // The screen-only chain against the kernel with no lens or time bounds.
        const std::uint32_t screen_only = frontend::samples_passing_screen<Real>(screen, check_screen, lanes, 0, count);
        const std::uint32_t unbounded =
            frontend::samples_passing_scalar<Real>(screen, check_screen, K::no_sample_bounds(), lanes, 0, count);
        if (screen_only != unbounded) ++counts.mismatches;
    }
}

template <class Real>
void check_all(const char* precision) {
    const int configs = static_cast<int>(400 * property_scale());
    for (int method : all_methods) {
        Counts counts;
        for (Family family : all_families()) {
            Rng rng(0xc4a1ull * 131 + static_cast<std::uint64_t>(family) * 17 + static_cast<std::uint64_t>(method));
            for (int c = 0; c < configs; ++c) check_config<Real>(make_config(rng, family), method, rng, counts);
        }
        std::printf("sample chain %-6s %-9s samples %8llu passed %8llu mismatches %llu\n", precision,
                    method_name(method), static_cast<unsigned long long>(counts.samples),
                    static_cast<unsigned long long>(counts.passed), static_cast<unsigned long long>(counts.mismatches));
        CHECK_MESSAGE(counts.mismatches == 0, method_name(method));
        // Not vacuous: some samples pass and some are culled.
        CHECK(counts.passed > 0);
        CHECK(counts.passed < counts.samples);
    }
}

}  // namespace

TEST_CASE("sample chain: the many-sample masks are the kernel's sample_culled, double") {
    check_all<double>("double");
}

TEST_CASE("sample chain: the many-sample masks are the kernel's sample_culled, float") {
    check_all<float>("float");
}

TEST_CASE("sample chain: a box bound by hand") {
    using K = kerneld;
    K::ScreenBound screen{};
    screen.empty = false;
    screen.lo = K::vec2(-0.5, -0.5);
    screen.hi = K::vec2(0.5, 0.5);
    screen.hull_count = 0;
    K::SampleBounds bounds = K::no_sample_bounds();
    bounds.u_range = K::vec2(0.0, 1.0);
    frontend::SampleLanes lanes(8);
    lanes.set(0, 0.0f, 0.0f, 0.5f, 0.0f, 0.5f);   // passes
    lanes.set(1, 0.0f, 0.0f, -0.5f, 0.0f, 0.5f);  // lens outside
    lanes.set(2, 0.7f, 0.0f, 0.5f, 0.0f, 0.5f);   // screen outside
    lanes.set(3, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f);   // on the edges: passes
    lanes.set(4, 0.0f, 0.0f, 0.5f, 0.0f, 0.5f);   // beyond count
    CHECK(frontend::samples_passing<double>(screen, true, bounds, lanes, 0, 4) == 0b1001u);
    CHECK(frontend::samples_passing<double>(screen, false, bounds, lanes, 0, 4) == 0b1101u);
    bounds.empty = true;
    CHECK(frontend::samples_passing<double>(screen, true, bounds, lanes, 0, 4) == 0u);
}
