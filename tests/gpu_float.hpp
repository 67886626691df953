// gpu_float: a host emulation of the GPU arithmetic model (issue 22,
// docs/glsl.md; the model M1-M5 of the gpu-* work) as a scalar type for
// kernel<gpu_float>, so that the property, stress and fuzz families can ask
// whether the kernel stays conservative on any conformant GPU: no sample that
// kernel<gpu_float>::covers accepts may be culled by a kernel<gpu_float> bound.
//
// It stores a binary32 and rounds every operation as a GLSL 4.50 GPU may:
//   M1  + - *    correctly rounded (the host's float with -ffp-contract=off;
//                x86-64 without -mfma emits no fused multiply-add). With
//                fuse on (a GPU that ignores `precise`), a product keeps its
//                exact rounding error and the next + or - that consumes it
//                may fuse (a*b+c rounded once), at random.
//   M2  a / b    any float within 2.5 ULP of the exact quotient, picked by
//                the rounding mode; for |b| > 2^126 also +-0 (NVIDIA's
//                reciprocal flushes).
//   M3  sqrt     within 4 ULP of the correctly rounded root; inversesqrt
//                within 2 ULP of the exact value; sin, cos, exp, log, pow
//                (undefined precision) off by up to 2^-11 relative (plus
//                2^-11 absolute for sin and cos), so any dependence shows.
//   M4  any denormal input or result of an arithmetic operation, division or
//       root is flushed to zero of either sign, at random (flush_chance).
//   M5  comparisons, min, max, abs, floor, ceil, clamp, conversions: exact.
//
// The choices come from a seeded splitmix64 stream per thread
// (gpu_arithmetic()), so a run is reproducible. Modes: nearest (the host's
// float exactly: the emulation itself tested against kernel<float>), random
// (uniform in the permitted set), low and high (always its lowest or highest
// member).
//
// A test-only type, not under include/: an engine has no use for a scalar
// that rounds at random, and keeping it here keeps kernel.hpp's promise that
// kernel<Real> is float or double.
//
// Include this header before <blurcull/kernel.hpp> (or anything that
// includes it): kernel<Real>'s built-ins forward to glm::sqrt, glm::floor,
// ..., and the overloads for gpu_float below must be declared before the
// kernel's template is defined, as GLM's own are.
#pragma once

#include <glm/glm.hpp>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace blurcull::testing {

enum class GpuRounding { nearest, random, low, high };

// The emulation's settings and its random stream, one per thread.
struct GpuArithmetic {
    GpuRounding mode = GpuRounding::random;
    double flush_chance = 0.5;  // chance that a denormal input or result becomes +-0
    bool fuse = false;          // fuse a product into the + or - that consumes it (at random)
    std::uint64_t state = 0x6770755f666c6f61ull;
    // Counters for the emulation's own tests.
    std::uint64_t divisions = 0;
    std::uint64_t flushes = 0;
    std::uint64_t fused = 0;

