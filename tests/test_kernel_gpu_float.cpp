// The GPU arithmetic emulation itself (tests/gpu_float.hpp): each operation
// stays inside what the model permits, the adversarial modes reach both ends
// of it, and with rounding to nearest and no flushing kernel<gpu_float> is
// kernel<float> bit for bit (so the emulation's plumbing through GLM and the
// kernel adds nothing of its own).
#include "gpu_float.hpp"  // first: its glm overloads must precede kernel.hpp
#include "kernel_generators.hpp"

#include <doctest/doctest.h>

#include <cfloat>
#include <cmath>
#include <cstring>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

using G = gpu_float;

// The ULP of the binade holding the exact value q.
long double ulp_of(long double q) {
    q = std::fabs(q);
    if (q < (long double)FLT_MIN) return std::ldexp(1.0L, -149);
    int e = 0;
    std::frexp(q, &e);  // q = m 2^e, m in [0.5, 1)
    return std::ldexp(1.0L, e - 1 - 23);
}

// |r - a / b| in ULPs of a / b, without dividing: r b - a is exact in long
// double (48 + 24 bits of a 64-bit significand, exponents in range).
long double division_error_ulps(float r, float a, float b) {
    const long double q = (long double)a / (long double)b;
    return std::fabs((long double)r * (long double)b - (long double)a) / std::fabs((long double)b) / ulp_of(q);
}

float random_float(Rng& rng, int min_exp, int max_exp) {
    const double m = rng.uniform(1.0, 2.0) * (rng.chance(0.5) ? 1.0 : -1.0);
    return float(std::ldexp(m, min_exp + rng.below(max_exp - min_exp + 1)));
}

std::int64_t ulps_between(float a, float b) {
    auto ord = [](float x) {
        std::int32_t i;
        std::memcpy(&i, &x, sizeof i);
        return i >= 0 ? std::int64_t(i) : -std::int64_t(i & 0x7fffffff);
    };
    return ord(a) - ord(b);
}

}  // namespace

TEST_CASE("gpu_float: the limits and exact operations are float's") {
    CHECK(std::numeric_limits<G>::is_iec559);
    CHECK(std::numeric_limits<G>::epsilon().v == FLT_EPSILON);
    CHECK(std::numeric_limits<G>::max().v == FLT_MAX);
    CHECK(std::numeric_limits<G>::min().v == FLT_MIN);
    GpuArithmeticScope arithmetic(GpuRounding::random, 1);
    Rng rng(7);
    for (int n = 0; n < 100000; ++n) {
        const float a = random_float(rng, -60, 60), b = random_float(rng, -60, 60);
        const G x(a), y(b);
        // M1: + - * correctly rounded (no denormal in sight here).
        CHECK((x + y).v == a + b);
        CHECK((x - y).v == a - b);
        CHECK((x * y).v == a * b);
        // M5: exact comparisons and built-ins.
        CHECK((x < y) == (a < b));
        CHECK(glm::min(x, y).v == std::min(a, b));
        CHECK(glm::abs(x).v == std::fabs(a));
        CHECK(glm::floor(x).v == std::floor(a));
    }
}

