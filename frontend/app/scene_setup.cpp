#include "app/scene_setup.hpp"

#include "render/common/cull_method.hpp"
#include "scene/motion_segments.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace blurcull::frontend {

void parse_size(const std::string& text, int& width, int& height) {
    std::size_t x = text.find('x');
    auto bad = [&]() {
        return std::invalid_argument("--size: expected WxH with W and H in [1, 65536], got '" + text + "'");
    };
    if (x == std::string::npos || x == 0 || x + 1 >= text.size()) throw bad();
    try {
        std::size_t used_w = 0, used_h = 0;
        long w = std::stol(text.substr(0, x), &used_w);
        long h = std::stol(text.substr(x + 1), &used_h);
        if (used_w != x || used_h != text.size() - x - 1 || w < 1 || h < 1 || w > 65536 || h > 65536) throw bad();
        width = static_cast<int>(w);
        height = static_cast<int>(h);
    } catch (const std::logic_error&) {
        throw bad();
    }
}

void parse_shutter(const std::string& text, float& open, float& close) {
    std::size_t comma = text.find(',');
    auto bad = [&]() {
        return std::invalid_argument("--shutter: expected OPEN,CLOSE with finite OPEN <= CLOSE, got '" + text + "'");
    };
    if (comma == std::string::npos) throw bad();
    try {
        std::size_t used_open = 0, used_close = 0;
        double o = std::stod(text.substr(0, comma), &used_open);
        double c = std::stod(text.substr(comma + 1), &used_close);
        if (used_open != comma || used_close != text.size() - comma - 1 || !std::isfinite(o) || !std::isfinite(c) ||
            o > c)
            throw bad();
        open = static_cast<float>(o);
        close = static_cast<float>(c);
    } catch (const std::logic_error&) {
        throw bad();
    }
}

Scene load_scene(const SceneRequest& request) {
    const WarningSink print = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
    return load_scene(request.scene, request, print);
}

void SceneFlags::add_options(CLI::App& app, bool initial) {
    const std::string start = initial ? "initial " : "";
    app.add_option("--scene", scene, "built-in scene name (blurcull scenes) or a .gltf/.glb file")
        ->capture_default_str();
    app.add_option("--cull", cull, start + "culling method: " + cull_method_help())
        ->check(CLI::IsMember(cull_method_names_and_aliases()))
        ->capture_default_str();
    app.add_option("--spp", spp, start + "samples per pixel")->check(CLI::Range(1, 1024))->capture_default_str();
    app.add_option("--size", size, "image size WxH")->capture_default_str();
    auto* radius = app.add_option("--lens-radius", lens_radius, start + "thin-lens aperture radius (scene units)")
                       ->check(CLI::Range(0.0, 1e6));
    auto* fstop_option = app.add_option("--fstop", fstop, start + "f-number (35 mm equivalent focal length)")
                             ->check(CLI::Range(0.1, 1e6));
    radius->excludes(fstop_option);
    app.add_option("--focus", focus, start + "focus distance (view depth, scene units)")->check(CLI::Range(1e-6, 1e9));
    app.add_option("--shutter", shutter,
                   start + "OPEN,CLOSE: animation seconds for glTF, fractions of the nominal shutter for built-in scenes");
    app.add_option("--blur-scale", blur_scale, start + "multiplier of motion and lens radius (thesis x2 rows: 2)")
        ->check(CLI::Range(0.0, 1000.0))
        ->capture_default_str();
    app.add_option("--seed", seed, "sample pattern seed")->capture_default_str();
    app.add_option("--motion-segments", motion_segments,
                   "glTF: K linear motion segments over the shutter (1 to " + std::to_string(max_motion_segments) +
                       "), or auto: K from the largest rotation, chord within 1/16 pixel (cpu and embree, method "
                       "stochastic; elsewhere one segment, with a warning)")
        ->capture_default_str();
    app.add_option("--alpha-blend", alpha_blend,
                   "glTF alphaMode BLEND: stochastic (a sample is covered with probability alpha, then the depth "
                   "test) or opaque (drawn as alphaMode OPAQUE)")
        ->check(CLI::IsMember({"stochastic", "opaque"}))
        ->capture_default_str();
}

}  // namespace blurcull::frontend
