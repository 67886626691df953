// The host's sample-by-sample decisions for a whole render (what the GL
// backend must reproduce), and the comparison that says how a GPU whose
// arithmetic is not IEEE-exact may differ from them (docs/glsl.md, "Parity
// on a GPU that is not IEEE-exact"). Used by test_frontend_gl_render.cpp and
// test_frontend_sampler.cpp.
//
// Include it FIRST (it includes gl_parity_helpers.hpp, whose pragma keeps the
// host from contracting a*b+c).
#pragma once

#include "gl_parity_helpers.hpp"
#include "render/common/camera_model.hpp"
#include "render/common/moving_triangle.hpp"
#include "render/common/shading.hpp"
#include "render/gl/gl_backend.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace blurcull::frontend::test {

template <class Real>
struct SampleReference {
    using K = blurcull::kernel<Real>;
    struct Sample {
        typename K::vec2 ndc, lens;
        Real time;
    };
    std::vector<std::uint32_t> ids;  // nearest covering triangle per sample, or no_triangle
    std::vector<Real> depth;         // its depth
    Image image;                     // resolved as every backend resolves
    std::vector<Sample> samples;
    std::vector<typename K::MovingTriangle> triangles;  // by scene index
    Real near = Real(0);
    // (sample, triangle) pairs whose covers decision is within the edge
    // tolerance of flipping (covers_condition margin <= kEdgeTolerance):
    // how far a GPU's hit count may lie from the host's. Float only, and only
    // when asked for (a double evaluation per pair in the screen bound).
    long pairs_near_edge = 0;
};

// The CPU backend's decisions, sample by sample, without culling (its image
// does not depend on the cull): kernel<Real>, strict depth test in triangle
// order, over settings.sampler's samples. The callers check that it resolves
// to exactly render_cpu's image at the same precision.
template <class Real>
SampleReference<Real> reference_samples(const Scene& scene, const RenderSettings& settings, bool tally_near_edge = false) {
    using K = blurcull::kernel<Real>;
    SampleReference<Real> ref;
    const CameraModel model(scene.camera, settings.width, settings.height);
    const auto spp = static_cast<std::uint32_t>(settings.spp);
    const std::size_t pixels = static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height);
    ref.ids.assign(pixels * spp, no_triangle);
    ref.depth.assign(ref.ids.size(), std::numeric_limits<Real>::infinity());
    ref.samples.resize(ref.ids.size());
    ref.near = static_cast<Real>(model.znear);
    for (int py = 0; py < settings.height; ++py) {
        for (int px = 0; px < settings.width; ++px) {
            const blurcull::patternsf::SamplerSetup pattern = blurcull::patternsf::sampler_setup(
                settings.sampler, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py), spp, settings.seed);
            for (std::uint32_t j = 0; j < spp; ++j) {
                const blurcull::kernelf::PixelSample s = blurcull::patternsf::sampler_sample(pattern, j);
                ref.samples[(static_cast<std::size_t>(py) * settings.width + px) * spp + j] =
                    {typename K::vec2(model.sample_ndc(px, py, s.offset)), typename K::vec2(s.lens),
                     static_cast<Real>(s.time)};
            }
        }
    }
    ref.triangles.reserve(scene.triangles.size());
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        ref.triangles.push_back(make_moving_triangle<Real>(scene, model, t));
        const typename K::MovingTriangle& tri = ref.triangles.back();
        if (K::classify(tri) == BC_INVALID) continue;
        const typename K::ScreenBound bound = K::screen_bound(tri, ref.near, BC_CULL_BBOX);
        if (bound.empty) continue;
        const glm::vec2 lo = model.ndc_to_raster(glm::vec2(static_cast<float>(bound.lo.x), static_cast<float>(bound.hi.y)));
        const glm::vec2 hi = model.ndc_to_raster(glm::vec2(static_cast<float>(bound.hi.x), static_cast<float>(bound.lo.y)));
        const int x0 = std::max(0, static_cast<int>(std::floor(std::max(lo.x, -1.0f))) - 1);
        const int y0 = std::max(0, static_cast<int>(std::floor(std::max(lo.y, -1.0f))) - 1);
        const int x1 = std::min(settings.width - 1, static_cast<int>(std::min(hi.x, 1e6f)) + 1);
        const int y1 = std::min(settings.height - 1, static_cast<int>(std::min(hi.y, 1e6f)) + 1);
        for (int py = y0; py <= y1; ++py) {
            for (int px = x0; px <= x1; ++px) {
                for (std::uint32_t j = 0; j < spp; ++j) {
                    const std::size_t k = (static_cast<std::size_t>(py) * settings.width + px) * spp + j;
                    const auto& s = ref.samples[k];
                    if (!K::screen_contains(bound, s.ndc)) continue;
                    if constexpr (std::is_same_v<Real, float>) {
                        if (tally_near_edge &&
                            covers_condition(tri, s.ndc, s.lens, s.time, ref.near).margin <= kEdgeTolerance)
                            ++ref.pairs_near_edge;
                    }
                    Real z = Real(0);
                    if (!K::covers(tri, s.ndc, s.lens, s.time, ref.near, z)) continue;
                    if (z < ref.depth[k]) {
                        ref.depth[k] = z;
                        ref.ids[k] = static_cast<std::uint32_t>(t);
                    }
                }
            }
        }
    }
    const std::vector<glm::vec3> colours = shade_all(scene);
    ref.image = Image(settings.width, settings.height);
    for (std::size_t p = 0; p < pixels; ++p) {
        glm::vec3 sum(0.0f);
        for (std::uint32_t j = 0; j < spp; ++j) {
            const std::uint32_t id = ref.ids[p * spp + j];
            sum += id == no_triangle ? scene.background : colours[id];
        }
        ref.image.pixels[p] = resolve_box(sum, settings.spp);
    }
    return ref;
}

