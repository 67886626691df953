// What the GPU/host parity tests (test_frontend_gl_parity.cpp,
// test_frontend_gl_raster_parity.cpp, test_frontend_gl_secondary_parity.cpp) share: host arithmetic without fma
// contraction, the includes for running an emitted-kernel compute shader, and
// a headless context or a reasoned skip.
//
// Include it FIRST: llvmpipe does not fuse a*b+c (design brief, section 8), so
// the host must not contract either, and the pragma below has to come before
// the kernel's functions are instantiated.
#pragma once

#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "frontend_test_helpers.hpp"
#include "kernel_generators.hpp"
#include "render/gl/gl_context.hpp"

#include <blurcull/glsl/kernel_glsl.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace blurcull::frontend::test {

// A headless context (of `kind` when given), or nothing after saying why; a
// failure instead when CI=true.
inline std::optional<gl::HeadlessContext> context_or_skip(std::optional<gl::ContextKind> kind = std::nullopt) {
    try {
        return kind ? gl::HeadlessContext::create(*kind) : gl::HeadlessContext::create();
    } catch (const gl::GlError& e) {
        if (is_ci()) FAIL("no headless OpenGL 4.5 context in CI: " << std::string(e.what()));
        MESSAGE("SKIPPED: no headless OpenGL 4.5 context (" << std::string(e.what()) << "); CI=true makes this a failure");
        return std::nullopt;
    }
}

// A float's bits and back: the parity tests move floats through uint SSBOs
// and compare them bit for bit.
inline std::uint32_t bits_of(float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

inline float float_of(std::uint32_t b) {
    float x;
    std::memcpy(&x, &b, sizeof x);
    return x;
}

// Distance in representable floats; NaN against anything else counts as
// "infinitely" far, two NaNs as equal.
inline std::int64_t ulp_distance(float a, float b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : INT64_MAX;
    auto ordered = [](float x) {
        std::int64_t raw = static_cast<std::int64_t>(bits_of(x));
        return raw & 0x80000000 ? -(raw & 0x7fffffff) : raw;
    };
    std::int64_t d = ordered(a) - ordered(b);
    return d < 0 ? -d : d;
}

// ---- What a GPU may differ in (issue 22, item 3; docs/glsl.md's model) ------
//
// Host = GLSL bit for bit holds where the GL implementation's arithmetic is
// IEEE-exact like the host's (llvmpipe). Decided by a probe rather than by the
// GL_RENDERER string: a compute shader divides, takes square roots and
// evaluates an unmarked a*b+c on seeded inputs (ordinary magnitudes, tiny and
// huge divisors, near-halfway quotients); the implementation is exact when
// every result equals the host's correctly rounded, unfused one bit for bit.
// Elsewhere (e.g. NVIDIA: division within 2.5 ULP, sqrt through inversesqrt,
// fused a*b+c) the parity tests assert the model's bounds below instead.
// BLURCULL_GL_TOLERANT=1 forces the tolerant path on an exact GL too, so CI
// (llvmpipe) runs it and it must pass there.
struct ArithmeticProbe {
    bool exact = false;        // every probe result bit-equal to the host's
    bool forced = false;       // BLURCULL_GL_TOLERANT asked for the tolerant path
    int division_differs = 0;  // probe results that differ, by operation
    int sqrt_differs = 0;
    int fma_differs = 0;
    int probes = 0;
    bool tolerant() const { return forced || !exact; }
    std::string describe() const {
        return std::string(exact ? "IEEE-exact" : "not IEEE-exact") + " (probe: " + std::to_string(division_differs) +
               " divisions, " + std::to_string(sqrt_differs) + " square roots, " + std::to_string(fma_differs) +
               " a*b+c of " + std::to_string(probes) + " differ from the host)" +
               (forced ? "; BLURCULL_GL_TOLERANT forces the tolerant comparison" : "") +
               (tolerant() ? ": asserting the model's bounds" : ": asserting bit equality");
    }
};

inline bool tolerant_forced() {
    const char* env = std::getenv("BLURCULL_GL_TOLERANT");
    return env && *env && std::string(env) != "0";
}

inline ArithmeticProbe probe_arithmetic(const gl::HeadlessContext& context) {
    static const char* const kProbeMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { float probe_in[]; };
layout(std430, binding = 1) writeonly buffer Out { uint probe_out[]; };
uniform uint probe_count;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= probe_count) return;
    float a = probe_in[3u * i];
    float b = probe_in[3u * i + 1u];
    float c = probe_in[3u * i + 2u];
    probe_out[3u * i] = floatBitsToUint(a / b);
    probe_out[3u * i + 1u] = floatBitsToUint(sqrt(abs(a)));
    probe_out[3u * i + 2u] = floatBitsToUint(a * b + c);
}
)glsl";
    ArithmeticProbe probe;
    probe.forced = tolerant_forced();
    blurcull::testing::Rng rng(0x9b0be5eedull);
    std::vector<float> in;
    const int count = 4096;
    for (int n = 0; n < count; ++n) {
        double magnitude = n % 4 == 0 ? rng.log_uniform(1e-30, 1e30) : rng.log_uniform(1e-3, 1e3);
        auto a = static_cast<float>(rng.signed_unit() * magnitude);
        auto b = static_cast<float>(rng.signed_unit() * rng.log_uniform(1e-3, 1e3));
        if (n % 16 == 1) b = static_cast<float>(rng.log_uniform(1e-37, 1e-36));  // a tiny divisor
        if (n % 16 == 2) b = static_cast<float>(rng.log_uniform(1e36, 1e37));    // a huge one
        auto c = static_cast<float>(-static_cast<double>(a) * b * (1.0 + 1e-7 * rng.signed_unit()));  // cancels a*b
        in.insert(in.end(), {a, b, c});
    }
    const gl::Functions& f = context.gl();
    gl::Program program(f, {{GL_COMPUTE_SHADER, {glsl::kernel_source(), kProbeMain}}});
    gl::Buffer input(f, GL_SHADER_STORAGE_BUFFER, in.size() * sizeof(float), in.data());
    std::vector<std::uint32_t> out(in.size(), 0u);
    gl::Buffer output(f, GL_SHADER_STORAGE_BUFFER, out.size() * sizeof(std::uint32_t));
    input.bind_base(0);
    output.bind_base(1);
    f.UseProgram(program.id());
    f.Uniform1ui(f.GetUniformLocation(program.id(), "probe_count"), static_cast<GLuint>(count));
    f.DispatchCompute((count + 63) / 64, 1, 1);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    f.Finish();
    gl::check_gl(f, "running the arithmetic probe");
    output.read(out.data(), out.size() * sizeof(std::uint32_t));
    f.UseProgram(0);
    // The host's correctly rounded results; volatile keeps a*b and +c apart.
    for (int n = 0; n < count; ++n) {
        const float a = in[static_cast<std::size_t>(3 * n)], b = in[static_cast<std::size_t>(3 * n + 1)],
                    c = in[static_cast<std::size_t>(3 * n + 2)];
        volatile float product = a * b;
        const float q = a / b, r = std::sqrt(std::abs(a)), m = product + c;
        const std::uint32_t* g = &out[static_cast<std::size_t>(3 * n)];
        probe.division_differs += g[0] != bits_of(q);
        probe.sqrt_differs += g[1] != bits_of(r);
        probe.fma_differs += g[2] != bits_of(m);
    }
    probe.probes = count;
    probe.exact = probe.division_differs == 0 && probe.sqrt_differs == 0 && probe.fma_differs == 0;
    return probe;
}

