#include "scene/builtin/framing.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace blurcull::frontend::builtin {

float framing_yfov(const Scene& scene, const glm::mat4& view, std::uint32_t first, std::uint32_t end, float aspect,
                   float margin) {
    float extent = 0.05f;
    for (std::uint32_t i = first; i < end; ++i) {
        const glm::vec3 middle = 0.5f * (scene.position_open[i] + scene.position_close[i]);
        const glm::vec4 q = view * glm::vec4(middle, 1.0f);
        const float depth = -q.z;
        if (depth <= 1e-3f) continue;
        extent = std::max({extent, std::abs(q.y) / depth, std::abs(q.x) / (depth * aspect)});
    }
    return std::clamp(2.0f * std::atan(extent * margin), 0.15f, 2.2f);
}

glm::mat4 moved_view(const glm::mat4& view_open, const glm::vec3& eye_offset, const glm::vec3& axis, float angle) {
    if (eye_offset == glm::vec3(0.0f) && angle == 0.0f) return view_open;  // exactly static
    const glm::mat4 camera_to_world = glm::inverse(view_open);
    const glm::vec3 eye(camera_to_world[3]);
    const glm::mat4 turned = glm::translate(glm::mat4(1.0f), eye + eye_offset) *
                             glm::rotate(glm::mat4(1.0f), angle, glm::normalize(axis)) *
                             glm::translate(glm::mat4(1.0f), -eye) * camera_to_world;
    return glm::inverse(turned);
}

}  // namespace blurcull::frontend::builtin
