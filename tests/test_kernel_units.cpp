// Unit tests of the kernel's building blocks: the oracle against an
// independent ray-triangle intersection, the circle of confusion, the
// classifier, non-finite input and the sample pattern.
#include "kernel_generators.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <set>

using namespace blurcull;
using namespace blurcull::testing;
using Kf = kernel<float>;

namespace {

Kd::MovingTriangle static_triangle(Kd::vec3 a, Kd::vec3 b, Kd::vec3 c) {
    Kd::MovingTriangle tri;
    Kd::vec3 v[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
        tri.p[i] = tri.p[i + 3] = v[i];
        tri.c[i] = tri.c[i + 3] = Kd::vec2(0.0);
    }
    return tri;
}

// Independent reference: intersect the eye ray lambda (s, 1) with the sheared
// triangle by solving for barycentrics with Cramer's rule in long double.
// Returns -1 for a miss, else the hit depth lambda; `margin` reports how close
// to an edge the hit is (smallest barycentric).
long double reference_hit(const Kd::MovingTriangle& tri, Kd::vec2 s, Kd::vec2 uv, double t, long double& margin) {
    using L = long double;
    Kd::vec3 v[3];
    for (int i = 0; i < 3; ++i) v[i] = Kd::vertex_at(tri, i, t, uv);
    // lambda d = v0 + b1 (v1 - v0) + b2 (v2 - v0), d = (s, 1)
    L d[3] = {s.x, s.y, 1.0L};
    L e1[3], e2[3], o[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = L(v[1][k]) - L(v[0][k]);
        e2[k] = L(v[2][k]) - L(v[0][k]);
        o[k] = L(v[0][k]);
    }
    // Solve [d, -e1, -e2] (lambda, b1, b2) = o
    auto det3 = [](const L a[3], const L b[3], const L c[3]) {
        return a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1]) + c[0] * (a[1] * b[2] - a[2] * b[1]);
    };
    L ne1[3] = {-e1[0], -e1[1], -e1[2]};
    L ne2[3] = {-e2[0], -e2[1], -e2[2]};
    L den = det3(d, ne1, ne2);
    margin = 0;
    if (den == 0) return -1;
    L lambda = det3(o, ne1, ne2) / den;
    L b1 = det3(d, o, ne2) / den;
    L b2 = det3(d, ne1, o) / den;
    L b0 = 1 - b1 - b2;
    margin = std::min({b0, b1, b2});
    if (b0 < 0 || b1 < 0 || b2 < 0) return -1;
    return lambda;
}

}  // namespace

TEST_CASE("oracle agrees with an independent ray-triangle intersection") {
    Rng rng(42);
    int compared = 0, covered = 0, ambiguous = 0;
    for (int n = 0; n < 20000; ++n) {
        Family family = n % 3 == 0 ? Family::near_crossing : (n % 3 == 1 ? Family::both : Family::motion);
        Config cfg = make_config(rng, family);
        for (int k = 0; k < 8; ++k) {
            Sample5 smp = make_sample(rng, cfg);
            long double margin = 0;
            long double lambda = reference_hit(cfg.tri, smp.s, smp.uv, smp.t, margin);
            bool expected = lambda >= (long double)cfg.near;
            double depth = 0;
            bool got = Kd::covers(cfg.tri, smp.s, smp.uv, smp.t, cfg.near, depth);
            // Samples within rounding distance of an edge or of the near plane may go either way.
            if (std::fabs(double(margin)) < 1e-9 || std::fabs(double(lambda - (long double)cfg.near)) < 1e-9 * cfg.near) {
                ++ambiguous;
                continue;
            }
            ++compared;
            if (expected) ++covered;
            REQUIRE(got == expected);
            if (got) CHECK(depth == doctest::Approx(double(lambda)).epsilon(1e-9));
        }
    }
    MESSAGE("oracle: ", compared, " samples compared (", covered, " covered), ", ambiguous, " within rounding of an edge");
    CHECK(covered > 1000);
    CHECK(compared > 100000);
}

