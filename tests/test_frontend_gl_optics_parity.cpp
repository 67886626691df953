// GPU/host parity of render/common/optics_shared.h (docs/reference-renderer.md,
// "Materials and environment"): a compute shader built from the kernel's GLSL
// and the embedded optics_shared.h evaluates the mirror and refracted
// directions, the Fresnel reflectance, the procedural sky, a mirror's or
// glass's environment colour and the environment seen along a direction
// of any length on 2^17 random
// (incident, normal, index) triples, including total internal reflection,
// index 1 and grazing rays; the host runs the C++ side of the same text on the
// same floats. The text spells every operation out in one order, each
// value `precise`, so on an IEEE-exact GL (llvmpipe) every decision (total
// internal reflection: a zero refracted vector, R = 1; index 1: R = 0) and
// every value is the host's, bit for bit. On a GL that is not IEEE-exact
// (probe_arithmetic), or with BLURCULL_GL_TOLERANT=1, the model's limits
// instead: decisions may differ within rounding of the critical angle, the
// values by the tolerances below (a mirrored component can cancel).
//
// And render/common/resolve_shared.h, the dof-secondary resolve's sample
// hit in fp64, on 2^16 samples with degenerate triangles and rays along
// their planes: the same validity and floats, bit for bit on an IEEE-exact
// GL, within 1e-5 relative elsewhere.
//
// No GL context (no Mesa): fails when CI=true, else skips with a message.

#include "gl_parity_helpers.hpp"  // first: no fma contraction on the host

#include "render/common/optics_shared.h"
#include "render/common/resolve_shared.h"
#include "render/gl/gl_context.hpp"
#include "render/gl/render_glsl.hpp"

#include <blurcull/glsl/kernel_glsl.hpp>
#include <doctest/doctest.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

using namespace blurcull;
using namespace blurcull::frontend::test;
namespace optics = blurcull::frontend::optics;
namespace resolve = blurcull::frontend::resolve;