// Whether this GL computes as the host does (asked once per process; the
// probe and BLURCULL_GL_TOLERANT as in gl_parity_helpers.hpp).
inline const ArithmeticProbe& render_probe(const GlRenderer& gl) {
    static const ArithmeticProbe probe = [&] {
        ArithmeticProbe p = probe_arithmetic(gl.context());
        MESSAGE("GL arithmetic: " << p.describe());
        return p;
    }();
    return probe;
}

// A GPU's sample ids against the host's float decisions, each difference
// explained by the model or not:
// - near_edge: the host's or the GPU's triangle is within the edge
//   tolerance of flipping its covers decision at that sample;
// - depth_tie: both triangles cover it on the host, at depths within the
//   depth tolerance of each other (kEdgeTolerance times the worse depth
//   condition, plus kDivisionUlps: covers' depth is one division), so a
//   division's rounding may order them either way (exact ties included:
//   the static path draws its triangles before the moving ones);
// - outside: anything else, which the model forbids.
// image_rmse_limit: the RMSE (as rmse() takes it) that the explained samples
// can account for: each moves its pixel by |colour(host) - colour(GPU)| / spp
// per channel, at most.
struct SampleIdComparison {
    long equal = 0, near_edge = 0, depth_tie = 0, outside = 0;
    std::string first_outside;
    double image_rmse_limit = 0.0;
};

inline SampleIdComparison compare_sample_ids(const Scene& scene, const SampleReference<float>& ref,
                                             const std::vector<std::uint32_t>& gpu_ids, int spp) {
    using K = blurcull::kernel<float>;
    REQUIRE(gpu_ids.size() == ref.ids.size());
    SampleIdComparison out;
    const std::vector<glm::vec3> colours = shade_all(scene);
    auto colour = [&](std::uint32_t id) { return id == no_triangle ? scene.background : colours[id]; };
    const auto sample_count = static_cast<std::size_t>(spp);
    std::vector<glm::dvec3> moved(ref.ids.size() / sample_count, glm::dvec3(0.0));
    for (std::size_t k = 0; k < ref.ids.size(); ++k) {
        const std::uint32_t a = ref.ids[k], b = gpu_ids[k];
        if (a == b) {
            ++out.equal;
            continue;
        }
        const auto& s = ref.samples[k];
        // Each triangle's condition at this sample, once (no_triangle: none).
        auto condition = [&](std::uint32_t id) {
            return id == no_triangle ? CoversCondition{1e300, 0.0}
                                     : covers_condition(ref.triangles[id], s.ndc, s.lens, s.time, ref.near);
        };
        const CoversCondition cond_a = condition(a), cond_b = condition(b);
        bool explained = false;
        if (cond_a.margin <= kEdgeTolerance || cond_b.margin <= kEdgeTolerance) {
            ++out.near_edge;
            explained = true;
        } else if (a != no_triangle && b != no_triangle) {
            float zb = 0.0f;
            if (K::covers(ref.triangles[b], s.ndc, s.lens, s.time, ref.near, zb)) {
                const double za = ref.depth[k];
                const double z = std::max(za, double(zb));
                const double allowed =
                    kEdgeTolerance * std::max(cond_a.depth_condition, cond_b.depth_condition) * z +
                    double(kDivisionUlps) * std::ldexp(1.0, std::ilogb(std::max(z, 0x1p-126)) - 23);
                if (std::abs(za - double(zb)) <= allowed) {
                    ++out.depth_tie;
                    explained = true;
                }
            }
        }
        if (explained) {
            moved[k / sample_count] += glm::abs(glm::dvec3(colour(a)) - glm::dvec3(colour(b))) / double(spp);
        } else {
            ++out.outside;
            if (out.first_outside.empty())
                out.first_outside = "sample " + std::to_string(k) + ": host triangle " +
                                    (a == no_triangle ? std::string("none") : std::to_string(a)) + ", GPU triangle " +
                                    (b == no_triangle ? std::string("none") : std::to_string(b));
        }
    }
    double sum = 0.0;
    for (const glm::dvec3& d : moved) sum += glm::dot(d, d);
    out.image_rmse_limit = moved.empty() ? 0.0 : std::sqrt(sum / (3.0 * double(moved.size())));
    return out;
}

}  // namespace blurcull::frontend::test
