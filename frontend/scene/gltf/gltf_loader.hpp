// glTF 2.0 (.gltf / .glb) scenes for blurcull: node animation, morph target
// weights and skinning are sampled at shutter open and close, giving every
// vertex its two world positions; an animated camera node gives view_open /
// view_close. The loader's steps live beside this header: parse,
// conformance, validate, accessors, nodes, animation, morph, skin, meshes,
// camera (docs/scenes.md).
#pragma once

#include "scene/scene.hpp"
#include "scene/scene_error.hpp"
#include "scene/warnings.hpp"

#include <string>

namespace blurcull::frontend {

struct GltfOptions {
    // Animation times (seconds) sampled for the two shutter ends.
    float shutter_open = 0.0f;
    float shutter_close = 1.0f / 24.0f;
    // Scales the shutter interval: close = open + blur_scale * (close - open).
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
    // Linear motion segments over the shutter (docs/reference-renderer.md,
    // "The motion model"): K >= 1 samples the animation at K + 1 times;
    // 0 = auto (the default), K from the largest rotation so the chord stays
    // within 1/16 pixel at an image image_height pixels high.
    int motion_segments = 0;
    int image_height = 480;
    // A frame of a sequence: the automatic camera (and a file camera's
    // automatic focus) frames the scene over its whole animation, sampled at
    // fixed times, instead of over this shutter, so that every frame has the
    // same camera whatever frame range is rendered.
    bool frame_whole_animation = false;
};

// Loads and validates (validate_scene) the file. Throws SceneError
// ("<path>: <problem>") for anything it cannot load. Non-fatal oddities
// (points/lines primitives, non-finite positions, unread extensions, ...) go to
// `warn`, one "<path>: warning: ..." line per kind; an empty sink drops them.
Scene load_gltf_scene(const std::string& path, const GltfOptions& options, const WarningSink& warn = {});

}  // namespace blurcull::frontend