namespace {

constexpr std::uint32_t kCount = 1u << 17;
constexpr int kOutputs = 16;  // mirror (3), refracted (3), reflectance (1), sky (3), specular colour (3), environment (3)
// The tolerant comparison's base: what llvmpipe gave before the text was
// spelt out (GLSL's dot and mix): 8.3e-6 (refracted rays within rounding of
// the critical angle, where sqrt(1 - sin^2) amplifies), 4.8e-5 and 5 ULP.
constexpr float kMaxDirectionError = 2e-5f;
constexpr float kMaxReflectanceError = 2e-4f;
constexpr std::int64_t kMaxSkyUlps = 16;
// On a GL that is not IEEE-exact (probe_arithmetic) or with
// BLURCULL_GL_TOLERANT=1, the model's limits (docs/glsl.md): 1 / ior through a
// division (2.5 ULP) and sqrt(1 - sin_t^2) (4.5 ULP) make the refracted
// direction and R ill-conditioned near the critical angle, by
// 1 / sqrt(1 - sin_t^2): the limits above plus kDivisionUlps float roundoffs
// times that condition (4 times for R, whose two quotients each carry it); a
// total-internal-reflection decision may differ only where 1 - sin_t^2 is
// within kEdgeTolerance. The sky: c = x / sqrt(x^2 + z^2) within 7 ULP
// (division and sqrt), T8's slope at most 64, 0.08 of a radiance of about
// 0.5, and mix's sqrt(y) 4.5 ULP: 64 x 7 x 0.08 x 2 + 6 ~ 78, so 96 ULP.
constexpr std::int64_t kModelSkyUlps = 96;

// sin_t^2 of the refracted ray in double on the float inputs (as
// bc_refract_direction computes it), and the condition 1 / sqrt(1 - sin_t^2).
struct RefractionCondition {
    double gap = 1.0;  // 1 - sin_t^2
    double condition = 1.0;
};

RefractionCondition refraction_condition(const float* a) {
    const glm::dvec3 i(a[0], a[1], a[2]), n(a[3], a[4], a[5]);
    const bool entering = glm::dot(n, i) < 0.0;
    const double eta = entering ? 1.0 / double(a[6]) : double(a[6]);
    const double cos_i = std::abs(glm::dot(n, i));
    RefractionCondition out;
    out.gap = 1.0 - eta * eta * std::max(0.0, 1.0 - cos_i * cos_i);
    out.condition = 1.0 / std::sqrt(std::max(std::abs(out.gap), 1e-300));
    return out;
}

const char* const kOpticsMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { float in_[]; };
layout(std430, binding = 1) writeonly buffer Results { uint out_[]; };
uniform uint count;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    uint a = 7u * i;
    vec3 incident = vec3(in_[a], in_[a + 1u], in_[a + 2u]);
    vec3 normal = vec3(in_[a + 3u], in_[a + 4u], in_[a + 5u]);
    float ior = in_[a + 6u];
    vec3 m = bc_mirror_direction(incident, normal);
    vec3 t = bc_refract_direction(incident, normal, ior);
    float r = bc_dielectric_reflectance(incident, normal, ior);
    vec3 sky = bc_sky_radiance(incident);
    vec3 background = vec3(0.3, 0.4, 0.5);
    vec3 colour = bc_specular_environment_colour(i % 3u == 0u, ior, true, background, incident, normal);
    vec3 seen = bc_environment_radiance(i % 2u == 0u, background, 2.5 * incident);
    uint o = 16u * i;
    out_[o] = floatBitsToUint(m.x); out_[o + 1u] = floatBitsToUint(m.y); out_[o + 2u] = floatBitsToUint(m.z);
    out_[o + 3u] = floatBitsToUint(t.x); out_[o + 4u] = floatBitsToUint(t.y); out_[o + 5u] = floatBitsToUint(t.z);
    out_[o + 6u] = floatBitsToUint(r);
    out_[o + 7u] = floatBitsToUint(sky.x); out_[o + 8u] = floatBitsToUint(sky.y); out_[o + 9u] = floatBitsToUint(sky.z);
    out_[o + 10u] = floatBitsToUint(colour.x); out_[o + 11u] = floatBitsToUint(colour.y);
    out_[o + 12u] = floatBitsToUint(colour.z);
    out_[o + 13u] = floatBitsToUint(seen.x); out_[o + 14u] = floatBitsToUint(seen.y); out_[o + 15u] = floatBitsToUint(seen.z);
}
)glsl";

// splitmix64 as in the built-in scenes: the same inputs everywhere.
struct Random {
    std::uint64_t state;
    float unit() {
        state += 0x9E3779B97F4A7C15ull;
        std::uint64_t z = state;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return static_cast<float>((z ^ (z >> 31)) >> 40) * (1.0f / 16777216.0f);
    }
    glm::vec3 direction() {
        for (;;) {
            const glm::vec3 v(2.0f * unit() - 1.0f, 2.0f * unit() - 1.0f, 2.0f * unit() - 1.0f);
            const float length = glm::length(v);
            if (length > 0.1f && length <= 1.0f) return v / length;
        }
    }
};

std::vector<float> make_inputs() {
    Random random{2013u};
    const float iors[] = {1.0f, 1.33f, 1.5f, 2.4f, 0.75f};
    std::vector<float> inputs;
    inputs.reserve(7u * kCount);
    for (std::uint32_t i = 0; i < kCount; ++i) {
        glm::vec3 incident = random.direction();
        const glm::vec3 normal = random.direction();
        if (i % 16u == 0u) {  // grazing: incident nearly in the surface
            incident = glm::normalize(incident - glm::dot(incident, normal) * normal + 1e-3f * normal);
        }
        for (float x : {incident.x, incident.y, incident.z, normal.x, normal.y, normal.z}) inputs.push_back(x);
        inputs.push_back(iors[i % 5u]);
    }
    return inputs;
}

