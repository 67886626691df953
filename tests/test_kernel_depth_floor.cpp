// depth_floor_scale and depth_floor (screen_bound_body.inl), the lower bound
// on the depth covers() gives a covered sample that lets the CPU backend skip
// samples already nearer than a triangle can be: every covered sample's
// depth, as covers computes it in float and in double, is at least the floor
// of its time range. The samples are where rounding decides: on the
// triangle's edges and vertices (a point of the sheared triangle projected,
// a few units in the last place beside), on the property generators'
// families and on triangles seen nearly edge-on, where the computed depth
// of a covered sample can lie far below every vertex's depth. Not vacuous:
// many covered samples, most floors above zero, and the floor without its
// rounding terms (the smallest vertex depth) is exceeded on the edge-on set.
#include "kernel_generators.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

struct Tally {
    std::uint64_t ranges = 0, floored = 0, covered = 0, below = 0, below_vertex_depth = 0;
};

template <class Real>
Real nudged(Rng& rng, double x) {
    Real r = static_cast<Real>(x);
    for (int k = rng.below(9) - 4; k != 0; k += k > 0 ? -1 : 1)
        r = std::nextafter(r, k > 0 ? std::numeric_limits<Real>::infinity() : -std::numeric_limits<Real>::infinity());
    return r;
}

