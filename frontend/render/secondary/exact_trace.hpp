// The scene's triangles in world space at one shutter time, and the exact
// nearest hit of a ray among them, or among them where they are at the
// ray's own time (a loop over every triangle): the bounce reference of the
// dof-secondary renderer's tests and the fallback for the rays no virtual
// view can hold (docs/secondary-rays.md, "The renderer").
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace blurcull::frontend {

struct WorldTriangles {
    std::vector<std::array<glm::vec3, 3>> vertices;  // per triangle, world space
    std::vector<glm::vec3> normals;                  // unit geometric normal by winding, or zero when degenerate
    glm::vec3 box_min{0.0f}, box_max{0.0f};          // bounds of every vertex
    float diagonal() const { return glm::length(box_max - box_min); }
};

// Triangle `triangle` of `scene` at shutter time t in [0, 1] (vertices
// linear in t, as everywhere in the dof-secondary renderer).
std::array<glm::vec3, 3> triangle_at(const Scene& scene, std::size_t triangle, float time);

// The unit geometric normal by winding, or zero when degenerate.
glm::vec3 unit_normal(const std::array<glm::vec3, 3>& vertices);

// Some vertex has another world position at shutter close than at open (a
// moving camera alone does not count: world space stands still).
bool scene_moves(const Scene& scene);

// Every triangle of `scene` at shutter time t in [0, 1].
WorldTriangles world_triangles(const Scene& scene, float time);

struct ExactHit {
    bool hit = false;
    std::uint32_t triangle = 0;
    float distance = 0.0f;  // along the unit direction
};

// The nearest triangle along origin + s direction, s > s_min (direction need
// not be unit; distance is in its units). Two-sided; ties: the lowest index.
// Computed in double (Moller-Trumbore).
ExactHit trace_exact(const WorldTriangles& triangles, glm::vec3 origin, glm::vec3 direction, float s_min);

// trace_exact among the scene's triangles where they are at shutter time
// `time` (each interpolated as world_triangles does, none stored).
ExactHit trace_exact_at(const Scene& scene, float time, glm::vec3 origin, glm::vec3 direction, float s_min);

}  // namespace blurcull::frontend
