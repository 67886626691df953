// Where a primary sample meets the reflector it shows, and the rays it
// spawns there, written once for C++ and GLSL (like optics_shared.h, whose
// text GLSL includes first): the dof-secondary resolve
// (render/secondary/secondary_rays.cpp) calls it on the host, and a GPU
// resolve runs the same text in fp64 (GL 4.0), so both start the bounced
// rays at the same points. The arithmetic is double, every operation spelt
// out in GLM's order (dot left to right, cross as GLM writes it, a matrix
// times a vector as GLM pairs the columns) and `precise` in GLSL: on a GL
// that rounds doubles as IEEE does (llvmpipe) the GLSL gives the host's
// floats bit for bit (tests/test_frontend_gl_optics_parity.cpp).
// docs/secondary-rays.md, "The renderer".
#ifndef BLURCULL_RESOLVE_SHARED_H
#define BLURCULL_RESOLVE_SHARED_H

#ifdef __cplusplus
#include "render/common/optics_shared.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>

namespace blurcull::frontend::resolve {
using uint = std::uint32_t;
using optics::bc_dielectric_reflectance;
using optics::bc_mirror_direction;
using optics::bc_optics_dot;
using optics::bc_refract_direction;
using glm::dmat4;
using glm::dvec3;
using glm::dvec4;
using glm::vec2;
using glm::vec3;
using glm::clamp;
using glm::floor;
using std::isinf;
using std::isnan;
using std::sqrt;
#define BC_RESOLVE_FN inline
#define BC_RESOLVE_PRECISE
#else
#define BC_RESOLVE_FN
#define BC_RESOLVE_PRECISE precise
#endif

// A sample's hit in world space: the point, the unit incident direction
// (from the sample's lens point) and the unit geometric normal of the
// triangle at the sample's time; valid false where there is none to trust.
struct SampleHit {
    vec3 point;
    vec3 incident;
    vec3 normal;
    bool valid;
};

// a . b summed left to right.
BC_RESOLVE_FN double bc_resolve_dot(dvec3 a, dvec3 b) {
    BC_RESOLVE_PRECISE double sum = a.x * b.x + a.y * b.y + a.z * b.z;
    return sum;
}

// a x b, each component as GLM's cross computes it.
BC_RESOLVE_FN dvec3 bc_resolve_cross(dvec3 a, dvec3 b) {
    BC_RESOLVE_PRECISE double x = a.y * b.z - b.y * a.z;
    BC_RESOLVE_PRECISE double y = a.z * b.x - b.z * a.x;
    BC_RESOLVE_PRECISE double z = a.x * b.y - b.x * a.y;
    return dvec3(x, y, z);
}

// m v as GLM's dmat4 * dvec4 sums it: (m0 x + m1 y) + (m2 z + m3 w).
BC_RESOLVE_FN dvec4 bc_resolve_transform(dmat4 m, dvec4 v) {
    BC_RESOLVE_PRECISE dvec4 product = (m[0] * v.x + m[1] * v.y) + (m[2] * v.z + m[3] * v.w);
    return product;
}

BC_RESOLVE_FN bool bc_resolve_finite(double x) { return !isinf(x) && !isnan(x); }

// The world point of the sample's lens point `lens` (view space at lens
// depth 0) at shutter time t: the inverse views at open and close
// (`to_world_open`, `to_world_close`) mixed as GLM mixes, x (1 - t) + y t.
BC_RESOLVE_FN dvec3 bc_lens_world(dmat4 to_world_open, dmat4 to_world_close, dvec3 lens, double t) {
    dvec3 at_open = dvec3(bc_resolve_transform(to_world_open, dvec4(lens, 1.0)));
    dvec3 at_close = dvec3(bc_resolve_transform(to_world_close, dvec4(lens, 1.0)));
    BC_RESOLVE_PRECISE dvec3 mixed = at_open * (1.0 - t) + at_close * t;
    return mixed;
}

// The sample's lens ray (origin o, direction d, view space at its time)
// meets the plane of the triangle's view-space vertices v0, v1, v2 at that
// time; the world point has the same barycentric coordinates (least squares
// through the Gram matrix) on the world triangle w0, w1, w2 at that time
// (exact for a static camera). The incident direction runs from the world
// lens point `lens_world`. Invalid where the ray runs in the plane, the
// triangle is degenerate, or the point or a length is not finite.
BC_RESOLVE_FN SampleHit bc_sample_hit(dvec3 v0, dvec3 v1, dvec3 v2, dvec3 w0, dvec3 w1, dvec3 w2, dvec3 o, dvec3 d,
                                      dvec3 lens_world) {
    SampleHit hit;
    hit.point = vec3(0.0f);
    hit.incident = vec3(0.0f);
    hit.normal = vec3(0.0f);
    hit.valid = false;
    BC_RESOLVE_PRECISE dvec3 e1 = v1 - v0;
    BC_RESOLVE_PRECISE dvec3 e2 = v2 - v0;
    dvec3 n = bc_resolve_cross(e1, e2);
    double denom = bc_resolve_dot(n, d);
    if (denom == 0.0 || !bc_resolve_finite(denom)) return hit;
    BC_RESOLVE_PRECISE double s = bc_resolve_dot(n, v0 - o) / denom;
    BC_RESOLVE_PRECISE dvec3 p = o + s * d - v0;
    double d11 = bc_resolve_dot(e1, e1), d12 = bc_resolve_dot(e1, e2), d22 = bc_resolve_dot(e2, e2);
    double p1 = bc_resolve_dot(p, e1), p2 = bc_resolve_dot(p, e2);
    BC_RESOLVE_PRECISE double det = d11 * d22 - d12 * d12;
    if (!(det > 0.0)) return hit;
    BC_RESOLVE_PRECISE double b1 = (d22 * p1 - d12 * p2) / det;
    BC_RESOLVE_PRECISE double b2 = (d11 * p2 - d12 * p1) / det;
    BC_RESOLVE_PRECISE dvec3 point = w0 + b1 * (w1 - w0) + b2 * (w2 - w0);
    BC_RESOLVE_PRECISE dvec3 to_point = point - lens_world;
    dvec3 normal = bc_resolve_cross(w1 - w0, w2 - w0);
    double normal_length = sqrt(bc_resolve_dot(normal, normal));
    double incident_length = sqrt(bc_resolve_dot(to_point, to_point));
    BC_RESOLVE_PRECISE double point_sum = point.x + point.y + point.z;
    if (!(normal_length > 0.0) || !(incident_length > 0.0) || !bc_resolve_finite(point_sum)) return hit;
    BC_RESOLVE_PRECISE dvec3 incident = to_point / incident_length;
    BC_RESOLVE_PRECISE dvec3 unit_normal = normal / normal_length;
    hit.point = vec3(point);
    hit.incident = vec3(incident);
    hit.normal = vec3(unit_normal);
    hit.valid = true;
    return hit;
}

// The part of the lens that lens position (u, v) in [-1, 1]^2 is in: 0 for
// one part, the quadrant (0..3) for 4, a cell of the 4 x 4 grid (0..15)
// for 16 (each sample's rays are clipped with its pixel's others in it).
BC_RESOLVE_FN int bc_lens_cell(float c, int cells) {
    BC_RESOLVE_PRECISE float scaled = (c + 1.0f) * 0.5f * float(cells);
    return clamp(int(floor(scaled)), 0, cells - 1);
}
BC_RESOLVE_FN uint bc_lens_part(vec2 lens, int parts) {
    if (parts <= 1) return 0u;
    int cells = parts == 4 ? 2 : 4;
    return uint(bc_lens_cell(lens.y, cells) * cells + bc_lens_cell(lens.x, cells));
}

// GLM's normalize: v (1 / sqrt(v . v)).
BC_RESOLVE_FN vec3 bc_resolve_normalize(vec3 v) {
    BC_RESOLVE_PRECISE float inverse = 1.0f / sqrt(bc_optics_dot(v, v));
    BC_RESOLVE_PRECISE vec3 unit = v * inverse;
    return unit;
}

// The rays a reflector sample spawns at its hit (`incident` and `normal`
// unit, as bc_sample_hit gives them): a mirror one of weight 1 along the
// mirrored direction; a dielectric of index `ior` a reflected ray of weight
// R (bc_dielectric_reflectance) when R > 0 and a refracted one of weight
// 1 - R when R < 1 and there is one (none under total internal
// reflection); directions normalised.
struct SpawnedRays {
    int count;
    vec3 direction0;
    float weight0;
    vec3 direction1;
    float weight1;
};

BC_RESOLVE_FN SpawnedRays bc_spawn_rays(bool mirror, float ior, vec3 incident, vec3 normal) {
    SpawnedRays spawned;
    spawned.count = 0;
    spawned.direction0 = vec3(0.0f);
    spawned.weight0 = 0.0f;
    spawned.direction1 = vec3(0.0f);
    spawned.weight1 = 0.0f;
    vec3 reflected = bc_resolve_normalize(bc_mirror_direction(incident, normal));
    if (mirror) {
        spawned.count = 1;
        spawned.direction0 = reflected;
        spawned.weight0 = 1.0f;
        return spawned;
    }
    float reflectance = bc_dielectric_reflectance(incident, normal, ior);
    if (reflectance > 0.0f) {
        spawned.count = 1;
        spawned.direction0 = reflected;
        spawned.weight0 = reflectance;
    }
    vec3 t = bc_refract_direction(incident, normal, ior);
    if (reflectance < 1.0f && bc_optics_dot(t, t) > 0.0f) {
        BC_RESOLVE_PRECISE float rest = 1.0f - reflectance;
        vec3 refracted = bc_resolve_normalize(t);
        if (spawned.count == 0) {
            spawned.direction0 = refracted;
            spawned.weight0 = rest;
        } else {
            spawned.direction1 = refracted;
            spawned.weight1 = rest;
        }
        spawned.count += 1;
    }
    return spawned;
}

#ifdef __cplusplus
}  // namespace blurcull::frontend::resolve
#endif
#undef BC_RESOLVE_FN
#undef BC_RESOLVE_PRECISE
#endif  // BLURCULL_RESOLVE_SHARED_H
