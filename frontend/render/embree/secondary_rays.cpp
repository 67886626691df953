#include "render/embree/secondary_rays.hpp"

#include "render/embree/embree_options.hpp"

#include "render/common/optics_shared.h"
#include "render/common/specular_shading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace blurcull::frontend {

const char* secondary_name(EmbreeSecondary secondary) {
    return secondary == EmbreeSecondary::bounce ? "bounce" : "none";
}

EmbreeSecondary parse_embree_secondary(const std::string& name) {
    if (name == "bounce") return EmbreeSecondary::bounce;
    if (name == "none") return EmbreeSecondary::none;
    throw std::invalid_argument("embree secondary rays: '" + name + "' is not bounce or none");
}

int specular_rays(const Material& material, glm::vec3 hit, glm::vec3 incident, glm::vec3 normal, float offset,
                  WeightedRay out[2]) {
    if (material.kind == MaterialKind::diffuse) return 0;
    const glm::vec3 towards_viewer = optics::bc_facing_normal(normal, incident);
    const glm::vec3 reflected = optics::bc_mirror_direction(incident, normal);
    if (material.kind == MaterialKind::mirror) {
        out[0] = WeightedRay{hit + offset * towards_viewer, reflected, 1.0f};
        return 1;
    }
    const float reflectance = optics::bc_dielectric_reflectance(incident, normal, material.ior);
    int count = 0;
    if (reflectance > 0.0f) out[count++] = WeightedRay{hit + offset * towards_viewer, reflected, reflectance};
    if (reflectance < 1.0f) {
        const glm::vec3 refracted = optics::bc_refract_direction(incident, normal, material.ior);
        if (refracted == glm::vec3(0.0f)) return count;  // total internal reflection that R rounded below 1
        out[count++] = WeightedRay{hit - offset * towards_viewer, glm::normalize(refracted), 1.0f - reflectance};
    }
    return count;
}

SecondaryTracer::SecondaryTracer(RTCScene rtc_scene, const Scene& scene, const CameraModel& model,
                                 const std::vector<glm::vec3>& colours)
    : rtc_scene_(rtc_scene), scene_(scene), model_(model), colours_(colours),
      view_to_world_open_(glm::inverse(glm::mat3(model.view_open))),
      view_to_world_close_(glm::inverse(glm::mat3(model.view_close))),
      camera_moves_(model.view_open != model.view_close) {
    rtcInitIntersectContext(&context_);
}

glm::vec3 SecondaryTracer::view_vertex(std::uint32_t vertex, float time) const {
    return model_.view_position_at(scene_, vertex, time);
}

// Directions are turned back to world space for the environment with the
// inverse of the view's rotation; for a moving camera, of the view matrix
// interpolated linearly to the sample's time (the motion model moves view
// positions linearly, so this is its rotation to first order).
glm::vec3 SecondaryTracer::to_world(glm::vec3 view_direction, float time) const {
    if (!camera_moves_) return view_to_world_open_ * view_direction;
    const glm::mat3 view = (1.0f - time) * glm::mat3(model_.view_open) + time * glm::mat3(model_.view_close);
    return glm::inverse(view) * view_direction;
}

glm::vec3 SecondaryTracer::bounce(glm::vec3 origin, glm::vec3 direction, float time, std::uint32_t triangle) {
    const glm::uvec3& tri = scene_.triangles[triangle];
    const glm::vec3 p0 = view_vertex(tri.x, time);
    const glm::vec3 normal_unscaled = glm::cross(view_vertex(tri.y, time) - p0, view_vertex(tri.z, time) - p0);
    const float area = glm::length(normal_unscaled);
    const glm::vec3 incident = glm::normalize(direction);
    const float facing = glm::dot(normal_unscaled, incident);
    // Embree hit it, so it has an area and faces the ray but for rounding.
    if (!(area > 0.0f) || facing == 0.0f) return colours_[triangle];
    const glm::vec3 normal = normal_unscaled / area;
    const float distance = glm::dot(normal_unscaled, p0 - origin) / facing;
    const glm::vec3 hit = origin + distance * incident;
    // Far enough for float rounding of the hit's coordinates, near enough
    // not to skip geometry: 1e-4 of the hit's largest coordinate (or of 1).
    const float offset = 1e-4f * std::max({1.0f, std::abs(hit.x), std::abs(hit.y), std::abs(hit.z)});
    WeightedRay rays[2];
    const int count = specular_rays(scene_.materials[scene_.triangle_material[triangle]], hit, incident, normal,
                                    offset, rays);
    glm::vec3 colour(0.0f);
    for (int i = 0; i < count; ++i) colour += rays[i].weight * trace(rays[i], time);
    return colour;
}

glm::vec3 SecondaryTracer::trace(const WeightedRay& ray, float time) {
    RTCRayHit query;
    query.ray.org_x = ray.origin.x;
    query.ray.org_y = ray.origin.y;
    query.ray.org_z = ray.origin.z;
    query.ray.tnear = 0.0f;
    query.ray.dir_x = ray.direction.x;
    query.ray.dir_y = ray.direction.y;
    query.ray.dir_z = ray.direction.z;
    query.ray.time = time;
    query.ray.tfar = std::numeric_limits<float>::infinity();
    query.ray.mask = 0xFFFFFFFFu;
    query.ray.id = 0;
    query.ray.flags = 0;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.primID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtc_scene_, &context_, &query);
    ++rays_traced_;
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return environment_radiance(scene_, to_world(ray.direction, time));
    const std::uint32_t triangle = query.hit.primID;
    const Material& material = scene_.materials[scene_.triangle_material[triangle]];
    if (material.kind == MaterialKind::diffuse) return colours_[triangle];
    const glm::vec3 normal = to_world(glm::vec3(query.hit.Ng_x, query.hit.Ng_y, query.hit.Ng_z), time);
    const float length = glm::length(normal);
    if (!(length > 0.0f)) return colours_[triangle];
    return specular_environment_colour(scene_, material, glm::normalize(to_world(ray.direction, time)),
                                       normal / length);
}

}  // namespace blurcull::frontend