    std::uint64_t next() {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    bool chance(double p) { return uniform() < p; }
};

inline GpuArithmetic& gpu_arithmetic() {
    thread_local GpuArithmetic settings;
    return settings;
}

// Sets the mode and reseeds the stream for the scope's lifetime, then restores.
class GpuArithmeticScope {
public:
    GpuArithmeticScope(GpuRounding mode, std::uint64_t seed, bool fuse = false, double flush_chance = 0.5)
        : saved_(gpu_arithmetic()) {
        GpuArithmetic& a = gpu_arithmetic();
        a.mode = mode;
        a.state = seed;
        a.fuse = fuse;
        a.flush_chance = flush_chance;
    }
    ~GpuArithmeticScope() { gpu_arithmetic() = saved_; }
    GpuArithmeticScope(const GpuArithmeticScope&) = delete;
    GpuArithmeticScope& operator=(const GpuArithmeticScope&) = delete;

private:
    GpuArithmetic saved_;
};

namespace gpu_detail {

inline bool denormal(float x) { return x != 0.0f && std::fabs(x) < FLT_MIN; }

// M4: a denormal becomes +-0 (either sign) with the configured chance.
// The test is inlined, the draw is not (every operation calls this twice).
[[gnu::noinline]] inline float flush_denormal(float x) {
    GpuArithmetic& a = gpu_arithmetic();
    if (a.flush_chance <= 0.0 || !a.chance(a.flush_chance)) return x;
    ++a.flushes;
    return (a.next() & 1u) ? 0.0f : -0.0f;
}
[[gnu::always_inline]] inline float flush(float x) { return denormal(x) ? flush_denormal(x) : x; }

// Floats as ordered integers (monotonic in value, -0 and +0 adjacent), for
// picking uniformly among consecutive floats.
inline std::int64_t ordered(float x) {
    std::int32_t i;
    std::memcpy(&i, &x, sizeof i);
    return i >= 0 ? std::int64_t(i) : -std::int64_t(i & 0x7fffffff) - 1;
}
inline float from_ordered(std::int64_t k) {
    std::int32_t i = k >= 0 ? std::int32_t(k) : std::int32_t((-(k + 1)) | 0x80000000ll);
    float x;
    std::memcpy(&x, &i, sizeof x);
    return x;
}

// One of the floats lo..hi (consecutive, lo <= hi) by the mode.
inline float pick(float lo, float nearest, float hi) {
    GpuArithmetic& a = gpu_arithmetic();
    switch (a.mode) {
        case GpuRounding::nearest: return nearest;
        case GpuRounding::low: return lo;
        case GpuRounding::high: return hi;
        case GpuRounding::random: break;
    }
    const std::int64_t l = ordered(lo), h = ordered(hi);
    return from_ordered(l + std::int64_t(a.next() % std::uint64_t(h - l + 1)));
}

// The unit in the last place of a float at the exact value q (q's binade;
// 2^-149 in the denormal range).
inline long double ulp_at(long double q) {
    q = std::fabs(q);
    if (q < (long double)FLT_MIN) return std::ldexp(1.0L, -149);
    return std::ldexp(1.0L, std::ilogb(q) - 23);
}

// The floats within `ulps` ULP of the exact value q: [lo, hi] around the
// rounded r.
inline void within(long double q, float r, long double ulps, float& lo, float& hi) {
    const long double bound = ulps * ulp_at(q);
    lo = r;
    hi = r;
    for (;;) {
        float down = std::nextafter(lo, -std::numeric_limits<float>::infinity());
        if (!(std::fabs((long double)down - q) <= bound)) break;
        lo = down;
    }
    for (;;) {
        float up = std::nextafter(hi, std::numeric_limits<float>::infinity());
        if (!(std::fabs((long double)up - q) <= bound)) break;
        hi = up;
    }
}

// Relative perturbation up to `rel` (and absolute `abs_err`) by the mode:
// the transcendentals, whose precision GLSL leaves undefined.
inline float perturb(double r, double rel, double abs_err) {
    GpuArithmetic& a = gpu_arithmetic();
    double d = 0.0;
    switch (a.mode) {
        case GpuRounding::nearest: return float(r);
        case GpuRounding::low: d = -1.0; break;
        case GpuRounding::high: d = 1.0; break;
        case GpuRounding::random: d = 2.0 * a.uniform() - 1.0; break;
    }
    return float(r + d * (rel * std::fabs(r) + abs_err));
}

}  // namespace gpu_detail

struct gpu_float {
    // Trivial (GLM keeps its components in unions): uninitialised until
    // assigned, like float. Every operation sets both members.
    float v;
    // With fusing on: the exact rounding error of the product that made v
    // (0 otherwise), which the next + or - may fold in (a*b+c rounded once).
    float residual;

    gpu_float() = default;
    template <class T, class = std::enable_if_t<std::is_arithmetic_v<T>>>
    constexpr explicit gpu_float(T x) : v(static_cast<float>(x)), residual(0.0f) {}
    template <class T, class = std::enable_if_t<std::is_arithmetic_v<T>>>
    constexpr explicit operator T() const {
        return static_cast<T>(v);
    }

    [[gnu::always_inline]] static gpu_float raw(float x) {
        gpu_float r;
        r.v = x;
        r.residual = 0.0f;
        return r;
    }

    friend gpu_float operator-(gpu_float a) {
        gpu_float r = raw(-a.v);
        r.residual = -a.residual;
        return r;
    }
    friend gpu_float operator+(gpu_float a) { return a; }

    [[gnu::always_inline]] friend gpu_float operator+(gpu_float a, gpu_float b) { return add(a, b); }
    [[gnu::always_inline]] friend gpu_float operator-(gpu_float a, gpu_float b) { return add(a, -b); }
    [[gnu::always_inline]] friend gpu_float operator*(gpu_float a, gpu_float b) {
        const float x = gpu_detail::flush(a.v), y = gpu_detail::flush(b.v);
        const float p = x * y;
        gpu_float r = raw(gpu_detail::flush(p));
        if (fusing() && r.v == p && std::isfinite(p)) {
            r.residual = float(double(x) * double(y) - double(p));  // exact (TwoProduct), barring underflow
        }
        return r;
    }
    friend gpu_float operator/(gpu_float a, gpu_float b) { return divide(a, b); }

