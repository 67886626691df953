// glTF 2.0 (.gltf / .glb) scenes for blurcull: node animation and skinning
// are sampled at shutter open and close, giving every vertex its two world
// positions; an animated camera node gives view_open / view_close.
#pragma once

#include "scene/builtin_scenes.hpp"
#include "scene/scene.hpp"
#include "scene/scene_error.hpp"

#include <string>

namespace blurcull::frontend {

struct GltfOptions {
    // Animation times (seconds) sampled for the two shutter ends.
    float shutter_open = 0.0f;
    float shutter_close = 1.0f / 24.0f;
    // Scales the shutter interval: close = open + blur_scale * (close - open).
    // For built-in scenes (load_scene) it scales motion and lens instead.
    float blur_scale = 1.0f;
    // Index into the file's cameras; -1 = the first perspective camera used
    // by a node, or an automatic camera framing the scene when there is none.
    int camera_index = -1;
    float aspect = 4.0f / 3.0f;  // image width / height
    // Index into the file's animations; -1 = no animation. 0 on a file
    // without animations simply means a static scene.
    int animation_index = 0;
    // glTF has no aperture: the thin lens comes from here. A negative focus
    // distance means "the view depth of the scene's bounding-box centre".
    float lens_radius = 0.0f;
    float focus_distance = -1.0f;
};

// Throws SceneError("<path>: <problem>") for anything it cannot load.
// Non-fatal oddities (points/lines primitives, non-finite positions, morph
// targets, ...) print one "<path>: warning: ..." line per kind on stderr.
Scene load_gltf_scene(const std::string& path, const GltfOptions& options);

// A path ending in .gltf / .glb (any case) loads the file; any other name
// is a built-in scene (blur_scale and aspect are passed on).
Scene load_scene(const std::string& name_or_path, const GltfOptions& options = GltfOptions{});

}  // namespace blurcull::frontend
