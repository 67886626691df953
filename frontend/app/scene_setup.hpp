// What `blurcull render` and `blurcull view` share: parsing --size and
// --shutter, and loading a built-in or glTF scene with the lens, focus,
// shutter and blur-scale overrides applied.
#pragma once

#include "render/common/render_types.hpp"
#include "scene/scene.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <utility>

namespace blurcull::frontend {

// "WxH" with W and H in [1, 65536]; throws std::invalid_argument naming --size.
void parse_size(const std::string& text, int& width, int& height);

// "OPEN,CLOSE" with finite OPEN <= CLOSE; throws std::invalid_argument naming --shutter.
void parse_shutter(const std::string& text, float& open, float& close);

// The file name without folder and extension ("scenes/a.gltf" -> "a").
std::string stem(const std::string& path);

struct SceneRequest {
    std::string scene = "forest";  // built-in name or a .gltf/.glb path
    float aspect = 4.0f / 3.0f;    // width / height of the image
    double blur_scale = 1.0;
    bool has_shutter = false;      // else the scene's own shutter
    float shutter_open = 0.0f;
    float shutter_close = 1.0f;
    double lens_radius = -1.0;     // < 0: the scene's own (multiplied by blur_scale when set)
    double fstop = -1.0;           // > 0: the lens radius for this f-number
    double focus = -1.0;           // > 0: the focus distance
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

    // Adds --scene, --cull, --spp, --size, --lens-radius | --fstop, --focus,
    // --shutter, --blur-scale and --seed, with their ranges. `initial`: the
    // help says they are starting values (the window changes them).
    void add_options(CLI::App& app, bool initial);
};

// Loads and validates the scene; throws SceneError or std::runtime_error
// with a one-line message.
Scene load_scene(const SceneRequest& request);

}  // namespace blurcull::frontend