TEST_CASE("oracle: simple cases, behind the eye and the near plane") {
    // Triangle at depth 2 covering the screen centre.
    Kd::MovingTriangle tri = static_triangle({-1, -1, 2}, {1, -1, 2}, {0, 1, 2});
    double depth = 0;
    CHECK(Kd::covers(tri, {0.0, 0.0}, {0.0, 0.0}, 0.5, 0.1, depth));
    CHECK(depth == doctest::Approx(2.0));
    CHECK_FALSE(Kd::covers(tri, {0.9, 0.9}, {0.0, 0.0}, 0.5, 0.1, depth));
    // Winding does not matter.
    Kd::MovingTriangle flipped = static_triangle({1, -1, 2}, {-1, -1, 2}, {0, 1, 2});
    CHECK(Kd::covers(flipped, {0.0, 0.0}, {0.0, 0.0}, 0.5, 0.1, depth));
    // The same triangle entirely behind the eye projects onto the centre too,
    // but is not seen.
    Kd::MovingTriangle behind = static_triangle({1, 1, -2}, {-1, 1, -2}, {0, -1, -2});
    CHECK_FALSE(Kd::covers(behind, {0.0, 0.0}, {0.0, 0.0}, 0.5, 0.1, depth));
    // Closer than the near plane: not covered.
    CHECK_FALSE(Kd::covers(tri, {0.0, 0.0}, {0.0, 0.0}, 0.5, 2.5, depth));
    // One vertex behind the eye: the triangle spans to infinity on one side only.
    Kd::MovingTriangle crossing = static_triangle({-1, 0, 1}, {1, 0, 1}, {0, 1, -1});
    CHECK(Kd::covers(crossing, {0.0, 0.1}, {0.0, 0.0}, 0.5, 0.01, depth));
    CHECK(Kd::covers(crossing, {0.0, 5.0}, {0.0, 0.0}, 0.5, 0.01, depth));
    CHECK_FALSE(Kd::covers(crossing, {0.0, -0.1}, {0.0, 0.0}, 0.5, 0.01, depth));
    // Zero area: never covered.
    Kd::MovingTriangle line = static_triangle({-1, 0, 1}, {1, 0, 1}, {0, 0, 1});
    CHECK_FALSE(Kd::covers(line, {0.0, 0.0}, {0.0, 0.0}, 0.5, 0.01, depth));
}

// A triangle in a plane through the eye has det 0 exactly, but its float
// det is rounding of either sign; with the wrong one the edge tests accepted
// the triangle's image behind the eye, a line of "hits" far beyond it
// (docs/kernel.md, "The oracle's conditioning"). covers takes det and the
// edge values relative to the first vertex and declines such a triangle,
// while a sub-pixel triangle, whose float det taken from the vertices as
// they are was just as small next to their magnitudes, keeps its samples.
TEST_CASE("oracle: seen edge-on within rounding covers nothing, a sub-pixel triangle still covers") {
    // Triangles on planes y = k x + m w through the eye, their vertices
    // rounded to float (so off the plane by rounding only), scanned along the
    // plane's line on the screen, y = k x + m, far beyond their projection.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int accepted = 0, scanned = 0;
    for (int n = 0; n < 200; ++n) {
        const float k = unit(rng), m = unit(rng);
        Kf::MovingTriangle edge_on;
        for (int i = 0; i < 3; ++i) {
            const float x = 2.0f * unit(rng), w = 2.0f + unit(rng);
            edge_on.p[i] = edge_on.p[i + 3] = Kf::vec3(x, k * x + m * w, w);
            edge_on.c[i] = edge_on.c[i + 3] = Kf::vec2(0.0f);
        }
        for (int i = -200; i <= 200; ++i) {
            const float sx = 0.05f * float(i);
            for (int j = -2; j <= 2; ++j) {
                float depth = 0.0f;
                const Kf::vec2 s(sx, k * sx + m + 1e-6f * float(j));
                ++scanned;
                if (Kf::covers(edge_on, s, Kf::vec2(0.0f), 0.5f, 0.01f, depth)) ++accepted;
            }
        }
    }
    CAPTURE(scanned);
    CHECK(accepted == 0);
    // A triangle 1e-3 NDC across (half a pixel at 1024 wide) at w = 5, off
    // centre: v0 . (v1 x v2) is about 1e-6 of the vertices' magnitudes, under
    // 32 eps of them, yet far above det's rounding taken relative to v0.
    const Kf::vec2 centre(0.3f, -0.2f);
    const float depth_w = 5.0f, size = 1e-3f;
    const Kf::vec2 corner[3] = {{0.0f, 0.0f}, {size, 0.0f}, {0.0f, size}};
    Kf::MovingTriangle tiny;
    for (int i = 0; i < 3; ++i) {
        const Kf::vec2 p = (centre + corner[i]) * depth_w;
        tiny.p[i] = tiny.p[i + 3] = Kf::vec3(p.x, p.y, depth_w);
        tiny.c[i] = tiny.c[i + 3] = Kf::vec2(0.0f);
    }
    float depth = 0.0f;
    const Kf::vec2 inside = centre + Kf::vec2(size / 3.0f);
    CHECK(Kf::covers(tiny, inside, Kf::vec2(0.0f), 0.5f, 0.01f, depth));
    // det / sum: both cancel to about 1e-6 of their terms, so the float
    // depth of a triangle this small is off by about 0.3% (4.986).
    CHECK(depth == doctest::Approx(5.0f).epsilon(1e-2));
    CHECK_FALSE(Kf::covers(tiny, centre + Kf::vec2(size), Kf::vec2(0.0f), 0.5f, 0.01f, depth));
}

