#include "scene/load_scene.hpp"

#include "scene/builtin/scenes.hpp"
#include "scene/gltf/loader.hpp"
#include "scene/scene_checks.hpp"
#include "scene/scene_name.hpp"

#include <glm/glm.hpp>

#include <cmath>

namespace blurcull::frontend {

namespace {

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

// The lens and focus settings, over what the scene chose.
void apply_lens_settings(Camera& camera, const SceneSettings& settings) {
    if (settings.lens_radius >= 0.0) {
        camera.lens_radius = static_cast<float>(settings.lens_radius * settings.blur_scale);
    }
    if (settings.fstop > 0.0) {
        camera.lens_radius =
            lens_radius_for_fstop(camera.yfov, settings.fstop) * static_cast<float>(settings.blur_scale);
    }
    if (settings.focus > 0.0) camera.focus_distance = static_cast<float>(settings.focus);
}

Scene build_gltf(const std::string& path, const SceneSettings& settings, const WarningSink& warn) {
    GltfOptions gltf;
    gltf.aspect = settings.aspect;
    gltf.blur_scale = static_cast<float>(settings.blur_scale);
    gltf.motion_segments = settings.motion_segments;
    gltf.image_height = settings.image_height;
    if (settings.has_shutter) {
        gltf.shutter_open = settings.shutter_open;
        gltf.shutter_close = settings.shutter_close;
    }
    gltf.frame_whole_animation = settings.has_frame;
    return gltf::build_scene(path, gltf, warn);
}

Scene build_builtin(const std::string& name, const SceneSettings& settings) {
    SceneOptions options;
    options.blur_scale = static_cast<float>(settings.blur_scale);
    options.aspect = settings.aspect;
    Scene scene = builtin::build_scene(name, options);
    if (settings.has_shutter) resample_shutter(scene, settings.shutter_open, settings.shutter_close);
    return scene;
}

}  // namespace

float lens_radius_for_fstop(float yfov, double fstop) {
    double focal_length = 0.012 / std::tan(0.5 * double(yfov));
    return static_cast<float>(focal_length / (2.0 * fstop));
}

std::pair<double, double> frame_shutter_interval(const std::string& name_or_path, const FrameShutter& frame) {
    if (frame.frame < 0) throw SceneError("frame " + std::to_string(frame.frame) + " is negative");
    if (!(frame.fps > 0.0) || !std::isfinite(frame.fps)) {
        throw SceneError("frame rate " + std::to_string(frame.fps) + " must be finite and positive");
    }
    if (!(frame.shutter_angle_degrees > 0.0 && frame.shutter_angle_degrees <= 360.0)) {
        throw SceneError("shutter angle " + std::to_string(frame.shutter_angle_degrees) +
                         " degrees is outside (0, 360]");
    }
    const double open_fraction = frame.shutter_angle_degrees / 360.0;  // of the frame interval
    const auto f = static_cast<double>(frame.frame);
    if (scene_file_type(name_or_path) == SceneFileType::none) return {f, f + open_fraction};
    return {f / frame.fps, (f + open_fraction) / frame.fps};
}

namespace {

void apply_alpha_blend(Scene& scene, const SceneSettings& settings) {
    if (!settings.blend_opaque) return;
    for (Material& material : scene.materials)
        if (material.alpha_mode == AlphaMode::blend) material.alpha_mode = AlphaMode::opaque;
}

}  // namespace

Scene load_scene(const std::string& name_or_path, const SceneSettings& given, const WarningSink& warn) {
    SceneSettings settings = given;
    if (settings.has_frame) {
        const std::pair<double, double> interval = frame_shutter_interval(name_or_path, settings.frame);
        settings.has_shutter = true;
        settings.shutter_open = static_cast<float>(interval.first);
        settings.shutter_close = static_cast<float>(interval.second);
    }
    switch (scene_file_type(name_or_path)) {
        case SceneFileType::gltf:
        case SceneFileType::glb: {
            Scene scene = build_gltf(name_or_path, settings, warn);
            apply_lens_settings(scene.camera, settings);
            apply_alpha_blend(scene, settings);
            gltf::validate_loaded_scene(scene, name_or_path);
            return scene;
        }
        case SceneFileType::unsupported:
            throw SceneError(name_or_path + ": unsupported scene file type (expected .gltf or .glb)");
        case SceneFileType::none:
            break;
    }
    Scene scene = build_builtin(name_or_path, settings);
    apply_lens_settings(scene.camera, settings);
    apply_alpha_blend(scene, settings);
    validate_scene(scene);
    scene.validated = true;
    return scene;
}

}  // namespace blurcull::frontend