// The model's limits for the tolerant comparison, derived in docs/glsl.md
// ("Parity on a GPU"):
// - kEdgeTolerance: a decision of the exact test (covers) may differ only for
//   a sample whose edge value (covers_hit's, relative to V0: e1 = -d2 . q,
//   e2 = d1 . q, e0 = (d2 - d1) . q + n . (s, 1), q = (s, 1) x V0, the
//   distance to edge i times the edge normal's length) is within 2^-18 (64
//   float roundoffs) of the sum of the magnitudes of its terms, or whose det
//   (against 0 and against the edge-on threshold) or depth (against near) is
//   that close. The value goes through vertex_at (4 roundings), a difference
//   (1), two cross products (3) and a dot product (5); each of the ~13 roundings is
//   within 1 ULP under + - * (M1), within 2 where a GPU fuses a*b+c (not
//   `precise`), so host and GPU differ by at most ~26 roundoffs of the terms;
//   64 leaves a factor of 2.5. In screen units that is a distance of
//   2^-18 |terms| / |normal| from the edge: a few float ULPs of the
//   coordinates' magnitude for a well-shaped triangle.
// - kDivisionUlps: a value computed through one or two divisions (2.5 ULP
//   each, M2) and a margin summed from them: 16 ULP (2 x 2.5 ULP, times 3 for
//   the sums that the quotients feed, rounded up).
constexpr double kEdgeTolerance = 0x1p-18;
constexpr std::int64_t kDivisionUlps = 16;