TEST_CASE("gpu_float: division within 2.5 ULP, both ends reached") {
    Rng rng(11);
    long double worst = 0.0L;
    int low_end = 0, high_end = 0, both_ends_seen = 0, cases = 0;
    for (int n = 0; n < 20000; ++n) {
        const float a = random_float(rng, -60, 60), b = random_float(rng, -60, 60);  // quotients in the normal range
        G lo_r, hi_r;
        {
            GpuArithmeticScope s(GpuRounding::low, 1, false, 0.0);
            lo_r = G(a) / G(b);
        }
        {
            GpuArithmeticScope s(GpuRounding::high, 1, false, 0.0);
            hi_r = G(a) / G(b);
        }
        // The ends are within 2.5 ULP and the next float beyond is not.
        CHECK(division_error_ulps(lo_r.v, a, b) <= 2.5L);
        CHECK(division_error_ulps(hi_r.v, a, b) <= 2.5L);
        CHECK(division_error_ulps(std::nextafter(lo_r.v, -INFINITY), a, b) > 2.5L);
        CHECK(division_error_ulps(std::nextafter(hi_r.v, INFINITY), a, b) > 2.5L);
        CHECK(lo_r.v <= a / b);
        CHECK(hi_r.v >= a / b);
        // Random: always inside [low, high]; over 64 draws both ends appear.
        GpuArithmeticScope s(GpuRounding::random, 0x1234 + std::uint64_t(n), false, 0.0);
        bool saw_lo = false, saw_hi = false;
        for (int k = 0; k < 64; ++k) {
            const G r = G(a) / G(b);
            worst = std::max(worst, division_error_ulps(r.v, a, b));
            CHECK(r.v >= lo_r.v);
            CHECK(r.v <= hi_r.v);
            saw_lo = saw_lo || r.v == lo_r.v;
            saw_hi = saw_hi || r.v == hi_r.v;
        }
        low_end += saw_lo;
        high_end += saw_hi;
        both_ends_seen += saw_lo && saw_hi;
        ++cases;
    }
    MESSAGE("division: worst error ", double(worst), " ULP; random mode reached the low end in ", low_end, " and the high end in ",
            high_end, " of ", cases, " quotients");
    CHECK(worst <= 2.5L);
    CHECK(worst > 2.0L);
    CHECK(both_ends_seen > cases * 9 / 10);
}

TEST_CASE("gpu_float: division by |b| > 2^126 may give 0") {
    const float a = 0x1p122f, b = 0x1.8p127f;
    {
        GpuArithmeticScope s(GpuRounding::low, 1, false, 0.0);
        CHECK((G(a) / G(b)).v == 0.0f);
        CHECK((G(-a) / G(b)).v < 0.0f);  // the low end of a negative quotient is its own
    }
    {
        GpuArithmeticScope s(GpuRounding::high, 1, false, 0.0);
        CHECK((G(a) / G(b)).v > 0.0f);
        CHECK((G(-a) / G(b)).v == 0.0f);
    }
    GpuArithmeticScope s(GpuRounding::random, 5, false, 0.0);
    int zeros = 0;
    for (int k = 0; k < 1000; ++k) {
        const G r = G(a) / G(b);
        if (r.v == 0.0f) ++zeros;
        else CHECK(division_error_ulps(r.v, a, b) <= 2.5L);
    }
    CHECK(zeros > 100);
    CHECK(zeros < 900);
}

TEST_CASE("gpu_float: sqrt within 4 ULP of the rounded root, inversesqrt within 2 ULP") {
    Rng rng(13);
    GpuArithmeticScope s(GpuRounding::random, 17, false, 0.0);
    std::int64_t worst = 0;
    bool saw_lo = false, saw_hi = false;
    for (int n = 0; n < 100000; ++n) {
        const float a = std::fabs(random_float(rng, -120, 120));
        const float r = glm::sqrt(G(a)).v;
        const std::int64_t d = ulps_between(r, std::sqrt(a));
        worst = std::max<std::int64_t>(worst, d < 0 ? -d : d);
        saw_lo = saw_lo || d == -4;
        saw_hi = saw_hi || d == 4;
        const long double exact = 1.0L / std::sqrt((long double)a);
        CHECK(std::fabs((long double)glm::inversesqrt(G(a)).v - exact) <= 2.0L * ulp_of(exact));
    }
    CHECK(worst == 4);
    CHECK(saw_lo);
    CHECK(saw_hi);
}

TEST_CASE("gpu_float: denormal inputs and results flushed to either zero") {
    const float tiny = FLT_MIN / 8.0f;  // denormal
    {
        GpuArithmeticScope s(GpuRounding::nearest, 1, false, 0.0);
        CHECK((G(tiny) + G(tiny)).v == tiny + tiny);
        CHECK((G(FLT_MIN) * G(0.25f)).v == FLT_MIN * 0.25f);
    }
    GpuArithmeticScope s(GpuRounding::nearest, 3, false, 1.0);
    int negative = 0;
    for (int k = 0; k < 200; ++k) {
        const G sum = G(tiny) + G(1.0f);  // the input flushed: exactly 1
        CHECK(sum.v == 1.0f);
        const G product = G(FLT_MIN) * G(0.25f);  // a denormal result: flushed
        CHECK(product.v == 0.0f);
        negative += std::signbit(product.v);
    }
    CHECK(negative > 20);  // either sign
    CHECK(negative < 180);
}

