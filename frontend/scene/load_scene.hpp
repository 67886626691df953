// One entry point for "a scene by name or path, with the image's aspect and
// the user's blur, shutter, lens and focus settings": picks the built-in
// scene or the glTF loader by the rule of scene_name.hpp, applies the
// settings, and validates the result once. The backends trust what it
// returns (scene.hpp).
#pragma once

#include "scene/scene.hpp"
#include "scene/scene_error.hpp"
#include "scene/warnings.hpp"

#include <string>
#include <utility>

namespace blurcull::frontend {

// One frame of an animation sequence (blurcull render --frames): the
// shutter opens at the frame's time and stays open for shutter_angle / 360
// of the frame interval (the film convention: 180 degrees is half of it).
struct FrameShutter {
    long frame = 0;                       // >= 0
    double fps = 24.0;                    // frames per second, > 0 (glTF; built-in scenes count frames)
    double shutter_angle_degrees = 180.0; // in (0, 360]
};

struct SceneSettings {
    float aspect = 4.0f / 3.0f;  // width / height of the image
    // Multiplies every blur: a built-in scene's motion and lens, a glTF
    // file's shutter interval, and the lens radius / f-number set here.
    double blur_scale = 1.0;
    bool has_shutter = false;    // else the scene's own shutter
    // glTF: animation seconds. Built-in scenes: fractions of their nominal
    // shutter [0, 1], whose linear motion is re-sampled there.
    float shutter_open = 0.0f;
    float shutter_close = 1.0f;
    // A frame of a sequence instead: the shutter interval on the scene's
    // animation clock that frame_shutter_interval gives (over has_shutter).
    bool has_frame = false;
    FrameShutter frame;
    double lens_radius = -1.0;   // >= 0: the lens radius (times blur_scale); < 0: the scene's own
    double fstop = -1.0;         // > 0: the lens radius of this f-number (times blur_scale)
    double focus = -1.0;         // > 0: the focus distance
    // glTF: linear motion segments over the shutter, 1 to max_motion_segments,
    // or 0 = auto (the default) for an image image_height pixels high
    // (GltfOptions). Built-in scenes move linearly: any K is the same motion,
    // so they stay one segment.
    int motion_segments = 0;
    int image_height = 480;
    // --alpha-blend opaque: alphaMode BLEND materials are drawn opaque (as
    // before stochastic transparency); else each covered sample stays
    // covered with probability alpha (AlphaMode::blend).
    bool blend_opaque = false;
};

// Lens radius for an f-number: R = f / (2 N), with the focal length of a
// 35 mm camera (24 mm sensor height) of the same vertical field of view, in
// scene units taken as metres.
float lens_radius_for_fstop(float yfov, double fstop);

// Frame `frame`'s shutter [open, close] on the animation clock of the scene
// `name_or_path` (the clock Scene::animation_end ends on):
// - a glTF file: its animation's seconds; open = frame / fps, close =
//   (frame + angle / 360) / fps (the loader then applies the blur scale);
// - a built-in scene: frames; its motion over the nominal shutter [0, 1] is
//   one frame interval, extended linearly before and after (every frame
//   moves as far as frame 0), so open = frame, close = frame + angle / 360
//   and fps does not matter. --frames 0:0 --shutter-angle 360 is the
//   scene's default render.
// Throws SceneError for a negative frame, fps <= 0 or an angle outside (0, 360].
std::pair<double, double> frame_shutter_interval(const std::string& name_or_path, const FrameShutter& frame);

// The built-in scene or glTF file `name_or_path` with `settings` applied,
// validated. Throws SceneError: for a file of another type ("<name>:
// unsupported scene file type (expected .gltf or .glb)"), an unknown
// built-in name, or anything the loaders reject. glTF warnings go to `warn`.
Scene load_scene(const std::string& name_or_path, const SceneSettings& settings = SceneSettings{},
                 const WarningSink& warn = {});

}  // namespace blurcull::frontend
