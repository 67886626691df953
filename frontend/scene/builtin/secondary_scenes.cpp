#include "scene/builtin/secondary_scenes.hpp"

#include "scene/scene_builder.hpp"

#include <algorithm>
#include <cmath>

namespace blurcull::frontend::builtin {

std::uint32_t add_specular_material(Scene& scene, const std::string& name, MaterialKind kind, float ior) {
    Material material;
    material.name = name;
    material.kind = kind;
    material.ior = ior;
    material.base_color = glm::vec3(1.0f);
    return add_material(scene, material);
}

float secondary_scene_yfov(float yfov_at_4_3, float aspect) {
    const float reference_aspect = 4.0f / 3.0f;
    if (aspect >= reference_aspect) return yfov_at_4_3;
    // Same horizontal half-width: tan(y'/2) aspect = tan(y/2) 4/3.
    const float widened = 2.0f * std::atan(std::tan(0.5f * yfov_at_4_3) * reference_aspect / aspect);
    return std::min(widened, 2.2f);
}

}  // namespace blurcull::frontend::builtin