// Whether float results h (host) and g (GPU) differ by at most `ulps` float
// ULPs of `magnitude` (or of |h|, when larger): a value computed through
// divisions whose error is relative to the magnitude of what it was computed
// from (e.g. -1 + 2 x / w: ULPs of 2, not of a result near 0). Non-finite:
// only equal.
inline bool within_ulps_of(float h, float g, double magnitude, std::int64_t ulps) {
    if (!std::isfinite(h) || !std::isfinite(g)) return bits_of(h) == bits_of(g) || (std::isnan(h) && std::isnan(g));
    const double m = std::max({magnitude, std::abs(double(h)), 0x1p-126});
    return std::abs(double(h) - double(g)) <= double(ulps) * std::ldexp(1.0, std::ilogb(m) - 23);
}

// How close, relative to the rounding of its computation, a sample's covers
// decision is to flipping (margin): the smallest of |e_i| / terms(e_i),
// |det| / terms(det) and |depth - near| / (depth * depth_condition), in
// double on the float triangle. A decision host and GPU disagree on must
// have margin <= kEdgeTolerance. depth_condition: the relative condition of
// depth = det / sum (det's and the sum's, plus 1 for the division), so host
// and GPU depths may differ by kEdgeTolerance * depth_condition relatively.
struct CoversCondition {
    double margin = 0.0;
    double depth_condition = 0.0;
};