TEST_CASE("oracle: motion and lens move the triangle as the model says") {
    Kd::MovingTriangle tri = static_triangle({-0.1, -0.1, 1}, {0.1, -0.1, 1}, {0, 0.1, 1});
    for (int i = 0; i < 3; ++i) tri.p[i + 3] = tri.p[i] + Kd::vec3(1.0, 0.0, 0.0);
    double depth = 0;
    CHECK(Kd::covers(tri, {0.0, 0.0}, {0.0, 0.0}, 0.0, 0.1, depth));
    CHECK_FALSE(Kd::covers(tri, {0.0, 0.0}, {0.0, 0.0}, 1.0, 0.1, depth));
    CHECK(Kd::covers(tri, {0.5, 0.0}, {0.0, 0.0}, 0.5, 0.1, depth));
    // Lens shear: c = 0.5 shifts the triangle by u c / w in x.
    Kd::MovingTriangle lens = static_triangle({-0.1, -0.1, 1}, {0.1, -0.1, 1}, {0, 0.1, 1});
    for (int j = 0; j < 6; ++j) lens.c[j] = Kd::vec2(0.5, 0.25);
    CHECK(Kd::covers(lens, {0.5, 0.0}, {1.0, 0.0}, 0.0, 0.1, depth));
    CHECK_FALSE(Kd::covers(lens, {0.5, 0.0}, {-1.0, 0.0}, 0.0, 0.1, depth));
    CHECK(Kd::covers(lens, {0.0, 0.25}, {0.0, 1.0}, 0.0, 0.1, depth));
}

