#include "scene/gltf/lights.hpp"

#include <algorithm>
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

// The light's colour x intensity (white by default), or non-finite.
glm::vec3 light_colour(const tg::Light& light) {
    glm::vec3 colour(1.0f);
    if (light.color.size() >= 3) {
        colour = glm::vec3(static_cast<float>(light.color[0]), static_cast<float>(light.color[1]),
                           static_cast<float>(light.color[2]));
    }
    return colour * static_cast<float>(light.intensity);
}

// A spot light's cone cosines; the spec's 0 <= inner < outer <= pi/2 is
// enforced by clamping (warned).
void spot_cones(const tg::Light& light, int index, PunctualLight& out, Diagnostics& diagnostics) {
    const double half_pi = 1.5707963267948966;
    double inner = light.spot.innerConeAngle;
    double outer = light.spot.outerConeAngle;
    if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0.0 || outer > half_pi || !(inner < outer)) {
        diagnostics.warn_once("spot cones", "light " + std::to_string(index) + " has cone angles inner " +
                                                std::to_string(inner) + ", outer " + std::to_string(outer) +
                                                " outside 0 <= inner < outer <= pi/2; they are clamped");
        outer = std::isfinite(outer) ? std::clamp(outer, 0.0, half_pi) : 0.7853981634;
        inner = std::isfinite(inner) ? std::clamp(inner, 0.0, outer) : 0.0;
    }
    out.cos_inner = static_cast<float>(std::cos(inner));
    out.cos_outer = static_cast<float>(std::cos(outer));
}

}  // namespace

void setup_light(const tg::Model& model, const std::vector<int>& rendered, const NodePoses& poses, Scene& scene,
                 Diagnostics& diagnostics) {
    bool directional_found = false;
    bool any_light = false;
    std::size_t dropped = 0;
    for (int node_index : rendered) {
        const int index = node_light(model.nodes[static_cast<std::size_t>(node_index)]);
        if (index < 0) continue;
        if (static_cast<std::size_t>(index) >= model.lights.size()) {
            diagnostics.warn_once("light index", "node " + std::to_string(node_index) + " names light " +
                                                     std::to_string(index) + ", which does not exist; ignored");
            continue;
        }
        const tg::Light& light = model.lights[static_cast<std::size_t>(index)];
        const glm::mat4& world = poses.open[static_cast<std::size_t>(node_index)];
        // A light shines along its node's -Z; towards it is +Z.
        const glm::vec3 towards = glm::vec3(world * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
        const glm::vec3 position = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        const glm::vec3 colour = light_colour(light);
        PunctualLight punctual;
        if (light.type == "directional") {
            punctual.type = LightType::directional;
        } else if (light.type == "point") {
            punctual.type = LightType::point;
        } else if (light.type == "spot") {
            punctual.type = LightType::spot;
            spot_cones(light, index, punctual, diagnostics);
        } else {
            diagnostics.warn_once("light type", "light " + std::to_string(index) + " has unknown type '" + Diagnostics::quoted(light.type) +
                                                    "'; ignored");
            continue;
        }
        if (!finite(towards) || !(glm::dot(towards, towards) > 0.0f) || !finite(position) || !finite(colour)) {
            diagnostics.warn_once("bad light", "light " + std::to_string(index) +
                                                   " has a degenerate transform or non-finite colour; ignored");
            continue;
        }
        any_light = true;
        if (punctual.type == LightType::directional && !directional_found) {
            scene.light_direction = towards;
            scene.light_color = glm::max(colour, glm::vec3(0.0f));
            directional_found = true;
            continue;
        }
        if (scene.lights.size() >= max_punctual_lights) {
            ++dropped;
            continue;
        }
        if (!(light.range > 0.0) && light.range != 0.0) {
            diagnostics.warn_once("light range", "light " + std::to_string(index) + " has range " +
                                                     std::to_string(light.range) + " (must be > 0); unlimited is used");
        }
        punctual.range = light.range > 0.0 && std::isfinite(light.range) ? static_cast<float>(light.range) : 0.0f;
        punctual.position = position;
        punctual.direction = punctual.type == LightType::directional ? towards : -towards;
        punctual.colour = glm::max(colour, glm::vec3(0.0f));
        scene.lights.push_back(punctual);
    }
    if (dropped > 0) {
        diagnostics.warn_once("many lights", "only " + std::to_string(max_punctual_lights) +
                                                 " lights besides the first directional one are used; " +
                                                 std::to_string(dropped) + " more are ignored");
    }
    // The file lights itself: no default light beside its own.
    if (any_light && !directional_found) scene.light_color = glm::vec3(0.0f);
}

}  // namespace blurcull::frontend::gltf
