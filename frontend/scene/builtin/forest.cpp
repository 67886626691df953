// forest: ~170k triangles, camera motion and defocus. Trees from a metre to
// 110 m away on rolling ground that also runs behind the camera.
// forest-10m: the same walk through 10 million triangles of the same trees,
// out to ~390 m (the compute pipeline's scale test, issue 23).
#include "scene/builtin/framing.hpp"
#include "scene/builtin/mesh_builder.hpp"
#include "scene/builtin/random.hpp"
#include "scene/builtin/scenes.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstddef>
#include <vector>

namespace blurcull::frontend::builtin {

namespace {

float forest_height(float x, float z) {
    return 0.6f * std::sin(0.08f * x) * std::cos(0.06f * z) + 0.3f * std::sin(0.21f * x + 0.13f * z);
}

struct ForestMaterials {
    std::uint32_t bark, pine, leaves, grass;
};

ForestMaterials forest_materials(MeshBuilder& mesh) {
    ForestMaterials m{};
    m.bark = mesh.material({0.36f, 0.25f, 0.16f}, "bark");
    m.pine = mesh.material({0.10f, 0.36f, 0.18f}, "pine");
    m.leaves = mesh.material({0.38f, 0.58f, 0.18f}, "leaves");
    m.grass = mesh.material({0.30f, 0.45f, 0.20f}, "grass");
    return m;
}

// One tree rooted on the ground at `spot` (x, z): a conifer (540 triangles)
// or a broadleaf (788), its height and kind drawn from `random`.
void add_tree(MeshBuilder& mesh, Random& random, glm::vec2 spot, const ForestMaterials& m) {
    const float height = random.uniform(4.0f, 11.0f);
    const glm::vec3 root(spot.x, forest_height(spot.x, spot.y) - 0.2f, spot.y);
    const bool conifer = random.unit() < 0.6f;
    const float trunk_height = (conifer ? 0.35f : 0.5f) * height;
    const float trunk_radius = 0.025f * height;
    mesh.frustum(upright(root), trunk_height + 0.3f, trunk_radius, 0.5f * trunk_radius, 10, 2, m.bark);
    if (conifer) {
        for (int tier = 0; tier < 3; ++tier) {
            const float t = static_cast<float>(tier);
            const float base = trunk_height * 0.8f + t * 0.2f * height;
            const float tier_height = (0.45f - 0.08f * t) * height;
            mesh.frustum(upright(root + glm::vec3(0.0f, base, 0.0f)), tier_height, (0.22f - 0.05f * t) * height,
                         0.0f, 20, 4, m.pine);
        }
    } else {
        const glm::vec3 crown = root + glm::vec3(0.0f, trunk_height + 0.3f * height, 0.0f);
        mesh.ellipsoid(upright(crown), {0.30f * height, 0.27f * height, 0.36f * height}, 28, 14, m.leaves);
    }
}

// The walk: forward-right while turning ~0.7 degrees, focused at 12 m.
void forest_camera(Scene& scene, float blur, float aspect) {
    const glm::vec3 eye(0.0f, forest_height(0.0f, 0.0f) + 2.2f, 0.0f);
    const glm::vec3 target(0.0f, 2.4f, -20.0f);
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(eye, target, kUp);
    camera.view_close = moved_view(camera.view_open, glm::vec3(0.30f, 0.0f, -0.40f) * blur, kUp, -0.012f * blur);
    // A fixed ~69 degree horizontal field of view, whatever the aspect.
    camera.yfov = 2.0f * std::atan(std::tan(0.6f) / aspect);
    camera.znear = 0.1f;
    camera.focus_distance = 12.0f;
    camera.lens_radius = 0.035f * blur;
    scene.light_direction = glm::normalize(glm::vec3(-0.4f, 0.8f, 0.3f));
    scene.background = {0.70f, 0.80f, 0.92f};
}

}  // namespace

Scene make_forest(float blur, float aspect) {
    Scene scene;
    scene.name = "forest";
    MeshBuilder mesh(scene);
    const ForestMaterials materials = forest_materials(mesh);
    mesh.heightfield(-70.0f, 70.0f, -120.0f, 15.0f, 96, 90, forest_height, materials.grass);

    Random random(0xF0257ull);
    std::vector<glm::vec2> placed;
    const int tree_target = 236;
    for (int attempt = 0; attempt < 20000 && static_cast<int>(placed.size()) < tree_target; ++attempt) {
        const float depth = random.uniform(2.0f, 110.0f);
        const float half_width = 0.8f * depth + 3.0f;
        const glm::vec2 spot(random.uniform(-half_width, half_width), -depth);
        if (glm::length(spot) < 5.0f) continue;
        bool crowded = false;
        for (const glm::vec2& other : placed) {
            if (glm::length(other - spot) < 2.0f) {
                crowded = true;
                break;
            }
        }
        if (crowded) continue;
        placed.push_back(spot);
        add_tree(mesh, random, spot, materials);
    }
    forest_camera(scene, blur, aspect);
    return scene;
}

Scene make_forest_10m(float blur, float aspect) {
    Scene scene;
    scene.name = "forest-10m";
    MeshBuilder mesh(scene);
    const ForestMaterials materials = forest_materials(mesh);
    mesh.heightfield(-360.0f, 360.0f, -440.0f, 15.0f, 160, 160, forest_height, materials.grass);

    // Trees on a jittered 2.8 m grid (no pairwise crowding test: 15,000
    // trees), row after row away from the camera inside the view's wedge,
    // until the scene holds 10 million triangles.
    constexpr std::size_t target_triangles = 10'000'000;
    constexpr float cell = 2.8f;
    Random random(0xF0257ull + 10);
    for (int row = 0; scene.triangles.size() < target_triangles && row < 160; ++row) {
        const float depth = 2.0f + cell * static_cast<float>(row);
        const int half_cells = static_cast<int>((0.8f * depth + 3.0f) / cell);
        for (int column = -half_cells; column <= half_cells && scene.triangles.size() < target_triangles; ++column) {
            const glm::vec2 spot(cell * (static_cast<float>(column) + random.uniform(-0.35f, 0.35f)),
                                 -(depth + cell * random.uniform(-0.35f, 0.35f)));
            if (glm::length(spot) < 5.0f) continue;
            add_tree(mesh, random, spot, materials);
        }
    }
    forest_camera(scene, blur, aspect);
    return scene;
}

}  // namespace blurcull::frontend::builtin
