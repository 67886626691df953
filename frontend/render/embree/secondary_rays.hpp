// One exact bounce of reflection or refraction for the Embree reference
// (docs/secondary-rays.md, "The Embree reference"). A primary sample whose
// winning triangle is a mirror or a dielectric is resolved at its own ray and
// shutter time (the hit point on the triangle moved to that time, its
// geometric normal), then:
//  * mirror: one reflected ray, weight 1;
//  * dielectric: the reflected ray with weight R and the refracted ray with
//    weight 1 - R, R the exact unpolarised Fresnel reflectance
//    (optics_shared.h); the refracted ray continues straight, with no second
//    refraction where it leaves the medium. Under total internal reflection
//    R = 1 and only the reflected ray is traced; index 1 gives R = 0 and the
//    refracted ray is the incident one (straight through).
// Each secondary ray is traced once at the sample's shutter time. It gets the
// environment when it misses, the flat diffuse colour when it hits a diffuse
// triangle, and, when it hits another mirror or dielectric, that surface's
// environment colour along its own bounced directions (no second bounce:
// the JCST 2013 rule).
#pragma once

#include "render/common/camera_model.hpp"
#include "scene/scene.hpp"

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace blurcull::frontend {

// A secondary ray in view space at a shutter time, and its weight.
struct WeightedRay {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f};  // unit
    float weight = 0.0f;
};

// The rays a mirror or dielectric spawns at `hit` for the unit `incident`
// direction and unit geometric `normal` (either side): one for a mirror, one
// or two (weights R and 1 - R, zero-weight rays left out) for a dielectric,
// none for a diffuse material. Origins are `hit` pushed off the surface by
// `offset` to the side each ray leaves on, so it does not hit its own triangle.
// Returns how many of out[0..1] it filled.
int specular_rays(const Material& material, glm::vec3 hit, glm::vec3 incident, glm::vec3 normal, float offset,
                  WeightedRay out[2]);

// Resolves and bounces the specular samples of one thread's rows. Not
// thread-safe; one per thread.
class SecondaryTracer {
public:
    // `colours` are shade_all(scene); the rtc_scene holds the scene's
    // view-space triangles with the two shutter time steps.
    SecondaryTracer(RTCScene rtc_scene, const Scene& scene, const CameraModel& model,
                    const std::vector<glm::vec3>& colours);

    // The colour of the primary ray (view space, any direction length, at
    // shutter time `time`) that hit the mirror or dielectric `triangle`.
    glm::vec3 bounce(glm::vec3 origin, glm::vec3 direction, float time, std::uint32_t triangle);

    // Secondary rays traced so far.
    std::uint64_t rays_traced() const { return rays_traced_; }

private:
    glm::vec3 trace(const WeightedRay& ray, float time);
    glm::vec3 to_world(glm::vec3 view_direction, float time) const;
    glm::vec3 view_vertex(std::uint32_t vertex, float time) const;

    RTCScene rtc_scene_;
    const Scene& scene_;
    const CameraModel& model_;
    const std::vector<glm::vec3>& colours_;
    glm::mat3 view_to_world_open_;
    glm::mat3 view_to_world_close_;
    bool camera_moves_;
    RTCIntersectContext context_;
    std::uint64_t rays_traced_ = 0;
};

}  // namespace blurcull::frontend
