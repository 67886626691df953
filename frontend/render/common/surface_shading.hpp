// Shading as a resolve step over (sample, winning triangle): the contract of
// docs/reference-renderer.md, "Shading". A raster engine keeps only the
// winning triangle id per sample; the resolve computes the hit's barycentric
// coordinates at the sample's own (ndc, lens, time) with the kernel's
// covers_hit (in double, from the scene, whatever precision the engine
// rasterized in) and shades from them, so every backend that agrees on the
// winners agrees on the colours bit for bit. A triangle without surface
// attributes keeps the flat colour of shading.hpp, so scenes without them
// render exactly as before.
#pragma once

#include "render/common/camera_model.hpp"
#include "render/common/image.hpp"
#include "render/common/render_types.hpp"
#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace blurcull::frontend {

// The colour of a hit on `triangle` at barycentric coordinates `barycentric`
// (weights of its first, second and third vertex, summing to 1): base
// colour x COLOR_0 x base colour texture, lit by ambient plus the two-sided
// diffuse term of the interpolated NORMAL (the geometric normal at shutter
// open where the triangle has none) times Scene::light_color, plus emissive x
// emissive texture. `incident`, the ray's direction, is not used by this
// diffuse model (it is two-sided); it is there so a bounced ray from any
// direction shades its hit through the same function. The caller guarantees a
// valid scene (validate_scene) and triangle index.
glm::vec3 shade_hit(const Scene& scene, std::size_t triangle, glm::vec3 barycentric, glm::vec3 incident);

// The alpha of a hit: baseColorFactor's alpha x COLOR_0's alpha x the base
// colour texture's alpha. Same guarantees as shade_hit.
float hit_alpha(const Scene& scene, std::size_t triangle, glm::vec3 barycentric);

// Whether the triangle's shading varies over it (a texture, vertex colours,
// smooth normals): false means shade_hit equals shade(scene, triangle) everywhere.
bool shades_per_hit(const Scene& scene, std::size_t triangle);

// The per-frame shading state every backend's resolve uses.
class SurfaceShader {
public:
    // No sample hit (every backend's "none" id: 0xffffffff).
    static constexpr std::uint32_t no_hit = 0xffffffffu;

    // `threads`: the flat colours (shade_all) on that many threads.
    SurfaceShader(const Scene& scene, const CameraModel& model, int threads = 1);

    // Whether `triangle`'s material is alphaMode MASK or BLEND: its coverage
    // depends on sample_kept, which the raster decision must call.
    bool masked(std::uint32_t triangle) const { return masked_[triangle] != 0; }
    bool any_masked() const { return any_masked_; }
    // Whether some triangle shades per hit (shades_per_hit).
    bool any_per_hit() const { return any_per_hit_; }
    // Whether `triangle` shades per hit: false means sample_colour is its flat colour.
    bool per_hit(std::uint32_t triangle) const { return per_hit_[triangle] != 0; }

    // The raster decision's alpha test: whether a sample that the exact test
    // finds covered by `triangle` stays covered (MASK: hit_alpha >= cutoff;
    // BLEND: with probability hit_alpha, by the hash of the sample and the
    // triangle, surface_shared.h's bc_alpha_test; always true for opaque triangles). Every backend calls it where it
    // decides the nearest hit, so a masked-out sample never wins a depth test.
    bool sample_kept(std::uint32_t triangle, glm::vec2 ndc, glm::vec2 lens, float time) const;

    // The colour of a sample whose winner is `triangle` (no_hit: the background).
    glm::vec3 sample_colour(std::uint32_t triangle, glm::vec2 ndc, glm::vec2 lens, float time) const;

    // The hit's barycentric coordinates at the sample: kerneld::covers_hit on
    // the double-precision triangle. Where that misses (a float engine's
    // sample on the edge, within rounding), the nearest corner or edge point
    // is not known, and the centroid (1/3, 1/3, 1/3) is used.
    glm::vec3 barycentrics(std::uint32_t triangle, glm::vec2 ndc, glm::vec2 lens, float time) const;

    // The flat colour of every triangle (shade_all).
    const std::vector<glm::vec3>& flat_colours() const { return flat_; }

private:
    const Scene& scene_;
    double near_;
    std::vector<glm::vec3> flat_;
    std::vector<std::uint8_t> per_hit_, masked_;
    bool any_masked_ = false;
    bool any_per_hit_ = false;
    std::vector<kerneld::MovingTriangle> triangles_;  // per triangle, when some triangle shades per hit or is masked
};

// The image of per-sample winner ids in the stochastic renderers' layout
// (sample j of pixel (px, py) at ids[(py width + px) spp + j], at
// the settings' sampler's position, lens and time): each sample's
// sample_colour, summed in sample order, then resolve_box. For an engine that
// outputs only winner ids (the GL backend reads them back).
Image resolve_sample_ids(const SurfaceShader& shader, const CameraModel& model, const RenderSettings& settings,
                         const std::vector<std::uint32_t>& ids);

}  // namespace blurcull::frontend
