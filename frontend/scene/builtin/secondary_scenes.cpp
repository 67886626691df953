#include "scene/builtin/secondary_scenes.hpp"

#include "scene/builtin/framing.hpp"
#include "scene/scene_builder.hpp"

#include <glm/gtc/matrix_transform.hpp>

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

void set_secondary_scene_view(Scene& scene, const SecondarySceneView& view, float blur, float aspect) {
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(view.eye, view.target, kUp);
    camera.view_close = camera.view_open;
    camera.yfov = secondary_scene_yfov(view.yfov_at_4_3, aspect);
    camera.znear = 0.1f;
    camera.focus_distance = view.focus_distance;
    camera.lens_radius = view.lens_radius * blur;
    scene.light_direction = glm::normalize(view.light_direction);
    scene.background = kSecondarySceneBackground;
    scene.environment = BC_ENVIRONMENT_SKY;
}

}  // namespace blurcull::frontend::builtin
