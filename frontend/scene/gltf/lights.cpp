#include "scene/gltf/lights.hpp"

#include <cmath>
#include <string>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

// The light index a node's KHR_lights_punctual extension names, or -1.
int node_light(const tg::Node& node) {
    const auto found = node.extensions.find("KHR_lights_punctual");
    if (found == node.extensions.end() || !found->second.IsObject() || !found->second.Has("light")) return -1;
    const tg::Value& light = found->second.Get("light");
    return light.IsInt() ? light.GetNumberAsInt() : -1;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void setup_light(const tg::Model& model, const std::vector<int>& rendered, const NodePoses& poses, Scene& scene,
                 Diagnostics& diagnostics) {
    bool found = false;
    for (int node_index : rendered) {
        const int index = node_light(model.nodes[static_cast<std::size_t>(node_index)]);
        if (index < 0) continue;
        if (static_cast<std::size_t>(index) >= model.lights.size()) {
            diagnostics.warn_once("light index", "node " + std::to_string(node_index) + " names light " +
                                                     std::to_string(index) + ", which does not exist; ignored");
            continue;
        }
        const tg::Light& light = model.lights[static_cast<std::size_t>(index)];
        if (light.type != "directional" || found) {
            diagnostics.warn_once("other lights", "only the first directional light is used; point, spot and further lights are ignored");
            continue;
        }
        const glm::mat4& world = poses.open[static_cast<std::size_t>(node_index)];
        // A light shines along its node's -Z; light_direction points towards it.
        const glm::vec3 towards = glm::vec3(world * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
        glm::vec3 colour(1.0f);
        if (light.color.size() >= 3) {
            colour = glm::vec3(static_cast<float>(light.color[0]), static_cast<float>(light.color[1]),
                               static_cast<float>(light.color[2]));
        }
        colour *= static_cast<float>(light.intensity);
        if (!finite(towards) || !(glm::dot(towards, towards) > 0.0f) || !finite(colour)) {
            diagnostics.warn_once("bad light", "light " + std::to_string(index) + " has a degenerate direction or non-finite colour; the default light is used");
            continue;
        }
        scene.light_direction = towards;
        scene.light_color = glm::max(colour, glm::vec3(0.0f));
        found = true;
    }
}

}  // namespace blurcull::frontend::gltf
