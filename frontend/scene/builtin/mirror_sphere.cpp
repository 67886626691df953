// mirror-sphere: a perfect mirror sphere on a chessboard floor, objects around
// it, and three objects BEHIND the camera that only the mirror shows. Focus
// on the sphere; the floor before and behind it is out of focus, and so is
// the reflection of what lies far away (docs/secondary-rays.md, "Scenes").
#include "scene/builtin/framing.hpp"
#include "scene/builtin/mesh_builder.hpp"
#include "scene/builtin/scenes.hpp"
#include "scene/builtin/secondary_scenes.hpp"


namespace blurcull::frontend::builtin {

Scene make_mirror_sphere(float blur, float aspect) {
    Scene scene;
    scene.name = "mirror-sphere";
    MeshBuilder mesh(scene);
    const std::uint32_t light_square = mesh.material({0.85f, 0.83f, 0.78f}, "board light");
    const std::uint32_t dark_square = mesh.material({0.12f, 0.12f, 0.14f}, "board dark");
    const std::uint32_t mirror = add_specular_material(scene, "mirror", MaterialKind::mirror, 1.5f);
    const std::uint32_t red = mesh.material({0.80f, 0.12f, 0.10f}, "red");
    const std::uint32_t green = mesh.material({0.15f, 0.65f, 0.20f}, "green");
    const std::uint32_t blue = mesh.material({0.15f, 0.25f, 0.80f}, "blue");
    const std::uint32_t yellow = mesh.material({0.90f, 0.80f, 0.15f}, "yellow");
    const std::uint32_t magenta = mesh.material({0.80f, 0.20f, 0.70f}, "magenta (behind the camera)");
    const std::uint32_t orange = mesh.material({0.95f, 0.50f, 0.10f}, "orange (behind the camera)");
    const std::uint32_t cyan = mesh.material({0.10f, 0.75f, 0.80f}, "cyan (behind the camera)");

    // 20 m x 20 m of 1 m squares, reaching behind the camera.
    mesh.chessboard({-10.0f, 0.0f, 12.0f}, {20.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -20.0f}, 20, 2, light_square,
                    dark_square);
    mesh.ellipsoid(upright({0.0f, 1.1f, 0.0f}), glm::vec3(1.1f), 128, 64, mirror);

    // Around the sphere, in view.
    mesh.box({-2.6f, 0.6f, -0.4f}, {0.6f, 0.6f, 0.6f}, 0.5f, 2, red);
    mesh.torus(upright({2.5f, 0.3f, 0.6f}), 0.6f, 0.28f, 64, 24, green);
    mesh.frustum(upright({-1.4f, 0.0f, -3.2f}), 2.2f, 0.6f, 0.0f, 48, 4, blue);
    mesh.capsule({1.5f, 0.3f, -2.6f}, {2.7f, 1.9f, -3.2f}, 0.3f, 32, 8, yellow);

    // Behind the camera (eye at z = 4.8): seen only in the mirror.
    mesh.ellipsoid(upright({-2.2f, 1.1f, 6.2f}), {1.0f, 1.0f, 1.1f}, 48, 24, magenta);
    mesh.box({2.3f, 1.0f, 6.4f}, {1.0f, 1.0f, 1.0f}, 0.3f, 2, orange);
    mesh.torus(frame_along({0.0f, 1.9f, 7.2f}, {0.0f, 0.0f, 1.0f}), 1.1f, 0.35f, 64, 24, cyan);

    SecondarySceneView view;
    view.eye = glm::vec3(0.0f, 1.7f, 4.8f);
    view.target = glm::vec3(0.0f, 0.9f, 0.0f);
    view.yfov_at_4_3 = 0.9f;
    view.focus_distance = glm::length(glm::vec3(0.0f, 1.1f, 1.1f) - view.eye);  // the sphere's front
    view.lens_radius = 0.12f;
    view.light_direction = glm::vec3(-0.4f, 0.9f, 0.5f);
    set_secondary_scene_view(scene, view, blur, aspect);
    return scene;
}

}  // namespace blurcull::frontend::builtin
