// Mirror and glass optics and the environment, written once for C++ and GLSL
// (like gpu_layout_shared.h): every backend that bounces a ray (the Embree
// reference, the CPU and GL dof-secondary renderers) and every backend that
// shades a miss calls these, so their images can be compared sample by sample.
// docs/reference-renderer.md, "Materials and environment".
//
// Conventions: directions are world space; `incident` points TOWARDS the
// surface (the ray's direction), `normal` is the unit geometric normal on
// either side (the functions orient it against `incident` themselves).
//
// Every operation is spelt out in one order, each value `precise` in GLSL
// (no fused or reordered products): dot products summed left to right as
// GLM sums them (GLSL's dot() may not: llvmpipe adds the last two terms
// first), mix as GLM's x (1 - a) + y a. So a GL that rounds as IEEE floats
// do gives the host's values bit for bit (tests/test_frontend_gl_optics_parity.cpp),
// and the host's are GLM's, unchanged.
#ifndef BLURCULL_OPTICS_SHARED_H
#define BLURCULL_OPTICS_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cmath>

namespace blurcull::frontend::optics {
using glm::vec3;
using glm::max;
using glm::min;
using glm::clamp;
using glm::abs;
using glm::sqrt;
using std::isinf;
using std::isnan;
#define BC_OPTICS_FN inline
#define BC_OPTICS_PRECISE
#else
#define BC_OPTICS_FN
#define BC_OPTICS_PRECISE precise
#endif

// a . b, summed left to right (GLM's order).
BC_OPTICS_FN float bc_optics_dot(vec3 a, vec3 b) {
    BC_OPTICS_PRECISE float sum = a.x * b.x + a.y * b.y + a.z * b.z;
    return sum;
}

// GLM's mix of two colours: x (1 - a) + y a.
BC_OPTICS_FN vec3 bc_optics_mix(vec3 x, vec3 y, float a) {
    BC_OPTICS_PRECISE vec3 mixed = x * (1.0f - a) + y * a;
    return mixed;
}

// The normal facing the incident ray (dot(result, incident) <= 0).
BC_OPTICS_FN vec3 bc_facing_normal(vec3 normal, vec3 incident) {
    return bc_optics_dot(normal, incident) > 0.0f ? -normal : normal;
}

// Perfect mirror: incident - 2 (n . incident) n, for a unit normal on either side.
BC_OPTICS_FN vec3 bc_mirror_direction(vec3 incident, vec3 normal) {
    BC_OPTICS_PRECISE vec3 mirrored = incident - 2.0f * bc_optics_dot(normal, incident) * normal;
    return mirrored;
}

// Unpolarised Fresnel reflectance of a smooth dielectric boundary (the mean of
// the s and p terms, exact, not Schlick's approximation). cos_i = |n . i| of the
// unit incident direction, eta = n_incident / n_transmitted. Returns 1 under
// total internal reflection, exactly 0 for eta = 1 (an index-matched boundary
// is invisible; the formula's rounding of cos_t would leave ~1e-8).
BC_OPTICS_FN float bc_fresnel_dielectric(float cos_i, float eta) {
    if (eta == 1.0f) return 0.0f;
    BC_OPTICS_PRECISE float cos_i2 = 1.0f - cos_i * cos_i;
    BC_OPTICS_PRECISE float sin_t2 = eta * eta * max(0.0f, cos_i2);
    if (sin_t2 >= 1.0f) return 1.0f;
    BC_OPTICS_PRECISE float cos_t = sqrt(1.0f - sin_t2);
    BC_OPTICS_PRECISE float r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    BC_OPTICS_PRECISE float r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    BC_OPTICS_PRECISE float mean = 0.5f * (r_s * r_s + r_p * r_p);
    return clamp(mean, 0.0f, 1.0f);
}

// Refraction through a boundary between air (index 1) and a medium of index
// `ior`: the side is told by the geometric normal (entering when the ray meets
// the side `normal` points to). Unit incident and normal. Returns the zero
// vector under total internal reflection; the incident direction itself for
// index 1.
BC_OPTICS_FN vec3 bc_refract_direction(vec3 incident, vec3 normal, float ior) {
    bool entering = bc_optics_dot(normal, incident) < 0.0f;
    vec3 n = entering ? normal : -normal;
    BC_OPTICS_PRECISE float inverse = 1.0f / ior;
    float eta = entering ? inverse : ior;
    if (eta == 1.0f) return incident;  // index-matched: straight on, even at grazing angles where 1 - cos^2 rounds to 1
    float cos_i = -bc_optics_dot(n, incident);
    BC_OPTICS_PRECISE float cos_i2 = 1.0f - cos_i * cos_i;
    BC_OPTICS_PRECISE float sin_t2 = eta * eta * max(0.0f, cos_i2);
    if (sin_t2 >= 1.0f) return vec3(0.0f);
    BC_OPTICS_PRECISE vec3 refracted = eta * incident + (eta * cos_i - sqrt(1.0f - sin_t2)) * n;
    return refracted;
}

// Fresnel reflectance of the same boundary for a unit incident direction.
BC_OPTICS_FN float bc_dielectric_reflectance(vec3 incident, vec3 normal, float ior) {
    float cosine = bc_optics_dot(normal, incident);
    BC_OPTICS_PRECISE float inverse = 1.0f / ior;
    float eta = cosine < 0.0f ? inverse : ior;
    return bc_fresnel_dielectric(min(1.0f, abs(cosine)), eta);
}

// Environment kinds: BC_ENVIRONMENT_NONE / BC_ENVIRONMENT_SKY, defined with
// Scene::environment in scene/scene.hpp (the scene layer owns them).

// The procedural sky: radiance seen along a unit direction (y up). A smooth
// gradient from the horizon to the zenith above, a darker ground below, and
// soft bands in azimuth so a blurred reflection of the sky shows its blur.
// Smooth everywhere, so sampling noise stays low and backends agree within
// rounding.
BC_OPTICS_FN vec3 bc_sky_radiance(vec3 direction) {
    float y = clamp(direction.y, -1.0f, 1.0f);
    vec3 horizon = vec3(0.85f, 0.88f, 0.92f);
    vec3 zenith = vec3(0.25f, 0.45f, 0.85f);
    vec3 ground = vec3(0.30f, 0.26f, 0.22f);
    BC_OPTICS_PRECISE float across = direction.x * direction.x + direction.z * direction.z;
    float bands = 0.0f;
    if (across > 0.0f) {
        // cos(8 phi) from (x, z) without trigonometry: Chebyshev T8 of cos(phi).
        BC_OPTICS_PRECISE float c = direction.x / sqrt(across);
        BC_OPTICS_PRECISE float c2 = c * c;
        BC_OPTICS_PRECISE float t8 = 1.0f + c2 * (-32.0f + c2 * (160.0f + c2 * (-256.0f + c2 * 128.0f)));
        BC_OPTICS_PRECISE float scaled = 0.08f * t8;
        bands = scaled;
    }
    BC_OPTICS_PRECISE float below = -8.0f * y;
    vec3 sky = y >= 0.0f ? bc_optics_mix(horizon, zenith, sqrt(y)) : bc_optics_mix(horizon, ground, min(1.0f, below));
    BC_OPTICS_PRECISE vec3 banded = sky * (1.0f + bands);
    return banded;
}

// What a ray along `direction` (any length) that leaves the scene sees:
// the procedural sky where `sky` (Scene::environment BC_ENVIRONMENT_SKY),
// else the `background` colour; the background too along a zero or
// non-finite direction.
BC_OPTICS_FN vec3 bc_environment_radiance(bool sky, vec3 background, vec3 direction) {
    float size = sqrt(bc_optics_dot(direction, direction));
    if (!sky || !(size > 0.0f) || isinf(size) || isnan(size)) return background;
    BC_OPTICS_PRECISE vec3 unit = direction / size;
    return bc_sky_radiance(unit);
}

// The colour of a mirror (`mirror`) or a dielectric of index `ior` from the
// environment alone, for the unit incident direction and unit geometric
// normal (either side): a mirror's environment along the mirrored ray; a
// dielectric's R times that plus 1 - R times the environment along the
// refracted ray (none under total internal reflection). One bounce.
BC_OPTICS_FN vec3 bc_specular_environment_colour(bool mirror, float ior, bool sky, vec3 background, vec3 incident,
                                                 vec3 normal) {
    vec3 reflected = bc_environment_radiance(sky, background, bc_mirror_direction(incident, normal));
    if (mirror) return reflected;
    float reflectance = bc_dielectric_reflectance(incident, normal, ior);
    BC_OPTICS_PRECISE vec3 colour = reflectance * reflected;
    if (!(reflectance < 1.0f)) return colour;
    vec3 through = bc_environment_radiance(sky, background, bc_refract_direction(incident, normal, ior));
    BC_OPTICS_PRECISE vec3 both = colour + (1.0f - reflectance) * through;
    return both;
}

#ifdef __cplusplus
}  // namespace blurcull::frontend::optics
#endif
#undef BC_OPTICS_FN
#undef BC_OPTICS_PRECISE
#endif  // BLURCULL_OPTICS_SHARED_H
