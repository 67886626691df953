// curved-mirror: the chessboard at a curved mirror of JCST 2013 Fig. 6, as
// three upright mirrors side by side on the far edge of a chessboard: flat,
// gently convex (radius 4 m) and strongly convex (radius 1.6 m), with
// objects on the board, and an upright chessboard chart behind the camera
// that only the mirrors show. The camera focuses on the mirrors; a flat
// mirror puts the reflected chart as far behind its surface as the chart is
// in front (blurred), a convex one pulls the reflection
// towards its focal point just behind the surface (sharper the stronger the
// curvature): the blur of the reflection depends on the curvature, not on
// the mirror's own depth (docs/secondary-rays.md, "Scenes").
#include "scene/builtin/framing.hpp"
#include "scene/builtin/mesh_builder.hpp"
#include "scene/builtin/scenes.hpp"
#include "scene/builtin/secondary_scenes.hpp"


#include <cmath>

namespace blurcull::frontend::builtin {

namespace {

constexpr float kMirrorWidth = 3.0f;   // arc length, metres
constexpr float kMirrorHeight = 2.4f;
constexpr float kMirrorBottom = 0.05f;
constexpr float kMirrorZ = -3.5f;      // the apex of every mirror

// An upright mirror whose horizontal section is a circular arc of length
// kMirrorWidth bulging towards +z (the camera); radius 0 makes it flat.
void upright_mirror(MeshBuilder& mesh, float centre_x, float radius, std::uint32_t material) {
    const int columns = radius > 0.0f ? 96 : 8;
    mesh.surface(columns, 4, [=](float s, float t) {
        const float arc = (s - 0.5f) * kMirrorWidth;
        const float y = kMirrorBottom + t * kMirrorHeight;
        if (radius <= 0.0f) return glm::vec3(centre_x + arc, y, kMirrorZ);
        const float angle = arc / radius;
        return glm::vec3(centre_x + radius * std::sin(angle), y, kMirrorZ + radius * (std::cos(angle) - 1.0f));
    }, material);
}

}  // namespace

Scene make_curved_mirror(float blur, float aspect) {
    Scene scene;
    scene.name = "curved-mirror";
    MeshBuilder mesh(scene);
    const std::uint32_t light_square = mesh.material({0.88f, 0.86f, 0.80f}, "board light");
    const std::uint32_t dark_square = mesh.material({0.10f, 0.10f, 0.12f}, "board dark");
    const std::uint32_t mirror = add_specular_material(scene, "mirror", MaterialKind::mirror, 1.5f);
    const std::uint32_t frame = mesh.material({0.30f, 0.22f, 0.15f}, "mirror back");
    const std::uint32_t red = mesh.material({0.85f, 0.15f, 0.10f}, "red");
    const std::uint32_t green = mesh.material({0.15f, 0.70f, 0.25f}, "green");
    const std::uint32_t blue = mesh.material({0.15f, 0.30f, 0.85f}, "blue");
    const std::uint32_t yellow = mesh.material({0.90f, 0.80f, 0.15f}, "yellow (behind the camera)");
    const std::uint32_t chart_light = mesh.material({0.92f, 0.92f, 0.92f}, "chart light (behind the camera)");
    const std::uint32_t chart_dark = mesh.material({0.70f, 0.10f, 0.12f}, "chart dark (behind the camera)");

    // 14 m x 14 m board of 1 m squares, from behind the camera to the mirrors.
    mesh.chessboard({-7.0f, 0.0f, 9.0f}, {14.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -14.0f}, 14, 2, light_square,
                    dark_square);
    const float radii[] = {0.0f, 4.0f, 1.6f};
    const float centres[] = {-3.6f, 0.0f, 3.6f};
    for (int i = 0; i < 3; ++i) {
        upright_mirror(mesh, centres[i], radii[i], mirror);
        // A wall behind each mirror, so no mirror is seen from its back.
        mesh.box({centres[i], kMirrorBottom + 0.5f * kMirrorHeight, kMirrorZ - 1.8f},
                 {0.55f * kMirrorWidth, 0.5f * kMirrorHeight, 0.05f}, 0.0f, 1, frame);
    }

    // On the board, between camera and mirrors.
    mesh.ellipsoid(upright({-2.2f, 0.5f, -0.5f}), glm::vec3(0.5f), 48, 24, red);
    mesh.frustum(upright({0.8f, 0.0f, -1.2f}), 1.4f, 0.45f, 0.0f, 48, 4, green);
    mesh.box({2.6f, 0.45f, 0.6f}, {0.45f, 0.45f, 0.45f}, 0.6f, 2, blue);
    // Behind the camera (eye at z = 7), seen only in the mirrors: an upright
    // chessboard chart of 0.5 m squares facing them, and a ring before it.
    mesh.chessboard({10.0f, -3.0f, 9.5f}, {-20.0f, 0.0f, 0.0f}, {0.0f, 20.0f, 0.0f}, 40, 1, chart_light, chart_dark);
    mesh.torus(frame_along({0.0f, 1.6f, 8.5f}, {0.0f, 0.0f, 1.0f}), 0.8f, 0.25f, 64, 24, yellow);

    SecondarySceneView view;
    view.eye = glm::vec3(0.0f, 1.7f, 7.0f);
    view.target = glm::vec3(0.0f, 1.1f, kMirrorZ);
    view.yfov_at_4_3 = 0.72f;
    view.focus_distance = glm::length(view.target - view.eye);  // the mirrors' surface
    view.lens_radius = 0.2f;
    view.light_direction = glm::vec3(-0.3f, 0.9f, 0.6f);
    set_secondary_scene_view(scene, view, blur, aspect);
    return scene;
}

}  // namespace blurcull::frontend::builtin
