// The limit of time-interval culling, measured (docs/benchmarks.md, "The limit").
//
// For a footprint and a lens position (u, v), the best any bound that gives a
// time interval per lens position can do is the hull of the times at which the
// sheared triangle at (u, v) meets the footprint's frustum (x and y jointly,
// in front of the near plane). A sample outside that hull is never covered;
// inside it, any such bound must keep it. The methods here also test each
// sample's screen position against a per-triangle screen bound (at best the
// convex hull, BC_CULL_HULL's), so the limit keeps that test too:
//   STE_limit = covered / samples inside the screen hull whose t lies in the time hull at their (u, v),
// and every method's STE can be given as a fraction of it. The methods are
// judged by sample_passes_at (each sample at its own position): the edge
// bound then keeps the sample's position in its planes, which makes it more
// than a time interval per lens position, so it can pass the limit; the
// column "edges/fp" is the same bound over the whole footprint
// (sample_passes), a time-interval bound again. Run over the
// kernel generators' families (tests/kernel_generators.hpp), each footprint
// made one pixel of a 1024-wide screen, the same configurations and samples
// for every method:
//   build/bench/bench_limit [configs per family, default 4000] [samples per config, default 64]
//
// The hull is found numerically: the triangle is clipped against the frustum
// (near plane and the footprint's four side planes) at 129 times inside the
// two-stage bounds' time interval at (u, v), and each end of the first-to-last
// hit range is refined by bisection against its missing neighbour. A hit
// range narrower than 1/128 of that interval between two missing grid times
// is missed (the limit is then a little optimistic; the last column counts
// covered samples outside the hull found); zero-area positions (det = 0,
// which the oracle never covers) do not count as hits.
#include "kernel_generators.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using namespace blurcull;
using namespace blurcull::testing;

using V3 = Kd::vec3;

constexpr double kPixel = 2.0 / 1024.0;

// Whether the triangle at (uv, t) meets {w >= near, s_lo w <= (x, y) <= s_hi w}:
// Sutherland-Hodgman against the five planes, in double.
bool meets_frustum(const Kd::MovingTriangle& tri, Kd::vec2 uv, double t, Kd::vec2 s_lo, Kd::vec2 s_hi, double near) {
    V3 poly[16];
    int n = 3;
    for (int i = 0; i < 3; ++i) poly[i] = Kd::vertex_at(tri, i, t, uv);
    if (Kd::bc_dot3(poly[0], Kd::cross(poly[1], poly[2])) == 0.0) return false;
    // plane(p) >= 0 inside: w - near, x - lo.x w, hi.x w - x, y - lo.y w, hi.y w - y
    for (int plane = 0; plane < 5 && n > 0; ++plane) {
        auto f = [&](const V3& p) {
            switch (plane) {
                case 0: return p.z - near;
                case 1: return p.x - s_lo.x * p.z;
                case 2: return s_hi.x * p.z - p.x;
                case 3: return p.y - s_lo.y * p.z;
                default: return s_hi.y * p.z - p.y;
            }
        };
        V3 out[16];
        int m = 0;
        for (int k = 0; k < n; ++k) {
            const V3& a = poly[k];
            const V3& b = poly[(k + 1) % n];
            double fa = f(a), fb = f(b);
            if (fa >= 0.0) out[m++] = a;
            if ((fa >= 0.0) != (fb >= 0.0)) out[m++] = a + (b - a) * (fa / (fa - fb));
        }
        n = m;
        for (int k = 0; k < n; ++k) poly[k] = out[k];
    }
    return n > 0;
}

// The hull [lo, hi] of the times at which the triangle at uv meets the
// footprint's frustum; lo > hi when it never does. Searched inside the
// two-stage time lines at uv (which never cull a covered sample: the property
// tests), so a fast triangle's short crossing still spans many grid steps.
Kd::vec2 exact_time_hull(const Config& cfg, const Kd::SampleBounds& two_stage, Kd::vec2 uv) {
    constexpr int kSteps = 128;
    const Kd::SampleBounds& b = two_stage;
    if (b.empty || uv.x < b.u_range.x || uv.x > b.u_range.y || uv.y < b.v_range.x || uv.y > b.v_range.y)
        return Kd::vec2(1.0, 0.0);
    double t0 = std::max({0.0, b.u_time_a.x + b.u_time_a.y * uv.x, b.u_time_b.x + b.u_time_b.y * uv.x,
                          b.v_time_a.x + b.v_time_a.y * uv.y, b.v_time_b.x + b.v_time_b.y * uv.y});
    double t1 = std::min({1.0, b.u_time_a.z + b.u_time_a.w * uv.x, b.u_time_b.z + b.u_time_b.w * uv.x,
                          b.v_time_a.z + b.v_time_a.w * uv.y, b.v_time_b.z + b.v_time_b.w * uv.y});
    t0 = std::max(0.0, t0 - 1e-9);
    t1 = std::min(1.0, t1 + 1e-9);
    if (t0 > t1) return Kd::vec2(1.0, 0.0);
    auto at = [&](int k) { return k == kSteps ? t1 : t0 + (t1 - t0) * double(k) / kSteps; };
    auto hit = [&](double t) { return meets_frustum(cfg.tri, uv, t, cfg.s_lo, cfg.s_hi, cfg.near); };
    int first = -1, last = -1;
    for (int k = 0; k <= kSteps; ++k) {
        if (hit(at(k))) {
            if (first < 0) first = k;
            last = k;
        }
    }
    if (first < 0) return Kd::vec2(1.0, 0.0);
    auto refine = [&](double miss, double in) {
        for (int it = 0; it < 40; ++it) {
            double mid = 0.5 * (miss + in);
            (hit(mid) ? in : miss) = mid;
        }
        return in;
    };
    double lo = first == 0 ? at(0) : refine(at(first - 1), at(first));
    double hi = last == kSteps ? at(kSteps) : refine(at(last + 1), at(last));
    return Kd::vec2(lo, hi);
}

