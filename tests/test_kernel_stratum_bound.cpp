// stratum_screen_box (screen_bound_body.inl), the screen box of the samples
// in one stratum of shutter and lens that the CPU backend tests a stratum's
// samples in: every sample of the stratum that the double oracle covers lies
// inside it, on the property generators' families, float and double, for the
// CPU backend's strata (equal time slices by lens halves) and for random
// sub-ranges, with samples often on the strata's ends and beside a vertex. Not vacuous: many
// covered samples, and the box is often smaller than the whole-shutter box.
#include "kernel_generators.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

struct Tally {
    std::uint64_t strata = 0, narrowed = 0, samples = 0, covered = 0, outside = 0;
};

// A value in [lo, hi]: an end (chance 1/6 each) or uniform between.
double in_range(Rng& rng, double lo, double hi) { return value_or_end(rng, lo, hi, 6); }

// A screen position at or a few units in the last place beside the
// projection of a vertex at (uv, t): where the box's sides are decided.
template <class Real>
typename kernel<Real>::vec2 near_vertex(const Kd::MovingTriangle& tri, Rng& rng, typename kernel<Real>::vec2 uv, Real t) {
    const Kd::vec3 p = Kd::vertex_at(tri, rng.below(3), double(t), Kd::vec2(uv));
    if (!(p.z > 0.0)) return typename kernel<Real>::vec2(Real(0));
    auto nudge = [&](double x) {
        Real r = static_cast<Real>(x);
        for (int k = rng.below(7) - 3; k != 0; k += k > 0 ? -1 : 1)
            r = std::nextafter(r, k > 0 ? std::numeric_limits<Real>::infinity() : -std::numeric_limits<Real>::infinity());
        return r;
    };
    return typename kernel<Real>::vec2(nudge(p.x / p.z), nudge(p.y / p.z));
}

template <class Real>
void check_config(const Config& cfg, Family family, Rng& rng, Tally& tally) {
    using K = kernel<Real>;
    using vec2 = typename K::vec2;
    const typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
    const Kd::MovingTriangle tri_d = to_double<Real>(tri);
    const Real near = static_cast<Real>(cfg.near);
    const typename K::ScreenBound whole = K::screen_bound(tri, near, BC_CULL_HULL);
    for (int q = 0; q < 4; ++q) {
        const vec2 time(sub_range(rng, 0.0, 1.0)), u(sub_range(rng, -1.0, 1.0)), v(sub_range(rng, -1.0, 1.0));
        const typename K::vec4 b = K::stratum_screen_box(tri, near, whole, time, u, v);
        ++tally.strata;
        if (b.x <= b.z && !whole.empty && (b.x > whole.lo.x || b.z < whole.hi.x || b.y > whole.lo.y || b.w < whole.hi.y))
            ++tally.narrowed;
        for (int n = 0; n < 48; ++n) {
            vec2 s(static_cast<Real>(in_range(rng, cfg.s_lo.x, cfg.s_hi.x)),
                   static_cast<Real>(in_range(rng, cfg.s_lo.y, cfg.s_hi.y)));
            const vec2 uv(static_cast<Real>(in_range(rng, double(u.x), double(u.y))),
                          static_cast<Real>(in_range(rng, double(v.x), double(v.y))));
            const Real t = static_cast<Real>(in_range(rng, double(time.x), double(time.y)));
            if (n % 2 == 1) s = near_vertex<Real>(tri_d, rng, uv, t);
            if (uv.x < u.x || uv.x > u.y || uv.y < v.x || uv.y > v.y || t < time.x || t > time.y) continue;
            ++tally.samples;
            double depth = 0.0;
            if (!Kd::covers(tri_d, Kd::vec2(s), Kd::vec2(uv), double(t), double(near), depth)) continue;
            ++tally.covered;
            if (!(s.x >= b.x && s.x <= b.z && s.y >= b.y && s.y <= b.w)) {
                if (tally.outside < 5)
                    std::printf("stratum bound culls a covered sample: %s s=(%.9g, %.9g) uv=(%.9g, %.9g) t=%.9g\n",
                                family_name(family), double(s.x), double(s.y), double(uv.x), double(uv.y),
                                double(t));
                ++tally.outside;
            }
        }
    }
}

template <class Real>
void check_all(const char* precision) {
    Tally tally;
    const int configs = static_cast<int>(1500 * property_scale());
    for (Family family : all_families()) {
        Rng rng(0x57a7ull * 1013 + static_cast<std::uint64_t>(family));
        for (int c = 0; c < configs; ++c) check_config<Real>(make_config(rng, family), family, rng, tally);
    }
    std::printf("stratum bound %-6s strata %llu narrowed %llu samples %llu covered %llu outside %llu\n", precision,
                static_cast<unsigned long long>(tally.strata), static_cast<unsigned long long>(tally.narrowed),
                static_cast<unsigned long long>(tally.samples), static_cast<unsigned long long>(tally.covered),
                static_cast<unsigned long long>(tally.outside));
    CHECK(tally.outside == 0);
    CHECK(double(tally.covered) > 60000 * property_scale());
    CHECK(tally.narrowed > tally.strata / 4);
}

}  // namespace

TEST_CASE("stratum bound: every covered sample of a stratum lies in its box, double") { check_all<double>("double"); }

TEST_CASE("stratum bound: every covered sample of a stratum lies in its box, float") { check_all<float>("float"); }