TEST_CASE("gpu_float: fused mode rounds a*b+c once, some of the time") {
    const float a = 1.0f + 0x1p-12f;  // a * a = 1 + 2^-11 + 2^-24 exactly
    GpuArithmeticScope s(GpuRounding::nearest, 9, true, 0.0);
    int fused = 0, unfused = 0;
    for (int k = 0; k < 200; ++k) {
        const G r = G(a) * G(a) - G(1.0f);
        if (r.v == 0x1p-11f + 0x1p-24f) ++fused;
        else if (r.v == (a * a) - 1.0f) ++unfused;
        else FAIL("neither fused nor unfused: ", double(r.v));
    }
    CHECK(fused > 20);
    CHECK(unfused > 20);
}

TEST_CASE("gpu_float: kernel<gpu_float> rounding to nearest without flushing is kernel<float> bit for bit") {
    using K = kernel<G>;
    using Kf = kernel<float>;
    GpuArithmeticScope s(GpuRounding::nearest, 1, false, 0.0);
    Rng rng(19);
    int covered = 0, compared = 0;
    for (int n = 0; n < 400; ++n) {
        const Config cfg = make_config(rng, all_families()[std::size_t(n) % all_families().size()]);
        const Kf::MovingTriangle tf = to_real<float>(cfg.tri);
        K::MovingTriangle tg;
        for (int j = 0; j < 6; ++j) {
            tg.p[j] = K::vec3(G(tf.p[j].x), G(tf.p[j].y), G(tf.p[j].z));
            tg.c[j] = K::vec2(G(tf.c[j].x), G(tf.c[j].y));
        }
        const float near = float(cfg.near);
        const Kf::vec2 lo(cfg.s_lo), hi(cfg.s_hi);
        const K::vec2 glo(G(lo.x), G(lo.y)), ghi(G(hi.x), G(hi.y));
        for (int m : all_methods) {
            const Kf::ScreenBound a = Kf::screen_bound(tf, near, m);
            const K::ScreenBound b = K::screen_bound(tg, G(near), m);
            CHECK(a.lo.x == b.lo.x.v);
            CHECK(a.hi.y == b.hi.y.v);
            CHECK(a.hull_count == b.hull_count);
            for (int k = 0; k < a.hull_count; ++k) CHECK(a.hull_edge[k].z == b.hull_edge[k].z.v);
            const Kf::SampleBounds c = Kf::sample_bounds(tf, lo, hi, m);
            const K::SampleBounds d = K::sample_bounds(tg, glo, ghi, m);
            CHECK(c.empty == d.empty);
            CHECK(c.u_range.x == d.u_range.x.v);
            CHECK(c.u_time_a.z == d.u_time_a.z.v);
            CHECK(c.v_time_b.x == d.v_time_b.x.v);
        }
        for (int k = 0; k < 16; ++k) {
            const Sample5 smp = make_sample(rng, cfg);
            const Kf::vec2 sf(smp.s), uvf(smp.uv);
            const float tf_ = float(smp.t);
            float depth_f = 0.0f;
            G depth_g(0);
            const bool cf = Kf::covers(tf, sf, uvf, tf_, near, depth_f);
            const bool cg = K::covers(tg, K::vec2(G(sf.x), G(sf.y)), K::vec2(G(uvf.x), G(uvf.y)), G(tf_), G(near), depth_g);
            CHECK(cf == cg);
            CHECK(depth_f == depth_g.v);
            covered += cf;
            ++compared;
        }
    }
    MESSAGE(compared, " samples compared, ", covered, " covered");
    CHECK(covered > 100);
}
