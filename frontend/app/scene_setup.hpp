// What `blurcull render` and `blurcull view` share: parsing --size and
// --shutter, the scene flags, and loading a built-in or glTF scene with the
// lens, focus, shutter and blur-scale settings applied (the scene layer does
// the work; this prints its warnings).
#pragma once

#include "render/common/render_types.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene.hpp"
#include "scene/scene_name.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <utility>

namespace blurcull::frontend {

// "WxH" with W and H in [1, 65536]; throws std::invalid_argument naming --size.
void parse_size(const std::string& text, int& width, int& height);

// "OPEN,CLOSE" with finite OPEN <= CLOSE; throws std::invalid_argument naming --shutter.
void parse_shutter(const std::string& text, float& open, float& close);

// The scene to load and its settings (aspect, blur scale, shutter, lens,
// focus: scene/load_scene.hpp), as the flags give them.
struct SceneRequest : SceneSettings {
    std::string scene = "forest";  // built-in name or a .gltf/.glb path (scene/scene_name.hpp)
};

// The flags `blurcull render` and `blurcull view` share: the scene, its lens,
// focus, shutter and blur scale, the cull method, spp, size and seed.
struct SceneFlags {
    SceneFlags(std::string default_scene, int default_spp, std::string default_size)
        : scene(std::move(default_scene)), spp(default_spp), size(std::move(default_size)) {}

    std::string scene;
    std::string cull = to_string(RenderSettings{}.cull);
    int spp;
    std::string size;
    double lens_radius = -1.0;  // < 0: the scene's own
    double fstop = -1.0;
    double focus = -1.0;
    std::string shutter;        // "OPEN,CLOSE"; empty: the scene's own
    double blur_scale = 1.0;
    std::uint32_t seed = 1;
    std::string motion_segments = "auto";  // K, or "auto" (parse_motion_segments)
    std::string alpha_blend = "stochastic";  // or "opaque" (SceneSettings::blend_opaque)

    // Adds --scene, --cull, --spp, --size, --lens-radius | --fstop, --focus,
    // --shutter, --blur-scale, --seed, --motion-segments and --alpha-blend, with their ranges. `initial`: the
    // help says they are starting values (the window changes them).
    void add_options(CLI::App& app, bool initial);
};

// Loads the scene (validated once, by the scene layer's load_scene) and
// prints its warnings on stderr, one line each; throws SceneError or
// std::runtime_error with a one-line message.
Scene load_scene(const SceneRequest& request);

}  // namespace blurcull::frontend
