// Procedural stand-ins for the four workloads of the clip-space sample culling
// thesis (Hand, Car, Dragonfly, FairyForest): similar triangle counts and the
// same kind of blur, generated deterministically (no files, no std::
// distributions), so every backend and benchmark sees identical geometry.
#pragma once

#include "scene/scene.hpp"
#include "scene/scene_error.hpp"

#include <string>
#include <vector>

namespace blurcull::frontend {

struct SceneOptions {
    // Multiplies every blur: object displacement, camera displacement and
    // rotation angle, and lens radius (the thesis's "x2" rows are 2).
    float blur_scale = 1.0f;
    // Image width / height; the camera's yfov is chosen so the subject fits.
    float aspect = 4.0f / 3.0f;
};

// "hand", "car", "dragonfly", "forest", or one of secondary_scene_names()
// or large_scene_names(), validated. Throws SceneError for any
// other name, or for a blur_scale / aspect that is negative, zero (aspect) or
// not finite. Each scene is built in scene/builtin/<name>.cpp from the shapes
// of scene/builtin/mesh_builder.hpp.
Scene make_builtin_scene(const std::string& name, const SceneOptions& options);

// The four stand-ins for the thesis workloads (all diffuse), in the order
// `blurcull scenes` lists them first; the thesis tables and benchmarks
// iterate these.
std::vector<std::string> builtin_scene_names();

// The built-in secondary-ray scenes, made by make_builtin_scene like the
// others: "mirror-sphere", "water", "curved-mirror", "mirror-motion"
// (scene/builtin/secondary_scenes.hpp, docs/secondary-rays.md "Scenes").
// They have mirror or dielectric materials and the sky environment; the
// first three are static with defocus only, mirror-motion has object motion
// too.
std::vector<std::string> secondary_scene_names();

// The built-in scale tests: "forest-10m" (the forest's trees and walk at 10
// million triangles, ~2 s and ~1 GB to build). Listed by `blurcull scenes`,
// left out of the lists the tests and benchmarks iterate.
std::vector<std::string> large_scene_names();

// One built-in scene as `blurcull scenes` lists it.
struct BuiltinSceneInfo {
    std::string name;
    std::string description;  // one line: what it shows, its blur, how to see it
};

// Every built-in scene, builtin_scene_names(), secondary_scene_names(), then
// large_scene_names(), with a one-line description each: what `blurcull
// scenes` prints (name, then description). The lists come from one table
// (builtin_scenes.cpp).
std::vector<BuiltinSceneInfo> builtin_scene_catalogue();

// `source` with the lens closed, the camera still, and every triangle given
// its own vertices: triangle t with t % moving_every == 0 keeps the motion it
// had on screen (the camera's motion made its own, plus its own), the others
// stand still at their shutter-open place. With moving_every = 10, 90% of the
// triangles are static and in focus: the GL backend's static-path workload
// (docs/gl-backend.md). A scene with no motion (the hand) comes out all
// static. `source` must be valid; so is the result (not validated again).
// Throws SceneError when moving_every < 1.
Scene make_mostly_static(const Scene& source, int moving_every);

}  // namespace blurcull::frontend