std::vector<std::uint32_t> host_outputs(const std::vector<float>& in) {
    std::vector<std::uint32_t> out;
    out.reserve(kOutputs * std::size_t{kCount});
    for (std::uint32_t i = 0; i < kCount; ++i) {
        const float* a = &in[7u * i];
        const glm::vec3 incident(a[0], a[1], a[2]);
        const glm::vec3 normal(a[3], a[4], a[5]);
        const glm::vec3 m = optics::bc_mirror_direction(incident, normal);
        const glm::vec3 t = optics::bc_refract_direction(incident, normal, a[6]);
        const float r = optics::bc_dielectric_reflectance(incident, normal, a[6]);
        const glm::vec3 sky = optics::bc_sky_radiance(incident);
        const glm::vec3 background(0.3f, 0.4f, 0.5f);
        const glm::vec3 colour =
            optics::bc_specular_environment_colour(i % 3u == 0u, a[6], true, background, incident, normal);
        const glm::vec3 seen = optics::bc_environment_radiance(i % 2u == 0u, background, 2.5f * incident);
        for (float x : {m.x, m.y, m.z, t.x, t.y, t.z, r, sky.x, sky.y, sky.z, colour.x, colour.y, colour.z, seen.x,
                        seen.y, seen.z})
            out.push_back(bits_of(x));
    }
    return out;
}

// Runs `main` after the kernel's GLSL and the embedded `headers` over
// `count` invocations (uniform `count`): the floats `in` at binding 0,
// `outputs` words back from binding 1.
std::vector<std::uint32_t> run_parity_shader(const gl::HeadlessContext& context,
                                             const std::vector<std::string_view>& headers, const char* main,
                                             const std::vector<float>& in, std::size_t outputs, std::uint32_t count) {
    const gl::Functions& f = context.gl();
    std::vector<std::string_view> sources{glsl::kernel_source()};
    for (std::string_view name : headers) {
        sources.push_back(glsl::render_shader_source(name));
        REQUIRE_FALSE(sources.back().empty());
    }
    sources.push_back(main);
    gl::Program program(f, {{GL_COMPUTE_SHADER, sources}});
    gl::Buffer inputs(f, GL_SHADER_STORAGE_BUFFER, in.size() * 4, in.data());
    std::vector<std::uint32_t> out(outputs, 0u);
    gl::Buffer result(f, GL_SHADER_STORAGE_BUFFER, out.size() * 4);
    inputs.bind_base(0);
    result.bind_base(1);
    f.UseProgram(program.id());
    f.Uniform1ui(f.GetUniformLocation(program.id(), "count"), count);
    f.DispatchCompute((count + 63u) / 64u, 1, 1);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::check_gl(f, "running a parity shader");
    result.read(out.data(), out.size() * 4);
    f.UseProgram(0);
    return out;
}

}  // namespace

