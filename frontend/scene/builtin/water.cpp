// water: a gently waved water surface (a dielectric sheet of index 1.33, one
// surface, no bottom) over a chessboard pool floor with fish and stones
// under it and a post, a buoy and a ball above it. The floor runs on past
// the water towards the camera, so the same board is seen directly and
// refracted. Focus on the fish: the refracted floor is blurred by the
// distance its light travelled, the reflected post by its own
// (docs/secondary-rays.md, "Scenes").
#include "scene/builtin/framing.hpp"
#include "scene/builtin/mesh_builder.hpp"
#include "scene/builtin/scenes.hpp"
#include "scene/builtin/secondary_scenes.hpp"


#include <cmath>

namespace blurcull::frontend::builtin {

namespace {

// Two crossing swells a few centimetres high.
float wave_height(float x, float z) {
    return 0.05f * std::sin(1.3f * x + 0.4f * z) + 0.035f * std::sin(0.9f * z - 1.7f * x + 0.8f);
}

}  // namespace

Scene make_water(float blur, float aspect) {
    Scene scene;
    scene.name = "water";
    MeshBuilder mesh(scene);
    const std::uint32_t light_tile = mesh.material({0.85f, 0.82f, 0.70f}, "tile light");
    const std::uint32_t dark_tile = mesh.material({0.10f, 0.28f, 0.40f}, "tile dark");
    const std::uint32_t water = add_specular_material(scene, "water", MaterialKind::dielectric, 1.33f);
    const std::uint32_t fish = mesh.material({0.95f, 0.45f, 0.08f}, "fish");
    const std::uint32_t stone = mesh.material({0.45f, 0.45f, 0.42f}, "stone");
    const std::uint32_t post = mesh.material({0.80f, 0.15f, 0.12f}, "post");
    const std::uint32_t buoy = mesh.material({0.95f, 0.90f, 0.20f}, "buoy");
    const std::uint32_t ball = mesh.material({0.20f, 0.35f, 0.85f}, "ball");

    mesh.chessboard({-7.0f, -1.0f, 7.0f}, {14.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -14.0f}, 14, 2, light_tile,
                    dark_tile);
    mesh.heightfield(-6.0f, 6.0f, -6.0f, 3.5f, 120, 96, wave_height, water);

    // Under water.
    const float fish_x[] = {-1.6f, 0.4f, 1.9f, -0.4f};
    const float fish_z[] = {-0.8f, 0.6f, -2.2f, -3.4f};
    for (int i = 0; i < 4; ++i) {
        const float heading = 0.7f * static_cast<float>(i) - 1.0f;
        const glm::vec3 centre(fish_x[i], -0.55f - 0.08f * static_cast<float>(i), fish_z[i]);
        const glm::vec3 along(std::cos(heading), 0.0f, std::sin(heading));
        mesh.ellipsoid(frame_along(centre, along), {0.16f, 0.22f, 0.50f}, 32, 16, fish);
        mesh.frustum(frame_along(centre - 0.45f * along, -along), 0.35f, 0.05f, 0.22f, 16, 1, fish);
    }
    for (int i = 0; i < 5; ++i) {
        const float fi = static_cast<float>(i);
        mesh.ellipsoid(upright({-2.8f + 1.4f * fi, -1.0f, 1.6f - 1.1f * fi}), {0.35f, 0.28f, 0.18f}, 24, 12, stone);
    }

    // Above water: seen directly and in the water's reflection.
    mesh.capsule({-2.6f, -1.0f, -1.8f}, {-2.6f, 1.4f, -1.8f}, 0.12f, 24, 6, post);
    mesh.torus(upright({1.8f, 0.02f, 0.4f}), 0.35f, 0.12f, 48, 16, buoy);
    mesh.ellipsoid(upright({0.6f, 1.0f, -2.8f}), glm::vec3(0.45f), 48, 24, ball);

    SecondarySceneView view;
    view.eye = glm::vec3(0.0f, 2.2f, 7.0f);
    view.target = glm::vec3(0.0f, -0.6f, -0.8f);
    view.yfov_at_4_3 = 0.8f;
    view.focus_distance = glm::length(glm::vec3(0.4f, -0.63f, 0.6f) - view.eye);  // the nearest fish
    view.lens_radius = 0.10f;
    view.light_direction = glm::vec3(0.3f, 0.9f, 0.3f);
    set_secondary_scene_view(scene, view, blur, aspect);
    return scene;
}

}  // namespace blurcull::frontend::builtin
