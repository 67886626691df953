#include "scene/gltf/motion_times.hpp"

#include "scene/gltf/camera.hpp"
#include "scene/gltf/meshes.hpp"
#include "scene/motion_segments.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace blurcull::frontend::gltf {

namespace tg = tinygltf;

void add_interior_times(const tg::Model& model, const std::vector<int>& rendered, const PosesAt& poses_at,
                        const GltfOptions& options, float open, float close, int segments, Scene& scene,
                        Diagnostics& diagnostics) {
    const bool camera_moves = scene.camera.view_open != scene.camera.view_close;
    for (int k = 1; k < segments; ++k) {
        const float time = open + (close - open) * static_cast<float>(k) / static_cast<float>(segments);
        const NodePoses poses = poses_at(time);
        Scene at_time;
        add_mesh_instances(model, rendered, poses, at_time, diagnostics);
        if (at_time.position_open.size() != scene.position_open.size()) {
            diagnostics.fail("motion segment time " + std::to_string(time) + " gives " +
                             std::to_string(at_time.position_open.size()) + " vertices instead of " +
                             std::to_string(scene.position_open.size()));
        }
        scene.position_at.push_back(std::move(at_time.position_open));
        if (camera_moves) {
            setup_camera(model, rendered, poses, options, at_time, diagnostics);
            scene.camera.view_at.push_back(at_time.camera.view_open);
        }
    }
}

namespace {

// The rotation part of a world matrix (columns normalised: scale removed).
glm::quat rotation_of(const glm::mat4& world) {
    glm::mat3 m(world);
    for (int c = 0; c < 3; ++c) {
        const float length = glm::length(m[c]);
        m[c] = length > 0.0f ? m[c] / length : glm::vec3(0.0f);
    }
    return glm::normalize(glm::quat_cast(m));
}

// Radians turned by each node's world rotation over [open, close], summed
// over `steps` equal steps (a slerp turns less than pi per keyframe step).
std::vector<double> node_turns(const PosesAt& poses_at, float open, float close, std::size_t nodes, int steps) {
    std::vector<double> turned(nodes, 0.0);
    std::vector<glm::mat4> previous = poses_at(open).open;
    for (int j = 1; j <= steps; ++j) {
        const std::vector<glm::mat4> current =
            poses_at(open + (close - open) * static_cast<float>(j) / static_cast<float>(steps)).open;
        for (std::size_t n = 0; n < nodes; ++n) {
            const float d = std::min(1.0f, std::abs(glm::dot(rotation_of(previous[n]), rotation_of(current[n]))));
            turned[n] += 2.0 * std::acos(static_cast<double>(d));
        }
        previous = current;
    }
    return turned;
}

// Half the diagonal, in pixels, of the box of the points' projections
// (vertices behind the eye or beyond the image's diagonal count as the diagonal).
double projected_radius(const std::vector<glm::vec3>& points, const glm::mat4& view, const Camera& camera,
                        double aspect, int image_height) {
    const double k_y = 1.0 / std::tan(0.5 * static_cast<double>(camera.yfov));
    const double half_h = 0.5 * image_height, half_w = half_h * aspect;
    const double diagonal = 2.0 * std::hypot(half_w, half_h);
    if (points.empty()) return 0.0;
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::vec3& p : points) {
        const glm::dvec4 v = glm::dmat4(view) * glm::dvec4(glm::dvec3(p), 1.0);
        const double w = -v.z;
        if (!(w > static_cast<double>(camera.znear))) return diagonal;
        const glm::dvec2 pixel(k_y / aspect * v.x / w * half_w, k_y * v.y / w * half_h);
        lo = glm::min(lo, pixel);
        hi = glm::max(hi, pixel);
    }
    return std::min(diagonal, 0.5 * glm::length(hi - lo));
}

}  // namespace

int auto_motion_segments(const tg::Model& model, const std::vector<int>& rendered, const PosesAt& poses_at,
                         const GltfOptions& options, float open, float close, const Scene& scene,
                         Diagnostics& diagnostics) {
    if (!(close > open) || options.image_height < 1) return 1;
    const std::vector<double> turned = node_turns(poses_at, open, close, model.nodes.size(), 32);
    // The poses at both ends in one NodePoses (every field the mesh step reads).
    NodePoses ends = poses_at(open);
    const NodePoses at_close = poses_at(close);
    ends.close = at_close.open;
    ends.weights_close = at_close.weights_open;
    const double aspect = static_cast<double>(options.aspect);
    const int image_height = options.image_height;
    int segments = 1;
    for (int node : rendered) {
        const tg::Node& n = model.nodes[static_cast<std::size_t>(node)];
        if (n.mesh < 0) continue;
        double angle = turned[static_cast<std::size_t>(node)];
        if (n.skin >= 0 && static_cast<std::size_t>(n.skin) < model.skins.size()) {
            for (int joint : model.skins[static_cast<std::size_t>(n.skin)].joints)
                angle = std::max(angle, turned[static_cast<std::size_t>(joint)]);
        }
        if (angle <= 0.0) continue;
        Scene mesh;
        add_mesh_instances(model, {node}, ends, mesh, diagnostics);
        const double radius = std::max(
            projected_radius(mesh.position_open, scene.camera.view_open, scene.camera, aspect, image_height),
            projected_radius(mesh.position_close, scene.camera.view_close, scene.camera, aspect, image_height));
        segments = std::max(segments, motion_segments_for_turn(angle, radius, motion_chord_tolerance_px));
    }
    if (segments > max_motion_segments) {
        diagnostics.warn_once("motion segments", "--motion-segments auto wants " + std::to_string(segments) +
                                                     " segments; capped at " + std::to_string(max_motion_segments));
        segments = max_motion_segments;
    }
    return segments;
}

}  // namespace blurcull::frontend::gltf
