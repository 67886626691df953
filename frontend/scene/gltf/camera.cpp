#include "scene/gltf/camera.hpp"

#include "scene/scene_checks.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

glm::mat4 view_from_node(const glm::mat4& world, int node, const Diagnostics& diagnostics) {
    glm::mat4 camera_to_world = world;
    // Cameras ignore scale: keep the orientation and position only.
    for (int axis = 0; axis < 3; ++axis) {
        const glm::vec3 column(camera_to_world[axis]);
        const float length = glm::length(column);
        if (!(length > 1e-12f) || !std::isfinite(length)) {
            diagnostics.fail("camera node " + std::to_string(node) + " has a degenerate (zero-scale) transform");
        }
        camera_to_world[axis] = glm::vec4(column / length, 0.0f);
    }
    return glm::inverse(camera_to_world);
}

int find_camera_node(const tg::Model& model, const std::vector<int>& rendered, int camera) {
    for (int node : rendered) {
        if (model.nodes[static_cast<std::size_t>(node)].camera == camera) return node;
    }
    return -1;
}

// The node carrying the camera to use; -1 for the automatic camera.
int choose_camera_node(const tg::Model& model, const std::vector<int>& rendered, int camera_index,
                       Diagnostics& diagnostics) {
    if (camera_index >= 0) {
        if (static_cast<std::size_t>(camera_index) >= model.cameras.size()) {
            diagnostics.fail("camera " + std::to_string(camera_index) + " does not exist (the file has " +
                             std::to_string(model.cameras.size()) + ")");
        }
        if (model.cameras[static_cast<std::size_t>(camera_index)].type != "perspective") {
            diagnostics.fail("camera " + std::to_string(camera_index) +
                             " is orthographic; only perspective cameras are supported");
        }
        const int camera_node = find_camera_node(model, rendered, camera_index);
        if (camera_node < 0) {
            diagnostics.fail("camera " + std::to_string(camera_index) + " is not attached to any node of the scene");
        }
        return camera_node;
    }
    bool saw_orthographic = false;
    for (int node : rendered) {
        const int camera = model.nodes[static_cast<std::size_t>(node)].camera;
        if (camera < 0) continue;
        if (model.cameras[static_cast<std::size_t>(camera)].type == "perspective") return node;
        saw_orthographic = true;
    }
    if (saw_orthographic) {
        diagnostics.warn_once("orthographic", "orthographic cameras are not supported; using an automatic perspective camera");
    }
    return -1;
}

void file_camera(const tg::Model& model, int camera_node, const NodePoses& poses, const glm::vec3& center,
                 Camera& camera, const Diagnostics& diagnostics) {
    const auto node = static_cast<std::size_t>(camera_node);
    const tg::Camera& source = model.cameras[static_cast<std::size_t>(model.nodes[node].camera)];
    camera.yfov = static_cast<float>(source.perspective.yfov);
    camera.znear = static_cast<float>(source.perspective.znear);
    camera.view_open = view_from_node(poses.open[node], camera_node, diagnostics);
    camera.view_close = view_from_node(poses.close[node], camera_node, diagnostics);
    const float center_depth = -(camera.view_open * glm::vec4(center, 1.0f)).z;
    camera.focus_distance = std::max(center_depth, 10.0f * camera.znear);
}

// Looks at the bounds' centre from the front (+z, glTF's "forward" for
// models), slightly from above and right, far enough that the bounding
// sphere fits both fields of view.
void automatic_camera(const glm::vec3& center, float radius, float aspect, Camera& camera) {
    camera.yfov = 0.8f;
    const float half_fit = std::min(0.4f, std::atan(std::tan(0.4f) * aspect));
    const float distance = radius / std::sin(half_fit) * 1.05f;
    const glm::vec3 eye = center + glm::normalize(glm::vec3(0.25f, 0.3f, 1.0f)) * distance;
    camera.view_open = glm::lookAt(eye, center, glm::vec3(0.0f, 1.0f, 0.0f));
    camera.view_close = camera.view_open;
    camera.znear = std::max(0.5f * (distance - radius), 1e-3f * distance);
    camera.focus_distance = distance;
}

}  // namespace

void setup_camera(const tg::Model& model, const std::vector<int>& rendered, const NodePoses& poses,
                  const GltfOptions& options, Scene& scene, Diagnostics& diagnostics, const SceneStats* framing) {
    const SceneStats stats = framing != nullptr ? *framing : describe(scene);
    const glm::vec3 center = 0.5f * (stats.bounds_min + stats.bounds_max);
    const float radius = std::max(0.5f * glm::length(stats.bounds_max - stats.bounds_min), 1e-3f);
    const int camera_node = choose_camera_node(model, rendered, options.camera_index, diagnostics);
    Camera& camera = scene.camera;
    if (camera_node >= 0) {
        file_camera(model, camera_node, poses, center, camera, diagnostics);
    } else {
        automatic_camera(center, radius, options.aspect, camera);
    }
    if (options.focus_distance > 0.0f) camera.focus_distance = options.focus_distance;
    camera.lens_radius = options.lens_radius;
}

}  // namespace blurcull::frontend::gltf
