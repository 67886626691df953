// Deterministic flat shading, identical in every backend so their images
// can be compared pixel by pixel.
//
// colour(triangle) = base colour of its material * (0.2 + 0.8 |n . l| light
// colour) + emissive, where n is the unit geometric normal of the triangle's
// WORLD positions at shutter OPEN (two-sided, hence |.|) and l the unit light
// direction, plus the same term for each of scene.lights (point and spot
// lights with their falloffs at the centroid); KHR_materials_unlit: the base
// colour. The colour is constant over the shutter and the triangle. A
// triangle with surface attributes (textures, vertex colours, normals, an
// alpha mask) is shaded per sample instead: surface_shading.hpp, the
// contract in docs/reference-renderer.md, "Shading". A sample that hits nothing gets
// scene.background; a pixel is the mean of its samples (box filter): the
// sample colours summed in float in sample order j = 0 .. spp-1, then divided
// by spp (resolve_box), so backends that agree on every sample agree bit for bit.
#pragma once

#include "render/common/parallel_items.hpp"
#include "render/common/specular_shading.hpp"
#include "render/common/surface_shared.h"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>
#include <vector>

namespace blurcull::frontend {

constexpr float shading_ambient = 0.2f;
constexpr float shading_diffuse = 0.8f;

// The diffuse light at world point `p` with normal `normal`: the scene's
// directional light, then each of scene.lights (bc_punctual_light; the sum
// is the directional term alone, bit for bit, where there are none).
inline glm::vec3 scene_light(const Scene& scene, glm::vec3 p, glm::vec3 normal) {
    glm::vec3 light = surface::bc_punctual_light(BC_LIGHT_DIRECTIONAL, glm::vec3(0.0f), scene.light_direction,
                                                 scene.light_color, 0.0f, 1.0f, 1.0f, p, normal, shading_diffuse);
    for (const PunctualLight& l : scene.lights) {
        light += surface::bc_punctual_light(static_cast<int>(l.type), l.position, l.direction, l.colour, l.range,
                                            l.cos_inner, l.cos_outer, p, normal, shading_diffuse);
    }
    return light;
}

// Whether some light's contribution varies over a flat triangle (a point or
// spot light): then every diffuse triangle shades per hit (surface_shading.hpp).
inline bool lights_vary(const Scene& scene) {
    for (const PunctualLight& l : scene.lights)
        if (l.type != LightType::directional) return true;
    return false;
}

// The caller guarantees the triangle's vertex and material indices are valid
// (validate_scene in scene/scene_checks.hpp checks them). A degenerate triangle or
// zero light direction (or one so large its length overflows) gets ambient light only.
// A mirror or dielectric triangle gets primary_only_colour (specular_shading.hpp).
inline glm::vec3 shade(const Scene& scene, std::size_t triangle) {
    if (scene.materials[scene.triangle_material[triangle]].kind != MaterialKind::diffuse) {
        return primary_only_colour(scene, triangle);
    }
    const glm::uvec3& tri = scene.triangles[triangle];
    glm::vec3 p0 = scene.position_open[tri.x];
    glm::vec3 normal = glm::cross(scene.position_open[tri.y] - p0, scene.position_open[tri.z] - p0);
    // The lights at the centroid (point and spot lights shade per hit instead).
    const glm::vec3 centroid = (p0 + scene.position_open[tri.y] + scene.position_open[tri.z]) / 3.0f;
    const Material& material = scene.materials[scene.triangle_material[triangle]];
    return surface::bc_material_colour(material.unlit, material.base_color, scene_light(scene, centroid, normal),
                                       material.emissive, shading_ambient);
}

// shade() for every triangle, computed once per render; on `threads`
// threads (render_threads), runs of 16,384 triangles each: the same colours
// on any number.
inline std::vector<glm::vec3> shade_all(const Scene& scene, int threads = 1) {
    std::vector<glm::vec3> colours(scene.triangles.size());
    run_parallel_ranges(threads, colours.size(), 16384, [&](std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) colours[t] = shade(scene, t);
    });
    return colours;
}

inline glm::vec3 resolve_box(glm::vec3 sample_sum, int spp) { return sample_sum / static_cast<float>(spp); }

}  // namespace blurcull::frontend