TEST_CASE("GLSL optics_shared.h equals the host's: mirror, refraction, Fresnel, sky on 2^17 inputs") {
    std::optional<gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    const std::vector<float> inputs = make_inputs();
    const std::vector<std::uint32_t> host = host_outputs(inputs);
    const std::vector<std::uint32_t> gpu =
        run_parity_shader(*context, {"optics_shared.h"}, kOpticsMain, inputs, kOutputs * std::size_t{kCount}, kCount);
    // Largest absolute difference of the unit directions (both sides round
    // their dot products differently and m = i - 2 (n.i) n cancels, so ULPs
    // of a small component mean nothing), of R and of the sky.
    const ArithmeticProbe probe = probe_arithmetic(*context);
    MESSAGE(probe.describe());
    ToleranceTally model;  // the tolerant comparison's differences beyond the exact-GL limits
    float max_direction = 0.0f, max_reflectance = 0.0f, max_colour = 0.0f;
    std::int64_t max_sky_ulps = 0;
    long decision_mismatches = 0, total_reflections = 0, index_one = 0;
    std::string first;
    for (std::uint32_t i = 0; i < kCount; ++i) {
        const std::size_t o = kOutputs * std::size_t{i};
        // Decisions: a zero refracted vector (total internal reflection) and R of exactly 0 or 1.
        const bool host_tir = float_of(host[o + 3]) == 0.0f && float_of(host[o + 4]) == 0.0f &&
                              float_of(host[o + 5]) == 0.0f;
        const bool gpu_tir =
            float_of(gpu[o + 3]) == 0.0f && float_of(gpu[o + 4]) == 0.0f && float_of(gpu[o + 5]) == 0.0f;
        const float host_r = float_of(host[o + 6]), gpu_r = float_of(gpu[o + 6]);
        total_reflections += host_tir ? 1 : 0;
        index_one += inputs[7u * i + 6] == 1.0f ? 1 : 0;
        const RefractionCondition cond = refraction_condition(&inputs[7u * i]);
        if (host_tir != gpu_tir || (host_r == 1.0f) != (gpu_r == 1.0f) || (host_r == 0.0f) != (gpu_r == 0.0f)) {
            model.note(std::abs(cond.gap) <= kEdgeTolerance, "total internal reflection of item " + std::to_string(i));
            ++decision_mismatches;
            if (first.empty()) first = "decision of item " + std::to_string(i);
            continue;  // past the critical angle on one side only: the values differ by design
        }
        if (inputs[7u * i + 6] == 1.0f) CHECK(host_r == 0.0f);
        if (host_tir) CHECK(host_r == 1.0f);
        const double roundoff = double(kDivisionUlps) * 0x1p-24 * cond.condition;
        for (int k = 0; k < 6; ++k) {
            const float d = std::abs(float_of(host[o + k]) - float_of(gpu[o + k]));
            max_direction = std::max(max_direction, d);
            if (d > kMaxDirectionError)
                model.note(d <= double(kMaxDirectionError) + roundoff, "direction of item " + std::to_string(i));
        }
        max_reflectance = std::max(max_reflectance, std::abs(host_r - gpu_r));
        if (std::abs(host_r - gpu_r) > kMaxReflectanceError)
            model.note(std::abs(host_r - gpu_r) <= double(kMaxReflectanceError) + 4.0 * roundoff,
                       "reflectance of item " + std::to_string(i));
        for (int k = 7; k < 10; ++k) {
            const std::int64_t d = ulp_distance(float_of(host[o + k]), float_of(gpu[o + k]));
            max_sky_ulps = std::max(max_sky_ulps, d);
            if (d > kMaxSkyUlps) model.note(d <= kModelSkyUlps, "sky of item " + std::to_string(i));
        }
        // The specular colour and the environment: sums of the above, within 1e-3 of colours about 0.5.
        for (int k = 10; k < kOutputs; ++k) {
            const float d = std::abs(float_of(host[o + k]) - float_of(gpu[o + k]));
            max_colour = std::max(max_colour, d);
            if (d > 0.0f) model.note(d <= 1e-3f + 4.0 * roundoff, "colour of item " + std::to_string(i));
        }
    }
    MESSAGE(kCount << " inputs, " << total_reflections << " totally reflected, " << index_one
                   << " at index 1; max differences: directions " << max_direction << ", R " << max_reflectance
                   << ", sky " << max_sky_ulps << " ULP, specular and environment colours " << max_colour << "; "
                   << decision_mismatches << " decisions differ");
    CHECK(total_reflections > 1000);
    if (!probe.tolerant()) {
        CHECK_MESSAGE(decision_mismatches == 0, first);
        CHECK(max_direction == 0.0f);
        CHECK(max_reflectance == 0.0f);
        CHECK(max_sky_ulps == 0);
        CHECK(max_colour == 0.0f);
    } else {
        MESSAGE("tolerant comparison: beyond the exact-GL limits, " << model.within
                << " differ within the model's (critical-angle condition, sky " << kModelSkyUlps << " ULP), "
                << model.outside << " outside");
        CHECK_MESSAGE(model.outside == 0, model.first_outside);
    }
}