inline CoversCondition covers_condition(const kernel<float>::MovingTriangle& tri_f, kernel<float>::vec2 s_f,
                            kernel<float>::vec2 uv_f, float t_f, float near_f) {
    using Kd = kernel<double>;
    Kd::MovingTriangle tri;
    for (int j = 0; j < 6; ++j) {
        tri.p[j] = Kd::vec3(tri_f.p[j]);
        tri.c[j] = Kd::vec2(tri_f.c[j]);
    }
    const Kd::vec2 uv(uv_f);
    const double t = t_f;
    Kd::vec3 v[3], a[3];
    for (int i = 0; i < 3; ++i) {
        v[i] = Kd::vertex_at(tri, i, t, uv);
        // Magnitudes of what vertex_at sums.
        a[i] = glm::abs(tri.p[i]) + glm::abs(tri.p[i + 3]) +
               Kd::vec3(glm::abs(tri.c[i]) + glm::abs(tri.c[i + 3]), 0.0);
    }
    // covers_hit's evaluation (oracle_body.inl: relative to the pivot, taken
    // first; the edges in the frame sheared by the sample), each value with
    // the scale of its rounding error to first order (in units of the
    // roundoff): what it inherits from its operands plus its own rounding. A
    // vertex inherits a[i] (vertex_at's sums); beyond bc_shear_limit the
    // edges unsheared, as covers_hit takes them. Only the smallest margin is
    // kept, so the edges' order is moot.
    const int pivot = Kd::bc_oracle_pivot(v[0], v[1], v[2]);
    std::rotate(v, v + pivot, v + 3);
    std::rotate(a, a + pivot, a + 3);
    auto cross_terms = [](const Kd::vec3& x, const Kd::vec3& y) {
        return Kd::vec3(x.y * y.z + x.z * y.y, x.z * y.x + x.x * y.z, x.x * y.y + x.y * y.x);
    };
    auto dot_error = [](const Kd::vec3& x, const Kd::vec3& x_err, const Kd::vec3& y, const Kd::vec3& y_err) {
        return glm::dot(x_err, y) + glm::dot(x, y_err) + glm::dot(x, y);
    };
    const Kd::vec3 d1 = v[1] - v[0], d2 = v[2] - v[0];
    const Kd::vec3 d1_abs = glm::abs(d1), d2_abs = glm::abs(d2), v0_abs = glm::abs(v[0]);
    const Kd::vec3 d1_err = d1_abs + a[0] + a[1], d2_err = d2_abs + a[0] + a[2];
    const Kd::vec3 n = glm::cross(d1, d2), n_abs = glm::abs(n);
    const Kd::vec3 n_err = cross_terms(d1_err, d2_abs) + cross_terms(d1_abs, d2_err) + cross_terms(d1_abs, d2_abs);
    double e[3], terms[3];
    if (std::max(std::abs(s_f.x), std::abs(s_f.y)) <= kernel<float>::bc_shear_limit()) {
        // Sheared: a value and its error scale; products and differences as covers_hit rounds them.
        struct Term {
            double v, err;
        };
        auto mul = [](Term x, Term y) {
            const double p = x.v * y.v;
            return Term{p, x.err * std::abs(y.v) + std::abs(x.v) * y.err + std::abs(p)};
        };
        auto sub = [](Term x, Term y) {
            const double d = x.v - y.v;
            return Term{d, x.err + y.err + std::abs(d)};
        };
        auto add = [&](Term x, Term y) { return sub(x, Term{-y.v, y.err}); };
        const Term sx{double(s_f.x), 0.0}, sy{double(s_f.y), 0.0};
        auto sheared = [&](double c, double c_err, double w, double w_err, Term s_axis) {
            return sub(Term{c, c_err}, mul(s_axis, Term{w, w_err}));
        };
        const Term px = sheared(v[0].x, a[0].x, v[0].z, a[0].z, sx), py = sheared(v[0].y, a[0].y, v[0].z, a[0].z, sy);
        const Term a1 = sheared(d1.x, d1_err.x, d1.z, d1_err.z, sx), b1 = sheared(d1.y, d1_err.y, d1.z, d1_err.z, sy);
        const Term a2 = sheared(d2.x, d2_err.x, d2.z, d2_err.z, sx), b2 = sheared(d2.y, d2_err.y, d2.z, d2_err.z, sy);
        const Term edge[3] = {add(sub(mul(sub(b2, b1), px), mul(sub(a2, a1), py)), sub(mul(a1, b2), mul(b1, a2))),
                              sub(mul(a2, py), mul(b2, px)), sub(mul(px, b1), mul(py, a1))};
        for (int i = 0; i < 3; ++i) {
            e[i] = edge[i].v;
            terms[i] = edge[i].err;
        }
    } else {
        // Unsheared: q = (s, 1) x V0, e0 = (d2 - d1) . q + n . (s, 1), e1 = -d2 . q, e2 = d1 . q.
        const Kd::vec3 ray(double(s_f.x), double(s_f.y), 1.0), ray_abs = glm::abs(ray);
        const Kd::vec3 d21 = d2 - d1, d21_abs = glm::abs(d21), d21_err = d21_abs + d1_err + d2_err;
        const Kd::vec3 q = glm::cross(ray, v[0]), q_abs = glm::abs(q);
        const Kd::vec3 q_err = cross_terms(ray_abs, a[0]) + cross_terms(ray_abs, v0_abs);
        e[0] = glm::dot(d21, q) + glm::dot(n, ray);
        e[1] = -glm::dot(d2, q);
        e[2] = glm::dot(d1, q);
        terms[0] = dot_error(d21_abs, d21_err, q_abs, q_err) + dot_error(n_abs, n_err, ray_abs, Kd::vec3(0.0));
        terms[1] = dot_error(d2_abs, d2_err, q_abs, q_err);
        terms[2] = dot_error(d1_abs, d1_err, q_abs, q_err);
    }
    double margin = 1e300, e_sum = 0.0, e_terms = 0.0;
    for (int i = 0; i < 3; ++i) {
        margin = std::min(margin, std::abs(e[i]) / std::max(terms[i], 1e-300));
        e_sum += e[i];
        e_terms += terms[i];
    }
    // det = V0 . n, against 0 and against covers' edge-on threshold
    // 32 eps bc_det_terms(|V0|, |d1|, |d2|) (float eps).
    const double det = glm::dot(v[0], n), det_terms = dot_error(v0_abs, a[0], n_abs, n_err);
    const double threshold = 32.0 * 0x1p-23 * glm::dot(v0_abs, cross_terms(d1_abs, d2_abs));
    margin = std::min(margin, std::min(std::abs(det), std::abs(std::abs(det) - threshold)) / std::max(det_terms, 1e-300));
    CoversCondition out;
    out.depth_condition = 1e300;
    if (det != 0.0 && e_sum != 0.0) {
        const double depth = std::abs(det / e_sum);
        out.depth_condition = det_terms / std::abs(det) + e_terms / std::abs(e_sum) + 1.0;
        margin = std::min(margin, std::abs(depth - double(near_f)) / std::max(depth * out.depth_condition, 1e-300));
    }
    out.margin = margin;
    return out;
}

// A tolerant comparison's tally of one kind of difference: how many were
// allowed by the model (within its stated limit) and how many were not.
struct ToleranceTally {
    long within = 0;
    long outside = 0;
    std::string first_outside;
    void note(bool allowed, const std::string& what) {
        if (allowed) {
            ++within;
            return;
        }
        if (first_outside.empty()) first_outside = what;
        ++outside;
    }
};

}  // namespace blurcull::frontend::test