// A screen position on the sheared triangle at (uv, t): a point with random
// barycentric coordinates (often on an edge or a vertex) projected, nudged a
// few units in the last place; or a point of the configuration's footprint.
template <class Real>
typename kernel<Real>::vec2 sample_position(const Config& cfg, const Kd::MovingTriangle& tri, Rng& rng,
                                            typename kernel<Real>::vec2 uv, Real t) {
    using vec2 = typename kernel<Real>::vec2;
    if (rng.chance(0.25))
        return vec2(static_cast<Real>(rng.uniform(cfg.s_lo.x, cfg.s_hi.x)),
                    static_cast<Real>(rng.uniform(cfg.s_lo.y, cfg.s_hi.y)));
    double b[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
    if (rng.chance(0.5)) b[rng.below(3)] = 0.0;     // on an edge
    if (rng.chance(0.2)) b[rng.below(3)] = 0.0;     // often a vertex
    const double sum = b[0] + b[1] + b[2];
    if (!(sum > 0.0)) b[0] = 1.0;
    Kd::vec3 p(0.0);
    for (int i = 0; i < 3; ++i) p += (b[i] / (sum > 0.0 ? sum : 1.0)) * Kd::vertex_at(tri, i, double(t), Kd::vec2(uv));
    if (!(p.z > 0.0)) return vec2(Real(0));
    return vec2(nudged<Real>(rng, p.x / p.z), nudged<Real>(rng, p.y / p.z));
}

// A triangle seen nearly edge-on: its plane passes within `gap` of the eye
// (the origin of clip space) at some lens position, so det is small against
// its terms and covers' depth is ill-conditioned.
Config edge_on_config(Rng& rng) {
    Config cfg;
    const double gap = rng.log_uniform(1e-14, 1e-2);
    for (int end = 0; end < 2; ++end) {
        const bool moves = end == 1 && rng.chance(0.5);
        const int from = end * 3;
        if (end == 1 && !moves) {
            for (int i = 0; i < 3; ++i) cfg.tri.p[3 + i] = cfg.tri.p[i];
        } else {
            const Kd::vec3 p0(rng.signed_unit() * 3.0, rng.signed_unit() * 3.0, rng.uniform(0.5, 20.0));
            const Kd::vec3 side(rng.signed_unit(), rng.signed_unit(), rng.signed_unit() * 0.5);
            // The second side nearly along the ray from the eye through p0.
            const Kd::vec3 jitter(rng.signed_unit(), rng.signed_unit(), rng.signed_unit());
            const Kd::vec3 along = p0 * rng.uniform(0.05, 0.8) + jitter * gap * glm::length(p0);
            cfg.tri.p[from + 0] = p0;
            cfg.tri.p[from + 1] = p0 + side;
            cfg.tri.p[from + 2] = p0 + along;
        }
    }
    const bool defocus = rng.chance(0.5);
    for (int j = 0; j < 6; ++j) {
        const double w = cfg.tri.p[j].z;
        const double c = defocus ? 0.02 * (1.0 - w / 5.0) : 0.0;
        cfg.tri.c[j] = Kd::vec2(c, c);
    }
    cfg.near = 0.05;
    cfg.s_lo = Kd::vec2(-1.0);
    cfg.s_hi = Kd::vec2(1.0);
    return cfg;
}

template <class Real>
void check_config(const Config& cfg, const char* family, Rng& rng, Tally& tally) {
    using K = kernel<Real>;
    using vec2 = typename K::vec2;
    const typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
    const Kd::MovingTriangle tri_d = to_double<Real>(tri);
    const Real near = static_cast<Real>(cfg.near);
    // The scale over a box of time and lens (often the whole shutter and
    // lens, as the CPU backend takes it), floors over sub-ranges of its time.
    const bool whole = rng.chance(0.5);
    const vec2 time = whole ? vec2(0, 1) : vec2(sub_range(rng, 0.0, 1.0));
    const vec2 u = whole ? vec2(-1, 1) : vec2(sub_range(rng, -1.0, 1.0));
    const vec2 v = whole ? vec2(-1, 1) : vec2(sub_range(rng, -1.0, 1.0));
    const Real extent = static_cast<Real>(std::max({1.0, std::abs(cfg.s_lo.x), std::abs(cfg.s_lo.y),
                                                    std::abs(cfg.s_hi.x), std::abs(cfg.s_hi.y)}));
    const Real scale = K::depth_floor_scale(tri, time, u, v, extent);
    CHECK(scale >= Real(0));
    CHECK(scale <= Real(1));
    for (int q = 0; q < 3; ++q) {
        const vec2 range(sub_range(rng, double(time.x), double(time.y)));
        const Real floor = K::depth_floor(tri, range, scale);
        // The smallest vertex depth over the range: the floor without its rounding terms.
        const Real vertex_depth = K::depth_floor(tri, range, Real(1));
        ++tally.ranges;
        if (floor > Real(0)) ++tally.floored;
        for (int n = 0; n < 40; ++n) {
            const vec2 uv(static_cast<Real>(value_or_end(rng, double(u.x), double(u.y), 6)),
                          static_cast<Real>(value_or_end(rng, double(v.x), double(v.y), 6)));
            const Real t = static_cast<Real>(value_or_end(rng, double(range.x), double(range.y), 6));
            if (uv.x < u.x || uv.x > u.y || uv.y < v.x || uv.y > v.y || t < range.x || t > range.y) continue;
            const vec2 s = sample_position<Real>(cfg, tri_d, rng, uv, t);
            if (!(std::abs(s.x) <= extent && std::abs(s.y) <= extent)) continue;
            Real depth = Real(0);
            if (!K::covers(tri, s, uv, t, near, depth)) continue;
            ++tally.covered;
            if (depth < vertex_depth) ++tally.below_vertex_depth;
            if (depth < floor) {
                if (tally.below < 5)
                    std::printf("depth floor above a covered sample's depth: %s floor=%.17g depth=%.17g "
                                "s=(%.9g, %.9g) uv=(%.9g, %.9g) t=%.9g\n",
                                family, double(floor), double(depth), double(s.x), double(s.y), double(uv.x),
                                double(uv.y), double(t));
                ++tally.below;
            }
        }
    }
}

template <class Real>
void check_all(const char* precision) {
    Tally families, edge_on;
    const int configs = static_cast<int>(1500 * property_scale());
    for (Family family : all_families()) {
        Rng rng(0xf100ull * 1013 + static_cast<std::uint64_t>(family));
        for (int c = 0; c < configs; ++c) check_config<Real>(make_config(rng, family), family_name(family), rng, families);
    }
    Rng rng(0xed9e0ull);
    for (int c = 0; c < 6 * configs; ++c) check_config<Real>(edge_on_config(rng), "edge_on", rng, edge_on);
    for (const Tally* t : {&families, &edge_on}) {
        std::printf("depth floor %-6s %-9s ranges %llu floored %llu covered %llu below the floor %llu "
                    "below the smallest vertex depth %llu\n",
                    precision, t == &families ? "families" : "edge-on", static_cast<unsigned long long>(t->ranges),
                    static_cast<unsigned long long>(t->floored), static_cast<unsigned long long>(t->covered),
                    static_cast<unsigned long long>(t->below), static_cast<unsigned long long>(t->below_vertex_depth));
        CHECK(t->below == 0);
        CHECK(double(t->covered) > 20000 * property_scale());
    }
    // Many ranges get a floor that can skip something (in double most; float's
    // rounding terms leave small or thin triangles without one).
    CHECK(families.floored > families.ranges / (sizeof(Real) == 8 ? 2 : 4));
    // Edge-on triangles are where the floor needs its rounding terms: their
    // computed depths fall below the smallest vertex depth.
    CHECK(edge_on.below_vertex_depth > 0);
}

}  // namespace

TEST_CASE("depth floor: no covered sample's depth lies below it, double") { check_all<double>("double"); }

TEST_CASE("depth floor: no covered sample's depth lies below it, float") { check_all<float>("float"); }
