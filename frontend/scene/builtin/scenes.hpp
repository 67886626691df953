// The four built-in scenes, one file each (hand.cpp, car.cpp,
// dragonfly.cpp, forest.cpp), and the dispatch by name before validation.
// Public entry points: scene/builtin_scenes.hpp.
#pragma once

#include "scene/builtin_scenes.hpp"
#include "scene/scene.hpp"

#include <string>

namespace blurcull::frontend::builtin {

// ~15k triangles, static, defocus only.
Scene make_hand(float blur, float aspect);
// ~54k triangles, object motion only.
Scene make_car(float blur, float aspect);
// ~85k triangles (centimetres), camera motion only.
Scene make_dragonfly(float blur, float aspect);
// ~170k triangles, camera motion and defocus.
Scene make_forest(float blur, float aspect);
// The forest's trees and walk at 10 million triangles (large_scene_names()).
Scene make_forest_10m(float blur, float aspect);

// make_builtin_scene without the final validate_scene: for load_scene
// (scene/load_scene.hpp), which applies its overrides first and then
// validates once. Throws SceneError for an unknown name or bad options.
Scene build_scene(const std::string& name, const SceneOptions& options);

}  // namespace blurcull::frontend::builtin
