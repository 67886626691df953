#include "scene/gltf/loader.hpp"

#include "scene/gltf/animation.hpp"
#include "scene/gltf/camera.hpp"
#include "scene/gltf/lights.hpp"
#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/meshes.hpp"
#include "scene/gltf/morph.hpp"
#include "scene/gltf/motion_times.hpp"
#include "scene/gltf/nodes.hpp"
#include "scene/gltf/parse.hpp"
#include "scene/gltf/validate.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_checks.hpp"
#include "scene/scene_name.hpp"

#include <cmath>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

void check_options(const GltfOptions& o, const Diagnostics& diagnostics) {
    if (!std::isfinite(o.shutter_open) || !std::isfinite(o.shutter_close) || o.shutter_close < o.shutter_open) {
        diagnostics.fail("shutter interval [" + std::to_string(o.shutter_open) + ", " +
                         std::to_string(o.shutter_close) + "] is not a finite, ordered interval");
    }
    const std::string problem = blur_and_aspect_problem(o.blur_scale, o.aspect);
    if (!problem.empty()) diagnostics.fail(problem);
    if (!std::isfinite(o.lens_radius) || o.lens_radius < 0.0f) {
        diagnostics.fail("lens radius " + std::to_string(o.lens_radius) + " must be finite and non-negative");
    }
    if (!std::isfinite(o.focus_distance)) diagnostics.fail("focus distance is not finite");
    if (o.motion_segments < 0 || o.motion_segments > max_motion_segments) {
        diagnostics.fail("motion segments " + std::to_string(o.motion_segments) + " must be 0 (auto) or 1 to " +
                         std::to_string(max_motion_segments));
    }
}

// World matrices of every node at animation time t.
std::vector<glm::mat4> pose_at(const tg::Model& model, const NodeTree& tree, const AnimationSamplers& samplers,
                               const GltfOptions& options, float t, Diagnostics& diagnostics) {
    std::vector<NodeTransform> transforms = file_transforms(model);
    apply_animation(model, samplers, options.animation_index, t, transforms, diagnostics);
    return world_matrices(tree, std::move(transforms));
}

// The poses of every node at one instant t (open = close): the framing's
// probes and the motion segments' interior times.
NodePoses poses_at_instant(const tg::Model& model, const NodeTree& tree, const AnimationSamplers& samplers,
                           const GltfOptions& options, float t, Diagnostics& diagnostics) {
    NodePoses poses;
    poses.open = pose_at(model, tree, samplers, options, t, diagnostics);
    poses.close = poses.open;
    poses.weights_open = morph_weights(model, samplers, options.animation_index, t, diagnostics);
    poses.weights_close = poses.weights_open;
    return poses;
}

// The bounds of the scene posed at `framing_samples` + 1 evenly spaced times
// over [0, the animation's end]: the same for every frame of a sequence.
SceneStats animation_framing(const tg::Model& model, const NodeTree& tree, const AnimationSamplers& samplers,
                             const GltfOptions& options, const std::vector<int>& rendered, Diagnostics& diagnostics) {
    constexpr int framing_samples = 16;
    const float end = animation_end_time(samplers, options.animation_index);
    SceneStats framing;
    for (int k = 0; k <= framing_samples; ++k) {
        const float t = end * static_cast<float>(k) / static_cast<float>(framing_samples);
        Scene probe;
        add_mesh_instances(model, rendered, poses_at_instant(model, tree, samplers, options, t, diagnostics), probe,
                           diagnostics);
        const SceneStats stats = describe(probe);
        framing.bounds_min = k == 0 ? stats.bounds_min : glm::min(framing.bounds_min, stats.bounds_min);
        framing.bounds_max = k == 0 ? stats.bounds_max : glm::max(framing.bounds_max, stats.bounds_max);
    }
    return framing;
}

}  // namespace

Scene build_scene(const std::string& path, const GltfOptions& options, const WarningSink& warn) {
    Diagnostics diagnostics(path, warn);
    check_options(options, diagnostics);
    const tg::Model model = parse_file(diagnostics);
    const NodeTree tree = validate_model(model, diagnostics);
    const AnimationSamplers samplers = read_animations(model, diagnostics);

    const float t_open = options.shutter_open;
    const float t_close = options.shutter_open + (options.shutter_close - options.shutter_open) * options.blur_scale;
    const std::vector<int> rendered = rendered_nodes(model, tree);
    NodePoses poses;
    poses.open = pose_at(model, tree, samplers, options, t_open, diagnostics);
    poses.close = pose_at(model, tree, samplers, options, t_close, diagnostics);
    poses.weights_open = morph_weights(model, samplers, options.animation_index, t_open, diagnostics);
    poses.weights_close = morph_weights(model, samplers, options.animation_index, t_close, diagnostics);

    Scene scene;
    scene.name = stem(path);
    scene.animation_end = animation_end_time(samplers, options.animation_index);
    add_mesh_instances(model, rendered, poses, scene, diagnostics);
    if (scene.triangles.empty()) diagnostics.fail("no triangles to render");
    if (options.frame_whole_animation) {
        const SceneStats framing = animation_framing(model, tree, samplers, options, rendered, diagnostics);
        setup_camera(model, rendered, poses, options, scene, diagnostics, &framing);
    } else {
        setup_camera(model, rendered, poses, options, scene, diagnostics);
    }
    setup_light(model, rendered, poses, scene, diagnostics);

    // Motion segments: the same steps at the interior times.
    const PosesAt poses_at = [&](float t) { return poses_at_instant(model, tree, samplers, options, t, diagnostics); };
    const int segments = options.motion_segments == 0
                             ? auto_motion_segments(model, rendered, poses_at, options, t_open, t_close, scene, diagnostics)
                             : options.motion_segments;
    add_interior_times(model, rendered, poses_at, options, t_open, t_close, segments, scene, diagnostics);
    scene.motion_segments_auto = options.motion_segments == 0;
    return scene;
}

void validate_loaded_scene(Scene& scene, const std::string& path) {
    try {
        validate_scene(scene);
    } catch (const SceneError& error) {
        throw SceneError(path + ": " + error.what());
    }
    scene.validated = true;
}

}  // namespace blurcull::frontend::gltf

namespace blurcull::frontend {

Scene load_gltf_scene(const std::string& path, const GltfOptions& options, const WarningSink& warn) {
    Scene scene = gltf::build_scene(path, options, warn);
    gltf::validate_loaded_scene(scene, path);
    return scene;
}

}  // namespace blurcull::frontend
