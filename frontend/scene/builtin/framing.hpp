// Camera helpers of the built-in scenes: a field of view that fits the
// subject, and the camera at shutter close for a camera-motion scene.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>

namespace blurcull::frontend::builtin {

// World up: every built-in scene stands on the xz plane.
inline const glm::vec3 kUp(0.0f, 1.0f, 0.0f);

// Smallest yfov that shows every vertex in [first, end) at mid-shutter from
// `view`, widened by `margin`; accounts for the aspect ratio. Mid-shutter
// positions keep the framing the same for every blur_scale.
float framing_yfov(const Scene& scene, const glm::mat4& view, std::uint32_t first, std::uint32_t end, float aspect,
                   float margin);

// The camera at close: eye moved by `eye_offset`, orientation turned by
// `angle` about the world-space `axis` through the eye.
glm::mat4 moved_view(const glm::mat4& view_open, const glm::vec3& eye_offset, const glm::vec3& axis, float angle);

}  // namespace blurcull::frontend::builtin
