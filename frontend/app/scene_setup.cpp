#include "app/scene_setup.hpp"

#include "scene/builtin_scenes.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/scene_checks.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <stdexcept>

namespace blurcull::frontend {
namespace {

bool ends_with(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool is_gltf_path(const std::string& name) { return ends_with(name, ".gltf") || ends_with(name, ".glb"); }

// A built-in scene's motion is defined over its nominal shutter [0, 1];
// another shutter re-samples that linear motion at OPEN and CLOSE.
void resample_shutter(Scene& scene, float open, float close) {
    for (std::size_t v = 0; v < scene.position_open.size(); ++v) {
        glm::vec3 p0 = scene.position_open[v], p1 = scene.position_close[v];
        scene.position_open[v] = glm::mix(p0, p1, open);
        scene.position_close[v] = glm::mix(p0, p1, close);
    }
    glm::mat4 v0 = scene.camera.view_open, v1 = scene.camera.view_close;
    scene.camera.view_open = v0 + (v1 - v0) * open;
    scene.camera.view_close = v0 + (v1 - v0) * close;
}

// Lens radius for an f-number: R = f / (2 N), with the focal length of a
// 35 mm camera (24 mm sensor height) of the same vertical field of view,
// in scene units taken as metres.
float lens_radius_for_fstop(float yfov, double fstop) {
    double focal_length = 0.012 / std::tan(0.5 * double(yfov));
    return static_cast<float>(focal_length / (2.0 * fstop));
}

}  // namespace

std::string stem(const std::string& path) {
    std::size_t slash = path.find_last_of('/');
    std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    std::size_t dot = base.find_last_of('.');
    return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

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
    Scene loaded;
    if (is_gltf_path(request.scene)) {
        GltfOptions gltf;
        gltf.aspect = request.aspect;
        gltf.blur_scale = static_cast<float>(request.blur_scale);
        if (request.has_shutter) {
            gltf.shutter_open = request.shutter_open;
            gltf.shutter_close = request.shutter_close;
        }
        loaded = load_gltf_scene(request.scene, gltf);
    } else {
        SceneOptions options;
        options.blur_scale = static_cast<float>(request.blur_scale);
        options.aspect = request.aspect;
        loaded = make_builtin_scene(request.scene, options);
        if (request.has_shutter) resample_shutter(loaded, request.shutter_open, request.shutter_close);
    }
    if (request.lens_radius >= 0.0) {
        loaded.camera.lens_radius = static_cast<float>(request.lens_radius * request.blur_scale);
    }
    if (request.fstop > 0.0) {
        loaded.camera.lens_radius =
            lens_radius_for_fstop(loaded.camera.yfov, request.fstop) * static_cast<float>(request.blur_scale);
    }
    if (request.focus > 0.0) loaded.camera.focus_distance = static_cast<float>(request.focus);
    validate_scene(loaded);
    return loaded;
}

void SceneFlags::add_options(CLI::App& app, bool initial) {
    const std::string start = initial ? "initial " : "";
    app.add_option("--scene", scene, "built-in scene name (blurcull scenes) or a .gltf/.glb file")
        ->capture_default_str();
    app.add_option("--cull", cull, start + "culling method")
        ->check(CLI::IsMember({"bbox", "hull", "dualspace", "clip2", "edges"}))
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
}

}  // namespace blurcull::frontend
