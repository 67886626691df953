// Mirror and dielectric hits shaded from the environment (the "primary-only"
// rule), and the environment itself, for every backend. The optics and the
// environment are optics_shared.h's (bc_environment_radiance,
// bc_specular_environment_colour: the text a GPU shading pass runs too);
// this file maps a scene and a material onto them.
//
//  * environment_radiance: what a ray leaving the scene along a WORLD
//    direction sees: the procedural sky (BC_ENVIRONMENT_SKY) or the scene's
//    background colour (BC_ENVIRONMENT_NONE, also for a zero direction).
//  * specular_environment_colour: a mirror returns the environment along the
//    mirrored direction; a dielectric returns R env(reflected) + (1 - R)
//    env(refracted), R the exact unpolarised Fresnel reflectance (1 under
//    total internal reflection, 0 at normal incidence through index 1). The
//    material's base colour is not used: perfect mirrors and clear glass.
//  * primary_only_colour: the per-triangle colour the backends without
//    secondary rays (cpu, gl, embree --secondary none) give a mirror or
//    dielectric triangle: specular_environment_colour for the pinhole ray
//    from the camera's eye at shutter open to the triangle's centroid, with
//    the triangle's geometric normal at shutter open. Constant per triangle
//    like the flat diffuse shading, so every backend agrees bit for bit.
// docs/reference-renderer.md, "Materials and environment".
#pragma once

#include "render/common/optics_shared.h"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>

namespace blurcull::frontend {

// Radiance seen along a world-space direction (any length) that leaves the scene.
inline glm::vec3 environment_radiance(const Scene& scene, glm::vec3 direction) {
    return optics::bc_environment_radiance(scene.environment == BC_ENVIRONMENT_SKY, scene.background, direction);
}

// The colour of a mirror or dielectric hit from the environment alone.
// `incident` is the unit world direction of the ray, `normal` the unit
// geometric normal (either side). A diffuse material gets black: callers
// shade diffuse hits with shade().
inline glm::vec3 specular_environment_colour(const Scene& scene, const Material& material, glm::vec3 incident,
                                             glm::vec3 normal) {
    if (material.kind != MaterialKind::mirror && material.kind != MaterialKind::dielectric) return glm::vec3(0.0f);
    return optics::bc_specular_environment_colour(material.kind == MaterialKind::mirror, material.ior,
                                                  scene.environment == BC_ENVIRONMENT_SKY, scene.background, incident,
                                                  normal);
}

// The primary-only colour of a mirror or dielectric triangle (see the top of
// the file). A degenerate triangle, or one whose centroid is the eye, sees
// the environment straight along the view direction of the camera.
inline glm::vec3 primary_only_colour(const Scene& scene, std::size_t triangle) {
    const glm::uvec3& tri = scene.triangles[triangle];
    const glm::vec3 p0 = scene.position_open[tri.x];
    const glm::vec3 p1 = scene.position_open[tri.y];
    const glm::vec3 p2 = scene.position_open[tri.z];
    const glm::mat4 camera_to_world = glm::inverse(scene.camera.view_open);
    const glm::vec3 eye(camera_to_world[3]);
    const glm::vec3 forward = -glm::vec3(camera_to_world[2]);
    glm::vec3 incident = (p0 + p1 + p2) / 3.0f - eye;
    const float distance = glm::length(incident);
    glm::vec3 normal = glm::cross(p1 - p0, p2 - p0);
    const float area = glm::length(normal);
    if (!(distance > 0.0f) || !(area > 0.0f) || !std::isfinite(distance * area)) {
        return environment_radiance(scene, forward);
    }
    incident /= distance;
    normal /= area;
    return specular_environment_colour(scene, scene.materials[scene.triangle_material[triangle]], incident, normal);
}

}  // namespace blurcull::frontend