struct Row {
    std::uint64_t samples = 0, covered = 0, in_hull = 0, covered_outside_hull = 0;
    std::uint64_t passed[method_count] = {};
    std::uint64_t passed_edges_footprint = 0;  // BC_CULL_EDGES by sample_passes (position unknown)
};

Row run_family(Family family, int configs, int samples, std::uint64_t seed) {
    Rng rng(seed);
    Row row;
    for (int c = 0; c < configs; ++c) {
        Config cfg = make_config(rng, family);
        // One pixel of a 1024-wide screen around the anchor: the limit is per
        // pixel, and a tile's bound would be judged against the screen test too.
        Kd::vec2 offset(rng.uniform(), rng.uniform());
        cfg.s_lo = cfg.anchor - offset * kPixel;
        cfg.s_hi = cfg.s_lo + Kd::vec2(kPixel);
        Kd::ScreenBound screen[method_count];
        Kd::SampleBounds bounds[method_count];
        for (int m : all_methods) {
            screen[m] = Kd::screen_bound(cfg.tri, cfg.near, m);
            bounds[m] = Kd::sample_bounds(cfg.tri, cfg.s_lo, cfg.s_hi, m);
        }
        for (int n = 0; n < samples; ++n) {
            Sample5 smp = make_sample(rng, cfg);
            Kd::vec2 s = glm::clamp(smp.s, cfg.s_lo, cfg.s_hi);
            double depth = 0.0;
            bool covered = Kd::covers(cfg.tri, s, smp.uv, smp.t, cfg.near, depth);
            Kd::vec2 hull = exact_time_hull(cfg, bounds[BC_CULL_TWO_STAGE], smp.uv);
            bool inside = smp.t >= hull.x && smp.t <= hull.y && Kd::screen_contains(screen[BC_CULL_HULL], s);
            ++row.samples;
            row.covered += covered;
            row.in_hull += inside;
            row.covered_outside_hull += covered && !inside;
            for (int m : all_methods)
                row.passed[m] += Kd::screen_contains(screen[m], s) && Kd::sample_passes_at(bounds[m], s, smp.uv, smp.t);
            row.passed_edges_footprint += Kd::screen_contains(screen[BC_CULL_EDGES], s) &&
                                          Kd::sample_passes(bounds[BC_CULL_EDGES], smp.uv, smp.t);
        }
    }
    return row;
}

double ste(std::uint64_t covered, std::uint64_t passed) { return passed ? 100.0 * double(covered) / double(passed) : 0.0; }

}  // namespace

int main(int argc, char** argv) {
    int configs = argc > 1 ? std::atoi(argv[1]) : 4000;
    int samples = argc > 2 ? std::atoi(argv[2]) : 64;
    std::printf("STE (%%) per family, double bounds, %d configurations x %d samples; limit = covered / samples "
                "inside the exact time hull at their (u, v); in brackets each method's STE as a fraction of it\n",
                configs, samples);
    std::printf("%-14s %9s", "family", "covered");
    for (int m : all_methods) std::printf(" %16s", method_name(m));
    std::printf(" %16s %8s %s\n", "edges/fp", "limit", "(covered outside the hull)");
    std::uint64_t seed = 0x1e7e0000;
    for (Family f : all_families()) {
        Row row = run_family(f, configs, samples, ++seed);
        double limit = ste(row.covered, row.in_hull);
        std::printf("%-14s %9" PRIu64, family_name(f), row.covered);
        for (int m : all_methods) {
            double v = ste(row.covered, row.passed[m]);
            std::printf("  %5.1f (%5.1f%%)", v, limit > 0.0 ? 100.0 * v / limit : 0.0);
        }
        double fp = ste(row.covered, row.passed_edges_footprint);
        std::printf("  %5.1f (%5.1f%%)", fp, limit > 0.0 ? 100.0 * fp / limit : 0.0);
        std::printf(" %8.1f (%" PRIu64 ")\n", limit, row.covered_outside_hull);
        std::fflush(stdout);
    }
    return 0;
}
