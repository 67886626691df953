// mirror-motion: motion seen in a mirror. A wide flat mirror stands at the
// far edge of a chessboard; a ball and a box cross the board in front of it
// (seen directly and in the mirror), and a ring and a column move behind the
// camera, where only the mirror shows them. The camera stands still and
// focuses on the mirror, so everything reflected is defocused as well as
// blurred by its motion: the scene of `--bounce-time-slices`
// (docs/secondary-rays.md, "Motion seen in a mirror").
#include "scene/builtin/framing.hpp"
#include "scene/builtin/mesh_builder.hpp"
#include "scene/builtin/scenes.hpp"
#include "scene/builtin/secondary_scenes.hpp"

namespace blurcull::frontend::builtin {

namespace {

constexpr float kMirrorZ = -4.0f;

}  // namespace

Scene make_mirror_motion(float blur, float aspect) {
    Scene scene;
    scene.name = "mirror-motion";
    MeshBuilder mesh(scene);
    const std::uint32_t light_square = mesh.material({0.88f, 0.86f, 0.80f}, "board light");
    const std::uint32_t dark_square = mesh.material({0.10f, 0.10f, 0.12f}, "board dark");
    const std::uint32_t mirror = add_specular_material(scene, "mirror", MaterialKind::mirror, 1.5f);
    const std::uint32_t frame = mesh.material({0.30f, 0.22f, 0.15f}, "mirror back");
    const std::uint32_t red = mesh.material({0.85f, 0.15f, 0.10f}, "red (moving)");
    const std::uint32_t blue = mesh.material({0.15f, 0.30f, 0.85f}, "blue (moving)");
    const std::uint32_t green = mesh.material({0.15f, 0.70f, 0.25f}, "green");
    const std::uint32_t yellow = mesh.material({0.90f, 0.80f, 0.15f}, "yellow (behind the camera, moving)");
    const std::uint32_t cyan = mesh.material({0.10f, 0.75f, 0.80f}, "cyan (behind the camera, moving)");

    // 16 m x 16 m board of 1 m squares, from behind the camera to the mirror.
    mesh.chessboard({-8.0f, 0.0f, 11.0f}, {16.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -16.0f}, 16, 2, light_square,
                    dark_square);
    // The mirror, 9 m x 3 m, and a wall 1.8 m behind it (nearer, it would lie
    // within the layers' slab thickness of the mirror).
    mesh.surface(24, 8, [](float s, float t) { return glm::vec3(-4.5f + 9.0f * s, 0.05f + 3.0f * t, kMirrorZ); },
                 mirror);
    mesh.box({0.0f, 1.55f, kMirrorZ - 1.8f}, {4.7f, 1.55f, 0.05f}, 0.0f, 1, frame);

    // Between camera and mirror: a ball rolling to the right, a box sliding
    // to the left and towards the mirror, a cone standing still.
    std::uint32_t first = mesh.vertex_count();
    mesh.ellipsoid(upright({-1.6f, 0.5f, -1.0f}), glm::vec3(0.5f), 48, 24, red);
    mesh.translate(first, mesh.vertex_count(), glm::vec3(-0.6f, 0.0f, 0.0f) * blur,
                   glm::vec3(0.6f, 0.0f, 0.0f) * blur);
    first = mesh.vertex_count();
    mesh.box({1.8f, 0.4f, 0.2f}, {0.4f, 0.4f, 0.4f}, 0.5f, 2, blue);
    mesh.translate(first, mesh.vertex_count(), glm::vec3(0.4f, 0.0f, 0.2f) * blur,
                   glm::vec3(-0.4f, 0.0f, -0.2f) * blur);
    mesh.frustum(upright({0.3f, 0.0f, -2.3f}), 1.3f, 0.4f, 0.0f, 48, 4, green);

    // Behind the camera (eye at z = 6.5), seen only in the mirror: a ring
    // passing from left to right and a column rising.
    first = mesh.vertex_count();
    mesh.torus(frame_along({-0.5f, 1.7f, 8.0f}, {0.0f, 0.0f, 1.0f}), 0.8f, 0.25f, 64, 24, yellow);
    mesh.translate(first, mesh.vertex_count(), glm::vec3(-0.9f, 0.0f, 0.0f) * blur,
                   glm::vec3(0.9f, 0.0f, 0.0f) * blur);
    first = mesh.vertex_count();
    mesh.box({2.2f, 1.0f, 8.5f}, {0.35f, 1.0f, 0.35f}, 0.3f, 2, cyan);
    mesh.translate(first, mesh.vertex_count(), glm::vec3(0.0f, -0.3f, 0.0f) * blur,
                   glm::vec3(0.0f, 0.3f, 0.0f) * blur);

    SecondarySceneView view;
    view.eye = glm::vec3(0.0f, 1.7f, 6.5f);
    view.target = glm::vec3(0.0f, 1.2f, kMirrorZ);
    view.yfov_at_4_3 = 0.75f;
    view.focus_distance = glm::length(view.target - view.eye);  // the mirror's surface
    view.lens_radius = 0.08f;
    view.light_direction = glm::vec3(-0.3f, 0.9f, 0.6f);
    set_secondary_scene_view(scene, view, blur, aspect);
    return scene;
}

}  // namespace blurcull::frontend::builtin
