// Consistency checks and a summary of a Scene, shared by every loader.
#pragma once

#include "scene/scene.hpp"
#include "scene/scene_error.hpp"

#include <glm/glm.hpp>

#include <cstddef>

namespace blurcull::frontend {

// Throws SceneError ("scene 'name': ...") unless: the two position arrays and
// the two per-triangle arrays have matching sizes, every vertex index and
// material index is in range, every position and camera matrix is finite, and
// the camera is usable (0 < yfov < pi, znear > 0, lens_radius >= 0,
// focus_distance > 0), and the motion segments' interior positions and views
// (position_at, view_at) have one entry per vertex (per interior time), are
// finite and within max_motion_segments. The scene makers call it on what they return.
void validate_scene(const Scene& scene);

// What a backend calls before rendering: nothing for a scene its maker
// validated (scene.validated), validate_scene for any other.
void require_valid_scene(const Scene& scene);

struct SceneStats {
    std::size_t triangles = 0;
    std::size_t vertices = 0;
    glm::vec3 bounds_min{0.0f};  // over both shutter ends; zero when empty
    glm::vec3 bounds_max{0.0f};
    bool object_motion = false;           // some vertex differs between open and close
    float max_vertex_displacement = 0.0f; // world units, largest |close - open|
    bool camera_motion = false;           // view_open != view_close
    float camera_displacement = 0.0f;     // distance between the two eye points
    float camera_rotation = 0.0f;         // radians between the two view orientations
    float lens_radius = 0.0f;
    float focus_distance = 0.0f;
};

// Size, bounds and blur of the scene: triangle and vertex counts, bounds over
// both shutter ends, how far vertices and camera move, the lens.
SceneStats describe(const Scene& scene);

}  // namespace blurcull::frontend