    gpu_float& operator+=(gpu_float b) { return *this = *this + b; }
    gpu_float& operator-=(gpu_float b) { return *this = *this - b; }
    gpu_float& operator*=(gpu_float b) { return *this = *this * b; }
    gpu_float& operator/=(gpu_float b) { return *this = *this / b; }

    // M5: exact comparisons (NaN compares false, as in GLSL on every GPU we model).
    friend bool operator==(gpu_float a, gpu_float b) { return a.v == b.v; }
    friend bool operator!=(gpu_float a, gpu_float b) { return a.v != b.v; }
    friend bool operator<(gpu_float a, gpu_float b) { return a.v < b.v; }
    friend bool operator<=(gpu_float a, gpu_float b) { return a.v <= b.v; }
    friend bool operator>(gpu_float a, gpu_float b) { return a.v > b.v; }
    friend bool operator>=(gpu_float a, gpu_float b) { return a.v >= b.v; }

    // M1 (and the fused mode): a + b correctly rounded, or with a product's
    // residual folded in before the one rounding.
    static bool fusing() { return gpu_arithmetic().fuse; }
    [[gnu::always_inline]] static gpu_float add(gpu_float a, gpu_float b) {
        const float x = gpu_detail::flush(a.v), y = gpu_detail::flush(b.v);
        if (a.residual == 0.0f && b.residual == 0.0f) return raw(gpu_detail::flush(x + y));  // residuals: fuse mode only
        return add_fused(a, b, x, y);
    }
    [[gnu::noinline]] static gpu_float add_fused(gpu_float a, gpu_float b, float x, float y) {
        GpuArithmetic& g = gpu_arithmetic();
        float s;
        if (g.fuse && x == a.v && y == b.v && g.chance(0.5)) {
            // One of the two products fused (a GPU fuses one multiply per add).
            const bool first = a.residual != 0.0f && (b.residual == 0.0f || (g.next() & 1u));
            const long double exact = (long double)x + (long double)y + (first ? a.residual : b.residual);
            s = float(exact);
            ++g.fused;
        } else {
            s = x + y;
        }
        return raw(gpu_detail::flush(s));
    }

    // M2: within 2.5 ULP of the exact quotient, and +-0 possible for |b| > 2^126.
    static gpu_float divide(gpu_float a, gpu_float b) {
        GpuArithmetic& g = gpu_arithmetic();
        ++g.divisions;
        const float x = gpu_detail::flush(a.v), y = gpu_detail::flush(b.v);
        const float r = x / y;
        if (x == 0.0f || y == 0.0f || !std::isfinite(x) || !std::isfinite(y) || g.mode == GpuRounding::nearest)
            return raw(gpu_detail::flush(r));
        const long double q = (long double)x / (long double)y;  // 64-bit significand: far below 2^-24
        float lo, hi;
        gpu_detail::within(q, r, 2.5L, lo, hi);
        if (std::fabs(y) > 0x1p126f) {
            // "Anything from 0 to that": random mode returns the signed zero
            // a quarter of the time; low and high take the ends.
            const float zero = q > 0 ? 0.0f : -0.0f;
            if (g.mode == GpuRounding::random && g.chance(0.25)) return raw(zero);
            if (g.mode != GpuRounding::random) {
                lo = std::fmin(lo, zero);
                hi = std::fmax(hi, zero);
            }
        }
        return raw(gpu_detail::flush(gpu_detail::pick(lo, r, hi)));
    }
};

// M3: sqrt within 4 ULP of the correctly rounded root.
inline gpu_float gpu_sqrt(gpu_float a) {
    const float x = gpu_detail::flush(a.v);
    const float r = std::sqrt(x);
    if (!(r > 0.0f) || !std::isfinite(r) || gpu_arithmetic().mode == GpuRounding::nearest)
        return gpu_float::raw(r);
    float lo = r, hi = r;
    for (int k = 0; k < 4; ++k) {
        lo = std::nextafter(lo, 0.0f);
        hi = std::nextafter(hi, std::numeric_limits<float>::infinity());
    }
    if (!std::isfinite(hi)) hi = FLT_MAX;
    return gpu_float::raw(gpu_detail::flush(gpu_detail::pick(lo, r, hi)));
}

// M3: inversesqrt within 2 ULP of the exact 1 / sqrt(a).
inline gpu_float gpu_inversesqrt(gpu_float a) {
    const float x = gpu_detail::flush(a.v);
    const float r = 1.0f / std::sqrt(x);
    if (!(x > 0.0f) || !std::isfinite(x) || gpu_arithmetic().mode == GpuRounding::nearest) return gpu_float::raw(r);
    const long double q = 1.0L / std::sqrt((long double)x);
    float lo, hi;
    gpu_detail::within(q, float(q), 2.0L, lo, hi);
    return gpu_float::raw(gpu_detail::flush(gpu_detail::pick(lo, float(q), hi)));
}

// M3: undefined precision: off by up to 2^-11.
inline gpu_float gpu_sin(gpu_float a) {
    return gpu_float::raw(gpu_detail::flush(gpu_detail::perturb(std::sin(double(gpu_detail::flush(a.v))), 0x1p-11, 0x1p-11)));
}
inline gpu_float gpu_cos(gpu_float a) {
    return gpu_float::raw(gpu_detail::flush(gpu_detail::perturb(std::cos(double(gpu_detail::flush(a.v))), 0x1p-11, 0x1p-11)));
}
inline gpu_float gpu_exp(gpu_float a) {
    return gpu_float::raw(gpu_detail::flush(gpu_detail::perturb(std::exp(double(gpu_detail::flush(a.v))), 0x1p-11, 0.0)));
}
inline gpu_float gpu_log(gpu_float a) {
    return gpu_float::raw(gpu_detail::flush(gpu_detail::perturb(std::log(double(gpu_detail::flush(a.v))), 0x1p-11, 0.0)));
}
inline gpu_float gpu_pow(gpu_float a, gpu_float b) {
    return gpu_float::raw(gpu_detail::flush(
        gpu_detail::perturb(std::pow(double(gpu_detail::flush(a.v)), double(gpu_detail::flush(b.v))), 0x1p-11, 0.0)));
}

}  // namespace blurcull::testing