namespace {

// resolve_shared.h's sample hit on the GPU: item i's 25 floats (view and
// world vertices, lens origin and direction, time) after the two inverse
// views (32 floats), out: point, incident, normal and valid, then the rays
// spawned at a valid hit (a mirror for every third item, else glass of one
// of five indices): count, direction and weight of each, 19 words.
const char* const kResolveMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { float in_[]; };
layout(std430, binding = 1) writeonly buffer Results { uint out_[]; };
uniform uint count;
dvec3 at(uint a) { return dvec3(in_[a], in_[a + 1u], in_[a + 2u]); }
dmat4 matrix(uint a) {
    return dmat4(dvec4(at(a), in_[a + 3u]), dvec4(at(a + 4u), in_[a + 7u]), dvec4(at(a + 8u), in_[a + 11u]),
                 dvec4(at(a + 12u), in_[a + 15u]));
}
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    uint a = 32u + 25u * i;
    dvec3 lens_world = bc_lens_world(matrix(0u), matrix(16u), at(a + 18u), double(in_[a + 24u]));
    SampleHit h = bc_sample_hit(at(a), at(a + 3u), at(a + 6u), at(a + 9u), at(a + 12u), at(a + 15u), at(a + 18u),
                                at(a + 21u), lens_world);
    uint o = 19u * i;
    out_[o] = floatBitsToUint(h.point.x); out_[o + 1u] = floatBitsToUint(h.point.y); out_[o + 2u] = floatBitsToUint(h.point.z);
    out_[o + 3u] = floatBitsToUint(h.incident.x); out_[o + 4u] = floatBitsToUint(h.incident.y);
    out_[o + 5u] = floatBitsToUint(h.incident.z);
    out_[o + 6u] = floatBitsToUint(h.normal.x); out_[o + 7u] = floatBitsToUint(h.normal.y); out_[o + 8u] = floatBitsToUint(h.normal.z);
    out_[o + 9u] = h.valid ? 1u : 0u;
    float iors[5] = float[5](1.0, 1.33, 1.5, 2.4, 0.75);
    SpawnedRays r = bc_spawn_rays(i % 3u == 0u, iors[i % 5u], h.incident, h.normal);
    if (!h.valid) r.count = 0;
    out_[o + 10u] = uint(r.count);
    out_[o + 11u] = floatBitsToUint(r.direction0.x); out_[o + 12u] = floatBitsToUint(r.direction0.y);
    out_[o + 13u] = floatBitsToUint(r.direction0.z); out_[o + 14u] = floatBitsToUint(r.weight0);
    out_[o + 15u] = floatBitsToUint(r.direction1.x); out_[o + 16u] = floatBitsToUint(r.direction1.y);
    out_[o + 17u] = floatBitsToUint(r.direction1.z); out_[o + 18u] = floatBitsToUint(r.weight1);
}
)glsl";

}  // namespace

