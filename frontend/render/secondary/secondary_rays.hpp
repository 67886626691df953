// The resolve step of the dof-secondary renderer: from the stochastic
// rasterizer's per-sample winning triangles to each sample's direct colour
// and the secondary (bounced) rays of the samples that hit a mirror or a
// dielectric, each from the sample's own lens point, time and hit point
// (docs/secondary-rays.md, "The renderer").
#pragma once

#include "render/common/camera_model.hpp"
#include "render/common/render_types.hpp"
#include "render/common/specular_shading.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace blurcull::frontend {

struct SecondaryRay {
    glm::vec3 origin{0.0f};     // world-space hit point on the reflector
    glm::vec3 direction{0.0f};  // unit, world space: mirrored or refracted
    glm::vec3 weight{0.0f};     // what the ray sees is multiplied by this
    std::uint32_t sample = 0;   // the sample it belongs to: (py * width + px) * spp + j
    std::uint32_t lens_part = 0;  // the part of the lens the sample's (u, v) is in
    std::uint32_t triangle = 0;   // the reflector triangle the sample hit
    float time = 0.5f;            // the sample's shutter time, in [0, 1]
};

struct PrimaryResolve {
    std::vector<glm::vec3> sample_colour;  // per sample: diffuse colour, background; 0 on a reflector
    std::vector<SecondaryRay> rays;
    std::uint64_t reflector_samples = 0;   // samples that hit a mirror or dielectric
};

// The lens part of lens position (u, v) in [-1, 1]^2: 0 for one part, the
// quadrant (0..3) for 4, a cell of the 4 x 4 grid (0..15) for 16.
std::uint32_t lens_part_of(glm::vec2 lens, int parts);

// Resolves every sample of `sample_ids` (render_cpu's layout, no_sample_hit
// for none): a diffuse hit gets shade(), a miss the background; a mirror hit
// one ray of weight 1 along bc_mirror_direction; a dielectric hit a
// reflected ray of weight F and a refracted one of weight 1 - F
// (F = bc_dielectric_reflectance; none under total internal reflection).
// Perfect mirrors and clear glass: the base colour is not used (the rule of
// specular_shading.hpp and of the Embree reference). The hit point is the sample's lens ray meeting the
// triangle's plane at the sample's time.
PrimaryResolve resolve_primary(const Scene& scene, const CameraModel& model, const RenderSettings& settings,
                               const std::vector<std::uint32_t>& sample_ids, int lens_parts);

// What a bounced ray that hit `triangle` along unit world `direction` sees:
// shade() of a diffuse triangle; of a mirror or dielectric, its environment
// colour for this ray (specular_environment_colour with the triangle's unit
// world normal `normal`), as the Embree reference does: one bounce only.
glm::vec3 bounce_hit_radiance(const Scene& scene, const std::vector<glm::vec3>& colours, std::uint32_t triangle,
                              glm::vec3 direction, glm::vec3 normal);

// Sums each pixel's samples in sample order and divides by spp (resolve_box):
// the image from per-sample colours.
Image resolve_samples(const std::vector<glm::vec3>& sample_colour, int width, int height, int spp);

}  // namespace blurcull::frontend
