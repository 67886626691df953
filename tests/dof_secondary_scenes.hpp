// The small scenes and the image comparison of the dof-secondary tests
// (test_frontend_dof_secondary.cpp, test_frontend_gl_dof_secondary.cpp): a
// plane mirror with quads seen only in it, the same quads mirrored
// analytically, and a mirror sphere over a floor.
#pragma once

#include "frontend_test_helpers.hpp"
#include "render/common/optics_shared.h"
#include "render/secondary/secondary_options.hpp"

#include <algorithm>
#include <cmath>

namespace blurcull::frontend::test {

inline constexpr float mirror_z = -5.0f;

// A quad in the plane z facing -z (its winding normal), from (x0, y0) to
// (x1, y1), moving by `motion` over the shutter.
inline void add_facing_quad(Scene& scene, float x0, float y0, float x1, float y1, float z, std::uint32_t material,
                            glm::vec3 motion = glm::vec3(0.0f)) {
    add_quad(scene, {x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}, motion, material);
}

// Two coloured quads behind the camera (z = 2 and 4, the nearer hiding part
// of the farther) seen only in a plane mirror at z = -5 that fills the
// screen; a camera at the origin looking down -z, focused on the mirror, so
// the reflections at depth 12 and 14 are blurred. With `quad_motion` the
// quads move by it over the shutter (the mirror stands still).
inline Scene plane_mirror_scene(float lens_radius, glm::vec3 quad_motion = glm::vec3(0.0f)) {
    Scene scene;
    scene.name = "plane-mirror";
    scene.materials = {Material{{1.0f, 1.0f, 1.0f}, "mirror", MaterialKind::mirror},
                       Material{{0.9f, 0.2f, 0.1f}, "red"}, Material{{0.1f, 0.8f, 0.2f}, "green"}};
    add_quad(scene, {-40, -40, mirror_z}, {40, -40, mirror_z}, {40, 40, mirror_z}, {-40, 40, mirror_z}, {0, 0, 0}, 0);
    add_facing_quad(scene, -1.5f, -1.0f, 0.3f, 0.8f, 2.0f, 1, quad_motion);
    add_facing_quad(scene, -0.4f, -0.6f, 2.0f, 1.6f, 4.0f, 2, quad_motion);
    scene.camera.yfov = 0.8f;
    scene.camera.znear = 0.1f;
    scene.camera.lens_radius = lens_radius;
    scene.camera.focus_distance = -mirror_z;
    scene.light_direction = {0.3f, 0.8f, 0.5f};
    return scene;
}

// The same view without the mirror: the quads reflected in the plane z = -5
// ((x, y, z) -> (x, y, 2 m - z), the light with them), which is what the
// mirror shows (moving as their mirror images do). Winding reverses under a
// reflection; shading is two-sided.
inline Scene mirrored_scene(float lens_radius, glm::vec3 quad_motion = glm::vec3(0.0f)) {
    Scene scene = plane_mirror_scene(lens_radius, quad_motion);
    Scene mirrored = scene;
    mirrored.position_open.clear();
    mirrored.position_close.clear();
    mirrored.triangles.clear();
    mirrored.triangle_material.clear();
    for (std::size_t t = 2; t < scene.triangles.size(); ++t) {
        const auto base = static_cast<std::uint32_t>(mirrored.position_open.size());
        auto mirror = [](glm::vec3 p) { return glm::vec3(p.x, p.y, 2.0f * mirror_z - p.z); };
        for (int k = 0; k < 3; ++k) {
            mirrored.position_open.push_back(mirror(scene.position_open[scene.triangles[t][k]]));
            mirrored.position_close.push_back(mirror(scene.position_close[scene.triangles[t][k]]));
        }
        mirrored.triangles.push_back({base, base + 2, base + 1});
        mirrored.triangle_material.push_back(scene.triangle_material[t]);
    }
    mirrored.light_direction.z = -scene.light_direction.z;
    return mirrored;
}

struct ImageError {
    double rmse = 0, max_abs = 0;
    int pixels_off = 0;  // pixels with some channel off by more than 0.05
};

inline ImageError compare(const Image& a, const Image& b) {
    ImageError e;
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        double worst = 0;
        for (int c = 0; c < 3; ++c) {
            const double d = double(a.pixels[i][c]) - double(b.pixels[i][c]);
            sum += d * d;
            worst = std::max(worst, std::abs(d));
        }
        e.max_abs = std::max(e.max_abs, worst);
        if (worst > 0.05) ++e.pixels_off;
    }
    e.rmse = std::sqrt(sum / double(3 * a.pixels.size()));
    return e;
}

inline SecondaryOptions small_options() {
    SecondaryOptions options;
    options.layer_size = 256;
    return options;
}

// A mirror sphere (radius 1 at (0, 0, -4)) over a floor, with two walls
// behind the camera: a curved reflector whose rays spread over many facets.
inline Scene mirror_sphere_scene() {
    Scene scene;
    scene.name = "mirror-sphere";
    scene.materials = {Material{{0.9f, 0.9f, 0.9f}, "mirror", MaterialKind::mirror},
                       Material{{0.7f, 0.6f, 0.4f}, "floor"}, Material{{0.2f, 0.3f, 0.9f}, "wall"}};
    const int rings = 16, segments = 24;
    const glm::vec3 centre(0.0f, 0.0f, -4.0f);
    auto vertex = [&](int i, int j) {
        const float theta = 3.14159265f * float(i) / float(rings), phi = 6.2831853f * float(j) / float(segments);
        return centre + glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j)
            add_quad(scene, vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1), vertex(i + 1, j), {0, 0, 0}, 0);
    // Floor at y = -1 facing up, a wall behind the camera facing -z.
    add_quad(scene, {-10, -1, 6}, {10, -1, 6}, {10, -1, -14}, {-10, -1, -14}, {0, 0, 0}, 1);
    add_facing_quad(scene, -3.0f, -1.0f, 3.0f, 3.0f, 3.0f, 2);
    scene.camera.yfov = 0.7f;
    scene.camera.znear = 0.1f;
    scene.camera.lens_radius = 0.08f;
    scene.camera.focus_distance = 3.0f;
    scene.environment = BC_ENVIRONMENT_SKY;
    return scene;
}

}  // namespace blurcull::frontend::test