TEST_CASE("GLSL resolve_shared.h (fp64) equals the host's sample hits and spawned rays on 2^16 samples, degenerate ones included") {
    std::optional<gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    constexpr std::uint32_t count = 1u << 16;
    Random random{2015u};
    auto spread = [&](float lo, float hi) { return lo + (hi - lo) * random.unit(); };
    std::vector<float> in;
    // Two inverse views: a rotation about y and a translation, shutter open and close.
    for (float angle : {0.3f, 0.35f}) {
        const glm::mat4 m = glm::translate(glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0.0f, 1.0f, 0.0f)),
                                           glm::vec3(1.0f, 2.0f, angle));
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) in.push_back(m[c][r]);
    }
    for (std::uint32_t i = 0; i < count; ++i) {
        glm::vec3 v[3], w[3];
        for (int k = 0; k < 3; ++k) {
            v[k] = glm::vec3(spread(-3.0f, 3.0f), spread(-3.0f, 3.0f), spread(-9.0f, -1.0f));
            w[k] = v[k] + glm::vec3(spread(-0.1f, 0.1f), 1.0f, 0.5f);
        }
        if (i % 64u == 1u) v[2] = v[0] + 2.0f * (v[1] - v[0]);  // degenerate: collinear
        const glm::vec3 o(spread(-0.2f, 0.2f), spread(-0.2f, 0.2f), 0.0f);
        glm::vec3 d(spread(-0.6f, 0.6f), spread(-0.6f, 0.6f), -1.0f);
        if (i % 64u == 2u) d = v[1] - v[0];  // along the plane
        for (const glm::vec3& x : {v[0], v[1], v[2], w[0], w[1], w[2], o, d})
            for (int c = 0; c < 3; ++c) in.push_back(x[c]);
        in.push_back(random.unit());
    }
    // The host, on the same floats.
    auto matrix = [&](std::size_t a) {
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = in[a + 4 * c + r];
        return m;
    };
    std::vector<std::uint32_t> host;
    long invalid = 0, spawned = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
        const std::size_t a = 32 + 25 * std::size_t{i};
        auto at = [&](std::size_t k) { return glm::dvec3(in[a + k], in[a + k + 1], in[a + k + 2]); };
        const glm::dvec3 lens_world = resolve::bc_lens_world(matrix(0), matrix(16), at(18), double(in[a + 24]));
        const resolve::SampleHit h =
            resolve::bc_sample_hit(at(0), at(3), at(6), at(9), at(12), at(15), at(18), at(21), lens_world);
        for (const glm::vec3& x : {h.point, h.incident, h.normal})
            for (int c = 0; c < 3; ++c) host.push_back(bits_of(x[c]));
        host.push_back(h.valid ? 1u : 0u);
        invalid += h.valid ? 0 : 1;
        const float iors[5] = {1.0f, 1.33f, 1.5f, 2.4f, 0.75f};
        resolve::SpawnedRays r = resolve::bc_spawn_rays(i % 3u == 0u, iors[i % 5u], h.incident, h.normal);
        if (!h.valid) r.count = 0;
        host.push_back(static_cast<std::uint32_t>(r.count));
        spawned += r.count;
        for (float x : {r.direction0.x, r.direction0.y, r.direction0.z, r.weight0, r.direction1.x, r.direction1.y,
                        r.direction1.z, r.weight1})
            host.push_back(bits_of(x));
    }
    const std::vector<std::uint32_t> gpu =
        run_parity_shader(*context, {"optics_shared.h", "resolve_shared.h"}, kResolveMain, in, host.size(), count);
    const bool tolerant = probe_arithmetic(*context).tolerant();
    long valid_differ = 0, values_differ = 0;
    float worst = 0.0f;
    for (std::uint32_t i = 0; i < count; ++i) {
        const std::size_t o = 19 * std::size_t{i};
        if (host[o + 9] != gpu[o + 9] || host[o + 10] != gpu[o + 10]) {
            ++valid_differ;  // or a different count of rays
            continue;
        }
        for (int k : {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 13, 14, 15, 16, 17, 18}) {
            const float h = float_of(host[o + k]), g = float_of(gpu[o + k]);
            const float gap = std::abs(h - g) / std::max(1.0f, std::abs(h));
            worst = std::max(worst, gap);
            values_differ += tolerant ? gap > 1e-5f : host[o + k] != gpu[o + k];
        }
    }
    MESSAGE(count << " samples, " << invalid << " without a hit, " << spawned << " rays spawned; " << valid_differ
                  << " validities or ray counts and " << values_differ << " values differ (largest relative difference "
                  << worst << ")");
    CHECK(invalid > 1000);  // the degenerate cases are exercised
    CHECK(spawned > count);  // glass spawns two rays where it does not reflect totally
    // A double-precision decision may differ only where a GL's doubles are not IEEE.
    CHECK(valid_differ <= (tolerant ? long(count / 10000) : 0L));
    CHECK(values_differ == 0);
}
