// The four built-in secondary-ray scenes (mirror_sphere.cpp, water.cpp,
// curved_mirror.cpp, mirror_motion.cpp) and what they share: the specular
// materials, the sky, the framing. docs/secondary-rays.md, "Scenes".
#pragma once

#include "scene/scene.hpp"

#include <cstdint>
#include <string>

namespace blurcull::frontend::builtin {

// The background colour of the secondary-ray scenes: the sky's horizon
// colour (optics_shared.h), so primary rays that miss (which every backend
// shades with the background) meet the sky that the bounced rays see.
inline const glm::vec3 kSecondarySceneBackground(0.85f, 0.88f, 0.92f);

// Adds a mirror or dielectric material (base colour unused); returns its index.
std::uint32_t add_specular_material(Scene& scene, const std::string& name, MaterialKind kind, float ior);

// The vertical field of view of a scene composed for a 4:3 image with
// vertical field `yfov_at_4_3`, widened for narrower images so the width
// shown never shrinks.
float secondary_scene_yfov(float yfov_at_4_3, float aspect);

// How a secondary-ray scene is seen: a still camera (no motion), the thin
// lens focused at `focus_distance`, one light, the sky as environment.
struct SecondarySceneView {
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f, 0.0f, -1.0f};
    float yfov_at_4_3 = 0.8f;     ///< radians, for a 4:3 image (secondary_scene_yfov)
    float focus_distance = 1.0f;  ///< scene units from the eye
    float lens_radius = 0.1f;     ///< at blur 1; scaled by the scene's blur
    glm::vec3 light_direction{0.0f, 1.0f, 0.0f};  ///< towards the light, normalised here
};

// Sets the camera, light, background and environment of a secondary-ray scene.
void set_secondary_scene_view(Scene& scene, const SecondarySceneView& view, float blur, float aspect);

// ~30k triangles, static, defocus: a mirror sphere on a chessboard with
// objects behind the camera.
Scene make_mirror_sphere(float blur, float aspect);
// ~30k triangles, static, defocus: a gently waved water surface (index 1.33)
// over a chessboard pool floor and objects under and above it.
Scene make_water(float blur, float aspect);
// ~12k triangles, static, defocus: a chessboard before three mirrors of
// different curvature (flat, gently and strongly convex), JCST 2013 Fig. 6.
Scene make_curved_mirror(float blur, float aspect);
// ~8k triangles, object motion and defocus: a flat mirror before a
// chessboard, objects crossing it in front and behind the camera (the
// motion seen in a mirror; --bounce-time-slices).
Scene make_mirror_motion(float blur, float aspect);

}  // namespace blurcull::frontend::builtin
