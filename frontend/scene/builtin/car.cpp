// car: ~54k triangles, object motion only. The car drives sideways across
// the view; the street, kerbs and buildings stay put.
#include "scene/builtin/framing.hpp"
#include "scene/builtin/mesh_builder.hpp"
#include "scene/builtin/random.hpp"
#include "scene/builtin/scenes.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace blurcull::frontend::builtin {

Scene make_car(float blur, float aspect) {
    Scene scene;
    scene.name = "car";
    MeshBuilder mesh(scene);
    const std::uint32_t paint = mesh.material({0.78f, 0.10f, 0.08f}, "paint");
    const std::uint32_t glass = mesh.material({0.12f, 0.18f, 0.26f}, "glass");
    const std::uint32_t rubber = mesh.material({0.06f, 0.06f, 0.06f}, "tyre");
    const std::uint32_t chrome = mesh.material({0.75f, 0.76f, 0.78f}, "chrome");
    const std::uint32_t lamp = mesh.material({0.98f, 0.92f, 0.60f}, "lamp");
    const std::uint32_t asphalt = mesh.material({0.22f, 0.22f, 0.24f}, "asphalt");
    const std::uint32_t pavement = mesh.material({0.55f, 0.53f, 0.50f}, "pavement");
    const std::uint32_t brick = mesh.material({0.62f, 0.42f, 0.30f}, "building");

    const std::uint32_t car_first = mesh.vertex_count();
    mesh.superellipsoid(upright({0.0f, 0.66f, 0.0f}), {2.2f, 0.90f, 0.38f}, 0.30f, 0.30f, 160, 56,
                        paint);
    mesh.superellipsoid(upright({-0.25f, 1.10f, 0.0f}), {1.25f, 0.78f, 0.34f}, 0.45f, 0.40f, 128, 40,
                        glass);
    for (float x : {-1.35f, 1.35f}) {
        for (float z : {-0.80f, 0.80f}) {
            // Wheels turn about the z axis (the axle).
            const Frame wheel{{x, 0.37f, z}, glm::mat3(1.0f)};
            mesh.torus(wheel, 0.26f, 0.11f, 72, 24, rubber);
            const Frame hub{{x, 0.37f, z + (z > 0.0f ? 0.06f : -0.06f)}, glm::mat3(1.0f)};
            mesh.ellipsoid(hub, {0.19f, 0.19f, 0.06f}, 32, 16, chrome);
        }
    }
    for (float z : {-0.62f, 0.62f}) {
        mesh.ellipsoid(frame_along({2.17f, 0.78f, z}, {1.0f, 0.0f, 0.0f}), {0.16f, 0.10f, 0.06f}, 24, 12, lamp);
        mesh.ellipsoid(frame_along({-2.17f, 0.78f, z}, {-1.0f, 0.0f, 0.0f}), {0.14f, 0.08f, 0.05f}, 24, 12, lamp);
    }
    mesh.capsule({2.22f, 0.42f, -0.78f}, {2.22f, 0.42f, 0.78f}, 0.08f, 24, 6, chrome);
    mesh.capsule({-2.22f, 0.42f, -0.78f}, {-2.22f, 0.42f, 0.78f}, 0.08f, 24, 6, chrome);
    const std::uint32_t car_end = mesh.vertex_count();

    auto flat = [](float, float) { return 0.0f; };
    mesh.heightfield(-40.0f, 40.0f, -4.0f, 4.0f, 64, 8, flat, asphalt);
    auto kerb = [](float, float) { return 0.12f; };
    mesh.heightfield(-40.0f, 40.0f, 4.0f, 16.0f, 64, 10, kerb, pavement);
    mesh.heightfield(-40.0f, 40.0f, -16.0f, -4.0f, 64, 10, kerb, pavement);
    Random random(0xCA5ull);
    for (float x = -34.0f; x < 34.0f;) {
        const float width = random.uniform(3.0f, 7.0f);
        const float height = random.uniform(3.0f, 12.0f);
        const float depth = random.uniform(3.0f, 6.0f);
        mesh.box({x + 0.5f * width, 0.12f + 0.5f * height, -8.0f - 0.5f * depth},
                 {0.5f * width - 0.1f, 0.5f * height, 0.5f * depth}, random.uniform(-0.05f, 0.05f),
                 3, brick);
        x += width;
    }

    // 0.45 m during the shutter (about 6% of the image width here), centred
    // on the modelled position so the framing does not depend on blur_scale.
    const glm::vec3 travel(0.45f * blur, 0.0f, 0.0f);
    mesh.translate(car_first, car_end, -0.5f * travel, 0.5f * travel);

    const glm::vec3 eye(1.8f, 1.6f, 8.5f);
    const glm::vec3 target(0.1f, 0.8f, 0.0f);
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(eye, target, kUp);
    camera.view_close = camera.view_open;
    camera.yfov = framing_yfov(scene, camera.view_open, car_first, car_end, aspect, 1.4f);
    camera.znear = 0.1f;
    camera.focus_distance = glm::length(target - eye);
    camera.lens_radius = 0.0f;
    scene.light_direction = glm::normalize(glm::vec3(-0.3f, 0.9f, 0.4f));
    scene.background = {0.55f, 0.70f, 0.90f};
    return scene;
}

}  // namespace blurcull::frontend::builtin