TEST_CASE_TEMPLATE("thin-lens circle of confusion", Real, float, double) {
    using K = kernel<Real>;
    typename K::vec2 ab = K::thin_lens_coc(Real(2), Real(0.1), Real(5));
    CHECK(K::coc_at(ab, Real(5)) == doctest::Approx(0.0));
    CHECK(K::coc_at(ab, Real(0)) == doctest::Approx(-0.2));
    CHECK(K::coc_at(ab, Real(10)) == doctest::Approx(0.2));
    // Controllable defocus: zero inside the in-focus range, continuous at its edge, clamped.
    CHECK(K::coc_controlled(ab, Real(5.4), Real(0.5), Real(1)) == Real(0));
    CHECK(K::coc_controlled(ab, Real(4.6), Real(0.5), Real(1)) == Real(0));
    CHECK(K::coc_controlled(ab, Real(5.5), Real(0.5), Real(1)) == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(K::coc_controlled(ab, Real(10), Real(0.5), Real(1)) == doctest::Approx(0.2 - 0.02));
    CHECK(K::coc_controlled(ab, Real(0), Real(0.5), Real(1)) == doctest::Approx(-(0.2 - 0.02)));
    CHECK(K::coc_controlled(ab, Real(100), Real(0), Real(0.5)) == doctest::Approx(0.5));
    CHECK(K::coc_controlled(ab, Real(0), Real(0), Real(0.1)) == doctest::Approx(-0.1));
}

TEST_CASE_TEMPLATE("classify says what a triangle needs", Real, float, double) {
    using K = kernel<Real>;
    typename K::MovingTriangle tri = to_real<Real>(static_triangle({-1, -1, 2}, {1, -1, 2}, {0, 1, 2}));
    CHECK(K::classify(tri) == 0);
    typename K::MovingTriangle moving = tri;
    moving.p[4].x += Real(0.25);
    CHECK(K::classify(moving) == BC_NEEDS_MOTION);
    typename K::MovingTriangle blurred = tri;
    for (int j = 0; j < 6; ++j) blurred.c[j] = typename K::vec2(Real(0.01));
    CHECK(K::classify(blurred) == BC_NEEDS_DEFOCUS);
    blurred.p[3].z += Real(1);
    CHECK(K::classify(blurred) == (BC_NEEDS_MOTION | BC_NEEDS_DEFOCUS));
}

TEST_CASE_TEMPLATE("NaN and Inf input: documented fallback, never a cull", Real, float, double) {
    using K = kernel<Real>;
    const Real bad[] = {std::numeric_limits<Real>::quiet_NaN(), std::numeric_limits<Real>::infinity(),
                        -std::numeric_limits<Real>::infinity()};
    Rng rng(7);
    for (Real value : bad) {
        for (int where = 0; where < 30; ++where) {
            typename K::MovingTriangle tri = to_real<Real>(make_config(rng, Family::both).tri);
            int j = where % 6;
            switch (where / 6) {
                case 0: tri.p[j].x = value; break;
                case 1: tri.p[j].y = value; break;
                case 2: tri.p[j].z = value; break;
                case 3: tri.c[j].x = value; break;
                default: tri.c[j].y = value; break;
            }
            CHECK(K::classify(tri) == BC_INVALID);
            for (int method : all_methods) {
                typename K::ScreenBound sb = K::screen_bound(tri, Real(0.05), method);
                CHECK_FALSE(sb.empty);
                CHECK(K::screen_contains(sb, typename K::vec2(Real(0.3), Real(-0.7))));
                typename K::SampleBounds b =
                    K::sample_bounds(tri, typename K::vec2(Real(0.1)), typename K::vec2(Real(0.11)), method);
                CHECK(K::sample_passes(b, typename K::vec2(Real(0.5), Real(-0.5)), Real(0.5)));
                CHECK(K::sample_passes(b, typename K::vec2(Real(-1), Real(1)), Real(1)));
            }
            Real depth = 0;
            CHECK_FALSE(K::covers(tri, typename K::vec2(Real(0)), typename K::vec2(Real(0)), Real(0.5), Real(0.05), depth));
        }
    }
    // A non-positive near plane is a caller error: no cull either.
    typename K::MovingTriangle tri = to_real<Real>(static_triangle({-1, -1, 2}, {1, -1, 2}, {0, 1, 2}));
    CHECK(K::screen_contains(K::screen_bound(tri, Real(0), BC_CULL_BBOX), typename K::vec2(Real(50), Real(50))));
}

TEST_CASE_TEMPLATE("screen bound: box of a static triangle, empty behind the near plane", Real, float, double) {
    using K = kernel<Real>;
    typename K::MovingTriangle tri = to_real<Real>(static_triangle({-1, -1, 2}, {1, -1, 2}, {0, 1, 2}));
    typename K::ScreenBound sb = K::screen_bound(tri, Real(0.1), BC_CULL_BBOX);
    CHECK(sb.lo.x == doctest::Approx(-0.5).epsilon(1e-4));  // widened by the margins
    CHECK(sb.hi.x == doctest::Approx(0.5).epsilon(1e-4));
    CHECK(sb.hi.y == doctest::Approx(0.5).epsilon(1e-4));
    CHECK_FALSE(K::screen_contains(sb, typename K::vec2(Real(0.6), Real(0))));
    typename K::ScreenBound hull = K::screen_bound(tri, Real(0.1), BC_CULL_HULL);
    CHECK(hull.hull_count == 3);
    CHECK(K::screen_contains(hull, typename K::vec2(Real(0), Real(0))));
    CHECK_FALSE(K::screen_contains(hull, typename K::vec2(Real(0.45), Real(0.45))));  // in the box, not the hull
    typename K::ScreenBound gone = K::screen_bound(tri, Real(3), BC_CULL_BBOX);
    CHECK(gone.empty);
}

TEST_CASE_TEMPLATE("sample pattern: deterministic, stratified, in range", Real, float, double) {
    using K = kernel<Real>;
    for (std::uint32_t spp : {1u, 4u, 16u, 32u}) {
        for (std::uint32_t px = 0; px < 6; ++px) {
            std::set<int> time_strata, cells;
            std::uint32_t n = 1;
            while ((n + 1) * (n + 1) <= spp) ++n;
            for (std::uint32_t j = 0; j < spp; ++j) {
                typename K::PixelSample s = K::pixel_sample(px, 3u, j, spp, 9u);
                typename K::PixelSample again = K::pixel_sample(px, 3u, j, spp, 9u);
                CHECK(s.time == again.time);
                CHECK(s.offset == again.offset);
                CHECK(s.time >= Real(0));
                CHECK(s.time < Real(1));
                CHECK(s.offset.x >= Real(0));
                CHECK(s.offset.x < Real(1));
                CHECK(s.offset.y >= Real(0));
                CHECK(s.offset.y < Real(1));
                CHECK(s.lens.x * s.lens.x + s.lens.y * s.lens.y <= Real(1) + Real(1e-6));
                time_strata.insert(int(s.time * Real(spp)));
                if (j < n * n) cells.insert(int(s.offset.x * Real(n)) + int(n) * int(s.offset.y * Real(n)));
            }
            CHECK(time_strata.size() == spp);  // one sample per time stratum
            CHECK(cells.size() == n * n);       // one sample per position stratum
        }
    }
    // Float and double draw the same samples.
    typename K::PixelSample s = K::pixel_sample(11u, 5u, 3u, 16u, 2u);
    kernelf::PixelSample f = kernelf::pixel_sample(11u, 5u, 3u, 16u, 2u);
    CHECK(double(s.time) == doctest::Approx(double(f.time)).epsilon(1e-6));
    CHECK(double(s.lens.x) == doctest::Approx(double(f.lens.x)).epsilon(1e-5));
    // Another seed gives other samples.
    CHECK(K::pixel_sample(11u, 5u, 3u, 16u, 3u).time != s.time);
}

TEST_CASE_TEMPLATE("footprint screen state and time range agree with the per-sample tests", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(99);
    std::size_t inside = 0, outside = 0, checked = 0;
    for (int n = 0; n < 4000; ++n) {
        Family family = all_families()[std::size_t(n) % all_families().size()];
        Config cfg = make_config(rng, family);
        typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
        // A footprint near the triangle, sometimes well off it.
        typename K::vec2 lo(cfg.s_lo), hi(cfg.s_hi);
        if (n % 3 == 0) {
            typename K::vec2 shift(Real(rng.signed_unit() * 0.2), Real(rng.signed_unit() * 0.2));
            lo += shift;
            hi += shift;
        }
        for (int method : all_methods) {
            typename K::ScreenBound sb = K::screen_bound(tri, Real(cfg.near), method);
            typename K::SampleBounds b = K::sample_bounds(tri, lo, hi, method);
            int state = K::screen_footprint(sb, lo, hi);
            typename K::vec2 range = K::sample_time_range(b);
            inside += state == BC_FOOTPRINT_INSIDE;
            outside += state == BC_FOOTPRINT_OUTSIDE;
            for (int k = 0; k < 16; ++k) {
                typename K::vec2 s(Real(rng.uniform(double(lo.x), double(hi.x))), Real(rng.uniform(double(lo.y), double(hi.y))));
                s = glm::clamp(s, lo, hi);
                typename K::vec2 uv(Real(rng.signed_unit()), Real(rng.signed_unit()));
                Real t = Real(rng.uniform());
                bool on_screen = K::screen_contains(sb, s);
                if (state == BC_FOOTPRINT_OUTSIDE) REQUIRE_FALSE(on_screen);
                if (state == BC_FOOTPRINT_INSIDE) REQUIRE(on_screen);
                if (K::sample_passes(b, uv, t)) {
                    REQUIRE(t >= range.x);
                    REQUIRE(t <= range.y);
                }
                ++checked;
            }
        }
    }
    MESSAGE(checked, " samples; footprints inside ", inside, ", outside ", outside);
    CHECK(inside > 100);
    CHECK(outside > 100);
}

// ---- the sampler's own arithmetic (sampling_body.inl; docs/glsl.md, "The GPU
// arithmetic model"): + - * and exact operations only, so that every GPU draws
// the host's samples. These pin its accuracy against the C++ library.
namespace {

using Kf = kernel<float>;
using Pf = patterns<float>;

std::int64_t float_order(float f) {
    std::int32_t i = 0;
    std::memcpy(&i, &f, sizeof i);
    return i < 0 ? -std::int64_t(i & 0x7fffffff) : std::int64_t(i);
}

std::int64_t ulps_apart(float a, float b) { return std::llabs(float_order(a) - float_order(b)); }

float float_of_bits(std::uint32_t bits) {
    float f = 0.0f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

}  // namespace

TEST_CASE("sampler arithmetic: bc_div is correctly rounded") {
    std::mt19937 rng(20261204u);
    std::uniform_real_distribution<float> unit(0.5f, 1.0f);
    long inputs = 0, wrong = 0;
    const auto check = [&](float a, float b) {
        ++inputs;
        if (Kf::bc_div(a, b) != a / b) {
            if (++wrong <= 5) MESSAGE("bc_div(" << a << ", " << b << ") = " << Kf::bc_div(a, b) << ", a / b = " << a / b);
        }
    };
    // Random signs and exponents over 2^-40 .. 2^40.
    for (int i = 0; i < 1000000; ++i) {
        const float a = std::ldexp(unit(rng), int(rng() % 80u) - 40) * (rng() & 1u ? 1.0f : -1.0f);
        const float b = std::ldexp(unit(rng), int(rng() % 80u) - 40) * (rng() & 1u ? 1.0f : -1.0f);
        check(a, b);
    }
    // The sampler's quotients: lens ratios of 2^-12 grids, strata (c + u) / n, 1 / base.
    for (int ky = -4096; ky <= 4096; ky += 5)
        for (int kx = 1; kx <= 4096; kx += 11) check(float(ky) * 0x1p-12f, float(kx) * 0x1p-12f);
    for (unsigned n = 1; n <= 16; ++n)
        for (unsigned u = 0; u < (1u << 24); u += 4099u) check(float(7u % n) + float(u) * 0x1p-24f, float(n));
    for (unsigned base = 2; base < 64; ++base) check(1.0f, float(base));
    check(0.0f, 3.0f);
    check(2.0f * 1023.0f, 1024.0f);
    MESSAGE("bc_div: " << inputs << " quotients, " << wrong << " not correctly rounded");
    CHECK(wrong == 0);
    CHECK(std::signbit(Kf::bc_div(-0.0f, 3.0f)) == std::signbit(-0.0f / 3.0f));
    // double: within one ulp (the tests of the float path are the exact claim).
    for (int i = 0; i < 100000; ++i) {
        const double a = std::ldexp(double(unit(rng)) + 1e-9 * double(i % 97), int(rng() % 80u) - 40);
        const double b = std::ldexp(double(unit(rng)), int(rng() % 80u) - 40);
        REQUIRE(std::fabs(Kd::bc_div(a, b) - a / b) <= std::fabs(a / b) * 2.3e-16);
    }
}

TEST_CASE("sampler arithmetic: bc_sqrt is correctly rounded") {
    long inputs = 0, wrong = 0;
    const auto check = [&](float x) {
        ++inputs;
        if (Kf::bc_sqrt(x) != std::sqrt(x)) {
            if (++wrong <= 5) MESSAGE("bc_sqrt(" << x << ") = " << Kf::bc_sqrt(x) << ", std::sqrt = " << std::sqrt(x));
        }
    };
    // Every float of [0.25, 4) (both parities of the exponent, every significand),
    // a stride over the whole normal range, and the edges.
    for (std::uint32_t bits = 0x3e800000u; bits < 0x40800000u; bits += 3u) check(float_of_bits(bits));
    for (std::uint32_t bits = 0x00800000u; bits < 0x7f800000u; bits += 997u) check(float_of_bits(bits));
    for (float x : {1.0f, 4.0f, 0.25f, 2.0f, 0.5f, std::numeric_limits<float>::min(), std::numeric_limits<float>::max(),
                    1.0f - std::numeric_limits<float>::epsilon(), 1.0f + std::numeric_limits<float>::epsilon()})
        check(x);
    MESSAGE("bc_sqrt: " << inputs << " inputs, " << wrong << " not correctly rounded");
    CHECK(wrong == 0);
    CHECK(Kf::bc_sqrt(0.0f) == 0.0f);
    CHECK(Kf::bc_sqrt(-1.0f) == 0.0f);  // documented: 0 for x <= 0
    for (double x : {2.0, 0.3, 1e-30, 7e40})
        CHECK(std::fabs(Kd::bc_sqrt(x) - std::sqrt(x)) <= std::sqrt(x) * 2.3e-16);
}

TEST_CASE("sampler arithmetic: the quarter-circle cos/sin within 2 ulp, never above 1") {
    std::int64_t worst_cos = 0, worst_sin = 0;
    for (int i = -(1 << 18); i <= (1 << 18); ++i) {
        const float t = float(i) * 0x1p-18f;
        const Kf::vec2 cs = Kf::bc_cos_sin_quarter_pi(t);
        const double angle = double(t) * 0.78539816339744830961566;
        worst_cos = std::max(worst_cos, ulps_apart(cs.x, float(std::cos(angle))));
        worst_sin = std::max(worst_sin, ulps_apart(cs.y, float(std::sin(angle))));
        REQUIRE(std::fabs(cs.x) <= 1.0f);
        REQUIRE(std::fabs(cs.y) <= 1.0f);
    }
    MESSAGE("cos: " << worst_cos << " ulp, sin: " << worst_sin << " ulp from the correctly rounded values");
    CHECK(worst_cos <= 2);
    CHECK(worst_sin <= 2);
    CHECK(Kf::bc_cos_sin_quarter_pi(0.0f) == Kf::vec2(1.0f, 0.0f));
    // double: its own series, to a few ulp.
    for (double t : {-1.0, -0.3, 0.1, 0.5, 1.0}) {
        CHECK(std::fabs(Kd::bc_cos_sin_quarter_pi(t).x - std::cos(t * 0.78539816339744830961566)) <= 1e-15);
        CHECK(std::fabs(Kd::bc_cos_sin_quarter_pi(t).y - std::sin(t * 0.78539816339744830961566)) <= 1e-15);
    }
}

TEST_CASE("sampler arithmetic: the concentric map stays in the unit disk and near the cos/sin one") {
    std::mt19937 rng(7u);
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const Kf::vec2 q(float(rng() >> 8) * 0x1p-24f, float(rng() >> 8) * 0x1p-24f);
        const Kf::vec2 d = Kf::bc_square_to_disk(q);
        REQUIRE(double(d.x) * double(d.x) + double(d.y) * double(d.y) <= 1.0 + 1e-6);
        REQUIRE(std::fabs(d.x) <= 1.0f);
        REQUIRE(std::fabs(d.y) <= 1.0f);
        // Shirley and Chiu's map in double.
        const double ax = 2.0 * double(q.x) - 1.0, ay = 2.0 * double(q.y) - 1.0;
        double x = 0.0, y = 0.0;
        if (std::fabs(ax) > std::fabs(ay)) {
            x = ax * std::cos(0.78539816339744830961566 * ay / ax);
            y = ax * std::sin(0.78539816339744830961566 * ay / ax);
        } else if (ay != 0.0) {
            x = ay * std::sin(0.78539816339744830961566 * ax / ay);
            y = ay * std::cos(0.78539816339744830961566 * ax / ay);
        }
        worst = std::max({worst, std::fabs(double(d.x) - x), std::fabs(double(d.y) - y)});
    }
    MESSAGE("concentric map: at most " << worst << " from the exact map");
    CHECK(worst <= 3e-7);
    // The polar map of the interleaved tuples: radius and angle as promised.
    for (int k = 0; k < 4000; ++k) {
        const float r2 = float(k % 97) / 97.0f, turn = float(k) / 4000.0f;
        const Kf::vec2 d = Pf::bc_polar_disk(r2, turn);
        const double angle = 6.283185307179586 * double(turn);
        REQUIRE(std::fabs(double(d.x) - std::sqrt(double(r2)) * std::cos(angle)) <= 3e-7);
        REQUIRE(std::fabs(double(d.y) - std::sqrt(double(r2)) * std::sin(angle)) <= 3e-7);
    }
}