// What std:: and GLM need: IEEE binary32 limits (the kernel static_asserts
// is_iec559; GLM's min, max, abs, clamp, dot, cross check it too).
template <>
class std::numeric_limits<blurcull::testing::gpu_float> : public std::numeric_limits<float> {
    using G = blurcull::testing::gpu_float;
    using F = std::numeric_limits<float>;

public:
    static constexpr G min() noexcept { return G(F::min()); }
    static constexpr G max() noexcept { return G(F::max()); }
    static constexpr G lowest() noexcept { return G(F::lowest()); }
    static constexpr G epsilon() noexcept { return G(F::epsilon()); }
    static constexpr G round_error() noexcept { return G(F::round_error()); }
    static constexpr G infinity() noexcept { return G(F::infinity()); }
    static constexpr G quiet_NaN() noexcept { return G(F::quiet_NaN()); }
    static constexpr G signaling_NaN() noexcept { return G(F::signaling_NaN()); }
    static constexpr G denorm_min() noexcept { return G(F::denorm_min()); }
};

// The GLSL built-ins kernel<Real> forwards to glm:: (kernel.hpp): exact ones
// (M5) on the stored float, roots and transcendentals by the model (M3).
namespace glm {
inline blurcull::testing::gpu_float sqrt(blurcull::testing::gpu_float a) { return blurcull::testing::gpu_sqrt(a); }
inline blurcull::testing::gpu_float inversesqrt(blurcull::testing::gpu_float a) {
    return blurcull::testing::gpu_inversesqrt(a);
}
inline blurcull::testing::gpu_float floor(blurcull::testing::gpu_float a) {
    return blurcull::testing::gpu_float::raw(std::floor(a.v));
}
inline blurcull::testing::gpu_float ceil(blurcull::testing::gpu_float a) {
    return blurcull::testing::gpu_float::raw(std::ceil(a.v));
}
inline blurcull::testing::gpu_float sin(blurcull::testing::gpu_float a) { return blurcull::testing::gpu_sin(a); }
inline blurcull::testing::gpu_float cos(blurcull::testing::gpu_float a) { return blurcull::testing::gpu_cos(a); }
inline blurcull::testing::gpu_float exp(blurcull::testing::gpu_float a) { return blurcull::testing::gpu_exp(a); }
inline blurcull::testing::gpu_float log(blurcull::testing::gpu_float a) { return blurcull::testing::gpu_log(a); }
inline blurcull::testing::gpu_float pow(blurcull::testing::gpu_float a, blurcull::testing::gpu_float b) {
    return blurcull::testing::gpu_pow(a, b);
}
}  // namespace glm
