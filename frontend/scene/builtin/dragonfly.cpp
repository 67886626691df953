// dragonfly: ~85k triangles (centimetres), camera motion only: the camera
// slides and turns a little while the insect sits still on a plant.
#include "scene/builtin/framing.hpp"
#include "scene/builtin/mesh_builder.hpp"
#include "scene/builtin/scenes.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

namespace blurcull::frontend::builtin {

namespace {

struct InsectMaterials {
    std::uint32_t body, eyes, wing, legs;
};

// Span along +-z, chord along x, a hair of thickness along y: two pairs.
void add_wings(MeshBuilder& mesh, const glm::vec3& origin, std::uint32_t wing) {
    for (float along : {0.55f, 1.25f}) {
        for (float side : {-1.0f, 1.0f}) {
            const glm::vec3 root = origin + glm::vec3(along, 0.48f, 0.22f * side);
            const float span = along > 1.0f ? 2.9f : 2.7f;
            const float sweep = along > 1.0f ? 0.10f : -0.12f;
            const glm::vec3 span_direction = glm::normalize(glm::vec3(sweep * side, 0.04f, side));
            const glm::vec3 chord = glm::normalize(glm::cross(kUp, span_direction));
            const Frame frame{root + span_direction * span,
                              glm::mat3(chord, glm::cross(span_direction, chord), span_direction)};
            mesh.ellipsoid(frame, {0.42f, 0.025f, span}, 96, 48, wing);
        }
    }
}

// Head, compound eyes, thorax, ten abdomen segments, wings and six legs;
// `origin` is where thorax meets abdomen.
void add_insect(MeshBuilder& mesh, const glm::vec3& origin, const InsectMaterials& materials) {
    const glm::vec3 head = origin + glm::vec3(2.25f, 0.15f, 0.0f);
    mesh.ellipsoid(frame_along(head, {1.0f, 0.0f, 0.0f}), {0.45f, 0.45f, 0.40f}, 48, 24, materials.body);
    for (float side : {-1.0f, 1.0f}) {
        mesh.ellipsoid(frame_along(head + glm::vec3(0.22f, 0.18f, 0.36f * side), {0.0f, 0.0f, side}),
                       {0.40f, 0.42f, 0.36f}, 64, 32, materials.eyes);
    }
    mesh.ellipsoid(frame_along(origin + glm::vec3(0.95f, 0.0f, 0.0f), {1.0f, 0.0f, 0.0f}), {0.50f, 0.55f, 0.95f}, 64,
                   32, materials.body);
    for (int segment = 0; segment < 10; ++segment) {
        const float s = static_cast<float>(segment);
        const glm::vec3 center = origin + glm::vec3(-0.30f - 0.62f * s, -0.012f * s * s, 0.0f);
        const float thickness = 0.24f - 0.008f * s;
        mesh.ellipsoid(frame_along(center, {-1.0f, -0.02f * s, 0.0f}), {thickness, thickness, 0.36f}, 48, 24,
                       materials.body);
    }
    add_wings(mesh, origin, materials.wing);
    for (int pair = 0; pair < 3; ++pair) {
        for (float side : {-1.0f, 1.0f}) {
            const float x = 0.55f + 0.35f * static_cast<float>(pair);
            const glm::vec3 hip = origin + glm::vec3(x, -0.35f, 0.18f * side);
            const glm::vec3 knee = origin + glm::vec3(x + 0.25f, -0.75f, 0.65f * side);
            const glm::vec3 foot =
                origin + glm::vec3(0.95f + 0.15f * static_cast<float>(pair - 1), -1.05f, 0.22f * side);
            mesh.capsule(hip, knee, 0.05f, 12, 3, materials.legs);
            mesh.capsule(knee, foot, 0.04f, 12, 3, materials.legs);
        }
    }
}

// A curved stem that ends just under the thorax, where the feet grip it,
// with three leaves.
void add_plant(MeshBuilder& mesh, std::uint32_t plant) {
    std::vector<glm::vec3> stem;
    std::vector<float> stem_radii;
    for (int i = 0; i <= 24; ++i) {
        const float f = static_cast<float>(i) / 24.0f;
        stem.push_back({0.95f * f * f + 0.4f * std::sin(3.0f * f), 10.9f * f, 0.3f * std::sin(2.0f * f)});
        stem_radii.push_back(0.22f - 0.08f * f);
    }
    mesh.tube(stem, stem_radii, 20, plant);
    for (int leaf = 0; leaf < 3; ++leaf) {
        const float f = 0.25f + 0.2f * static_cast<float>(leaf);
        const glm::vec3 attach = stem[static_cast<std::size_t>(f * 24.0f)];
        const float turn = 2.1f * static_cast<float>(leaf);
        const glm::vec3 out(std::cos(turn), 0.55f, std::sin(turn));
        const glm::vec3 span = glm::normalize(out);
        const Frame frame = frame_along(attach + span * 2.2f, span);
        mesh.ellipsoid(frame, {0.7f, 0.05f, 2.2f}, 48, 24, plant);
    }
}

}  // namespace

Scene make_dragonfly(float blur, float aspect) {
    Scene scene;
    scene.name = "dragonfly";
    MeshBuilder mesh(scene);
    InsectMaterials insect;
    insect.body = mesh.material({0.10f, 0.45f, 0.55f}, "body");
    insect.eyes = mesh.material({0.35f, 0.12f, 0.08f}, "eyes");
    insect.wing = mesh.material({0.80f, 0.86f, 0.90f}, "wing");
    insect.legs = mesh.material({0.08f, 0.08f, 0.08f}, "legs");
    const std::uint32_t plant = mesh.material({0.25f, 0.55f, 0.20f}, "plant");
    const std::uint32_t soil = mesh.material({0.40f, 0.33f, 0.22f}, "soil");

    const glm::vec3 origin(0.0f, 12.0f, 0.0f);  // where thorax meets abdomen
    const std::uint32_t insect_first = mesh.vertex_count();
    add_insect(mesh, origin, insect);
    const std::uint32_t insect_end = mesh.vertex_count();
    add_plant(mesh, plant);
    mesh.heightfield(-40.0f, 40.0f, -40.0f, 40.0f, 40, 40,
                     [](float x, float z) { return 0.4f * std::sin(0.2f * x) * std::cos(0.17f * z); }, soil);

    const glm::vec3 target = origin + glm::vec3(0.0f, -0.3f, 0.0f);
    const glm::vec3 eye = target + glm::vec3(5.0f, 6.5f, 13.0f);
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(eye, target, kUp);
    // A sideways slide of ~0.45 cm plus a 0.6 degree turn in the same sense:
    // a few percent of the image width.
    camera.view_close =
        moved_view(camera.view_open, glm::vec3(0.40f, -0.10f, -0.15f) * blur, kUp, 0.0105f * blur);
    camera.yfov = framing_yfov(scene, camera.view_open, insect_first, insect_end, aspect, 1.25f);
    camera.znear = 0.1f;
    camera.focus_distance = glm::length(target - eye);
    camera.lens_radius = 0.0f;
    scene.light_direction = glm::normalize(glm::vec3(0.5f, 0.9f, 0.2f));
    scene.background = {0.62f, 0.75f, 0.85f};
    return scene;
}

}  // namespace blurcull::frontend::builtin
