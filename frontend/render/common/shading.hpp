// Deterministic flat shading, identical in every backend so their images
// can be compared pixel by pixel.
//
// colour(triangle) = base colour of its material * (0.2 + 0.8 |n . l| light
// colour) + emissive, where n is the unit geometric normal of the triangle's
// WORLD positions at shutter OPEN (two-sided, hence |.|) and l the unit light
// direction. The colour is constant over the shutter and the triangle. A
// triangle with surface attributes (textures, vertex colours, normals, an
// alpha mask) is shaded per sample instead: surface_shading.hpp, the
// contract in docs/reference-renderer.md, "Shading". A sample that hits nothing gets
// scene.background; a pixel is the mean of its samples (box filter): the
// sample colours summed in float in sample order j = 0 .. spp-1, then divided
// by spp (resolve_box), so backends that agree on every sample agree bit for bit.
#pragma once

#include "render/common/surface_shared.h"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>
#include <vector>

namespace blurcull::frontend {

constexpr float shading_ambient = 0.2f;
constexpr float shading_diffuse = 0.8f;

// The caller guarantees the triangle's vertex and material indices are valid
// (validate_scene in scene/scene_checks.hpp checks them). A degenerate triangle or
// zero light direction (or one so large its length overflows) gets ambient light only.
inline glm::vec3 shade(const Scene& scene, std::size_t triangle) {
    const glm::uvec3& tri = scene.triangles[triangle];
    glm::vec3 p0 = scene.position_open[tri.x];
    glm::vec3 normal = glm::cross(scene.position_open[tri.y] - p0, scene.position_open[tri.z] - p0);
    const float lambert = surface::bc_lambert(normal, scene.light_direction);
    const Material& material = scene.materials[scene.triangle_material[triangle]];
    return surface::bc_lit_colour(material.base_color, lambert, scene.light_color, material.emissive, shading_ambient,
                                  shading_diffuse);
}

// shade() for every triangle, computed once per render.
inline std::vector<glm::vec3> shade_all(const Scene& scene) {
    std::vector<glm::vec3> colours(scene.triangles.size());
    for (std::size_t t = 0; t < colours.size(); ++t) colours[t] = shade(scene, t);
    return colours;
}

inline glm::vec3 resolve_box(glm::vec3 sample_sum, int spp) { return sample_sum / static_cast<float>(spp); }

}  // namespace blurcull::frontend
