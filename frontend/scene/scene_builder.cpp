#include "scene/scene_builder.hpp"

#include <cmath>

namespace blurcull::frontend {

std::string blur_and_aspect_problem(float blur_scale, float aspect) {
    if (!std::isfinite(blur_scale) || blur_scale < 0.0f) {
        return "blur scale " + std::to_string(blur_scale) + " must be finite and non-negative";
    }
    if (!std::isfinite(aspect) || !(aspect > 0.0f)) {
        return "aspect " + std::to_string(aspect) + " must be finite and positive";
    }
    return "";
}

std::uint32_t add_material(Scene& scene, const Material& material) {
    scene.materials.push_back(material);
    return static_cast<std::uint32_t>(scene.materials.size() - 1);
}

void append_mesh(Scene& scene, const std::vector<glm::vec3>& open, const std::vector<glm::vec3>& close,
                 const std::vector<glm::uvec3>& triangles, std::uint32_t material) {
    const glm::uvec3 offset(static_cast<std::uint32_t>(scene.position_open.size()));
    scene.position_open.insert(scene.position_open.end(), open.begin(), open.end());
    scene.position_close.insert(scene.position_close.end(), close.begin(), close.end());
    for (const glm::uvec3& triangle : triangles) {
        scene.triangles.push_back(triangle + offset);
        scene.triangle_material.push_back(material);
    }
}

}  // namespace blurcull::frontend
