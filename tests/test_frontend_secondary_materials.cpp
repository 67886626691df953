// Mirrors, glass and the environment (docs/secondary-rays.md): the built-in
// secondary-ray scenes, the bounce geometry against analytic cases, the
// Embree one-bounce reference against the same cases, the primary-only image
// against the CPU backend, and the bad input of the material side.
#include "render/common/optics_shared.h"
#include "render/common/shading.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/embree/embree_backend.hpp"
#include "render/embree/secondary_rays.hpp"
#include "render/gl/gl_backend.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/scene_checks.hpp"

#include "frontend_test_helpers.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <doctest/doctest.h>
#include <glm/glm.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using blurcull::frontend::test::add_quad;
using blurcull::frontend::test::fraction_close;
using blurcull::frontend::test::quiet_settings;
using blurcull::frontend::test::renderer_or_skip;
using blurcull::frontend::test::same_pixels;

namespace {

// Textbook unpolarised Fresnel reflectance from Snell's law, in double.
double textbook_fresnel(double cos_i, double n1, double n2) {
    const double sin_t = n1 / n2 * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
    if (sin_t >= 1.0) return 1.0;
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    const double rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    return 0.5 * (rs * rs + rp * rp);
}

Material kind_material(MaterialKind kind, float ior) {
    Material material;
    material.kind = kind;
    material.ior = ior;
    return material;
}

// A camera at the origin looking down -z (view = identity), pinhole.
Scene empty_scene(const char* name) {
    Scene scene;
    scene.name = name;
    scene.camera.yfov = 0.9f;
    scene.camera.znear = 0.01f;
    scene.background = glm::vec3(0.0f);
    scene.light_direction = glm::vec3(0.0f, 0.0f, 1.0f);
    return scene;
}

Material diffuse(glm::vec3 colour) {
    Material material;
    material.base_color = colour;
    return material;
}

// The view-space ray of sample j of pixel (px, py), as the backends make it.
// sampler: the settings' pattern (RenderSettings::sampler).
Ray sample_ray(const CameraModel& model, int px, int py, std::uint32_t j, std::uint32_t spp, std::uint32_t seed,
               int sampler) {
    const blurcull::kernelf::PixelSample sample = blurcull::patternsf::pattern_sample(
        sampler, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py), j, spp, seed);
    return model.lens_ray(model.sample_ndc(px, py, sample.offset), sample.lens);
}

constexpr glm::vec3 kRed(1.0f, 0.0f, 0.0f);
constexpr glm::vec3 kGreen(0.0f, 1.0f, 0.0f);

}  // namespace

// ---------------------------------------------------------------------------
// Scenes

TEST_CASE("secondary-ray scenes: names, validity, determinism, specular materials, sky, blur scale") {
    REQUIRE(secondary_scene_names() ==
            std::vector<std::string>{"mirror-sphere", "water", "curved-mirror", "mirror-motion"});
    // The thesis scenes' list (and so their images) is unchanged.
    CHECK(builtin_scene_names() == std::vector<std::string>{"hand", "car", "dragonfly", "forest"});
    for (const std::string& name : secondary_scene_names()) {
        CAPTURE(name);
        const Scene scene = make_builtin_scene(name, SceneOptions{});
        CHECK(scene.name == name);
        CHECK(scene.validated);
        CHECK_NOTHROW(validate_scene(scene));
        CHECK(scene.environment == BC_ENVIRONMENT_SKY);
        CHECK(scene.triangles.size() > 5000);
        CHECK(scene.triangles.size() < 60000);
        std::size_t specular_triangles = 0;
        for (std::uint32_t m : scene.triangle_material) {
            specular_triangles += scene.materials[m].kind != MaterialKind::diffuse ? 1 : 0;
        }
        CHECK(specular_triangles > 100);
        const Scene again = make_builtin_scene(name, SceneOptions{});
        CHECK(again.position_open == scene.position_open);
        CHECK(again.triangles == scene.triangles);
        const Scene twice = make_builtin_scene(name, SceneOptions{2.0f, 4.0f / 3.0f});
        CHECK(twice.camera.lens_radius == doctest::Approx(2.0f * scene.camera.lens_radius));
        CHECK(twice.triangles == scene.triangles);
        const Scene still = make_builtin_scene(name, SceneOptions{0.0f, 4.0f / 3.0f});
        CHECK(still.camera.lens_radius == 0.0f);
        CHECK(scene.camera.lens_radius > 0.0f);
        // Defocus only, but for mirror-motion's objects, whose motion scales with the blur too.
        const SceneStats stats = describe(scene);
        CHECK(stats.object_motion == (name == "mirror-motion"));
        CHECK_FALSE(stats.camera_motion);
        CHECK_FALSE(describe(still).object_motion);
    }
    CHECK(make_builtin_scene("water", SceneOptions{}).materials[2].ior == doctest::Approx(1.33f));
}

// ---------------------------------------------------------------------------
// Bounce geometry

TEST_CASE("bounce geometry: a plane mirror reflects by the law of reflection, from the viewer's side") {
    const glm::vec3 normal(0.0f, 1.0f, 0.0f);
    const glm::vec3 incident = glm::normalize(glm::vec3(0.3f, -0.5f, -0.8f));
    WeightedRay rays[2];
    const glm::vec3 hit(1.0f, 0.0f, -2.0f);
    REQUIRE(specular_rays(kind_material(MaterialKind::mirror, 1.5f), hit, incident, normal, 1e-3f, rays) == 1);
    CHECK(rays[0].weight == 1.0f);
    CHECK(rays[0].direction.x == doctest::Approx(incident.x));
    CHECK(rays[0].direction.y == doctest::Approx(-incident.y));
    CHECK(rays[0].direction.z == doctest::Approx(incident.z));
    CHECK(rays[0].origin.y > 0.0f);  // pushed to the side the ray came from
    // The same with the normal given on the other side.
    REQUIRE(specular_rays(kind_material(MaterialKind::mirror, 1.5f), hit, incident, -normal, 1e-3f, rays) == 1);
    CHECK(rays[0].direction.y == doctest::Approx(-incident.y));
    CHECK(rays[0].origin.y > 0.0f);
    // A diffuse material spawns nothing.
    CHECK(specular_rays(Material{}, hit, incident, normal, 1e-3f, rays) == 0);
}

TEST_CASE("bounce geometry: a ray reflected off a sphere leaves at the mirrored angle, in the plane of incidence") {
    // Analytic sphere of radius 1 at (0, 0, -5), rays from the origin.
    const glm::dvec3 centre(0.0, 0.0, -5.0);
    for (double angle : {0.0, 0.05, 0.1, 0.15, 0.19}) {
        CAPTURE(angle);
        const glm::dvec3 d = glm::normalize(glm::dvec3(std::sin(angle), 0.3 * std::sin(angle), -std::cos(angle)));
        // |t d - c|^2 = 1.
        const double b = glm::dot(d, centre);
        const double t = b - std::sqrt(b * b - glm::dot(centre, centre) + 1.0);
        const glm::dvec3 point = t * d;
        const glm::dvec3 n = glm::normalize(point - centre);
        WeightedRay rays[2];
        REQUIRE(specular_rays(kind_material(MaterialKind::mirror, 1.5f), glm::vec3(point), glm::vec3(d),
                              glm::vec3(n), 1e-4f, rays) == 1);
        const glm::dvec3 r(rays[0].direction);
        CHECK(glm::length(r) == doctest::Approx(1.0).epsilon(1e-6));
        CHECK(glm::dot(r, n) == doctest::Approx(-glm::dot(d, n)).epsilon(1e-5));      // angle out = angle in
        CHECK(glm::dot(glm::cross(d, n), r) == doctest::Approx(0.0).epsilon(1e-5));  // coplanar
        // Where the reflected ray meets the plane z = 10 (behind the camera):
        // the analytic point, within float rounding of the direction.
        const double s = (10.0 - point.z) / r.z;
        const glm::dvec3 r_exact = d - 2.0 * glm::dot(d, n) * n;
        const double s_exact = (10.0 - point.z) / r_exact.z;
        CHECK((point + s * r).x == doctest::Approx((point + s_exact * r_exact).x).epsilon(1e-4));
        CHECK((point + s * r).y == doctest::Approx((point + s_exact * r_exact).y).epsilon(1e-4));
    }
}

TEST_CASE("bounce geometry: a plane dielectric refracts by Snell's law with Fresnel weights R and 1 - R") {
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    for (float ior : {1.33f, 1.5f, 2.4f}) {
        for (double theta : {0.0, 0.3, 0.7, 1.2, 1.5}) {
            CAPTURE(ior);
            CAPTURE(theta);
            const glm::vec3 incident(static_cast<float>(std::sin(theta)), static_cast<float>(-std::cos(theta)), 0.0f);
            WeightedRay rays[2];
            const int count = specular_rays(kind_material(MaterialKind::dielectric, ior), glm::vec3(0.0f), incident,
                                            up, 1e-4f, rays);
            REQUIRE(count == 2);
            const double expected_r = textbook_fresnel(std::cos(theta), 1.0, ior);
            CHECK(rays[0].weight == doctest::Approx(expected_r).epsilon(1e-5));
            CHECK(rays[1].weight == doctest::Approx(1.0 - expected_r).epsilon(1e-5));
            CHECK(rays[0].direction.y == doctest::Approx(-incident.y));
            const glm::vec3 t = rays[1].direction;
            CHECK(t.y < 0.0f);  // into the medium
            CHECK(rays[1].origin.y < 0.0f);
            // n1 sin(theta_i) = n2 sin(theta_t).
            CHECK(ior * t.x == doctest::Approx(std::sin(theta)).epsilon(1e-5));
            // Leaving the medium along the reversed refracted ray retraces the path.
            WeightedRay back[2];
            REQUIRE(specular_rays(kind_material(MaterialKind::dielectric, ior), glm::vec3(0.0f), -t, up, 1e-4f,
                                  back) == 2);
            CHECK(back[1].direction.x == doctest::Approx(-incident.x).epsilon(1e-4));
            CHECK(back[1].direction.y == doctest::Approx(-incident.y).epsilon(1e-4));
            CHECK(back[0].weight == doctest::Approx(expected_r).epsilon(1e-4));  // Fresnel is reciprocal
        }
    }
}

TEST_CASE("bounce geometry: total internal reflection gives R = 1, index 1 goes straight through with R = 0") {
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    // Inside glass of index 1.5 (ray travelling up, against... along the
    // normal side it leaves on), beyond the critical angle asin(1 / 1.5).
    const double critical = std::asin(1.0 / 1.5);
    for (double theta : {critical + 0.01, 1.0, 1.4}) {
        const glm::vec3 incident(static_cast<float>(std::sin(theta)), static_cast<float>(std::cos(theta)), 0.0f);
        WeightedRay rays[2];
        REQUIRE(specular_rays(kind_material(MaterialKind::dielectric, 1.5f), glm::vec3(0.0f), incident, up, 1e-4f,
                              rays) == 1);
        CHECK(rays[0].weight == 1.0f);
        CHECK(rays[0].direction.y == doctest::Approx(-incident.y));
        CHECK(blurcull::frontend::optics::bc_dielectric_reflectance(incident, up, 1.5f) == 1.0f);
    }
    // Just inside the critical angle both rays exist.
    const double inside = critical - 0.02;
    const glm::vec3 below(static_cast<float>(std::sin(inside)), static_cast<float>(std::cos(inside)), 0.0f);
    WeightedRay rays[2];
    CHECK(specular_rays(kind_material(MaterialKind::dielectric, 1.5f), glm::vec3(0.0f), below, up, 1e-4f, rays) == 2);
    // Index 1: nothing to reflect off, the ray continues unchanged.
    for (double theta : {0.0, 0.8, 1.5}) {
        const glm::vec3 incident(static_cast<float>(std::sin(theta)), static_cast<float>(-std::cos(theta)), 0.0f);
        REQUIRE(specular_rays(kind_material(MaterialKind::dielectric, 1.0f), glm::vec3(0.0f), incident, up, 1e-4f,
                              rays) == 1);
        CHECK(rays[0].weight == 1.0f);
        CHECK(rays[0].direction.x == doctest::Approx(incident.x));
        CHECK(rays[0].direction.y == doctest::Approx(incident.y));
    }
}

// ---------------------------------------------------------------------------
// The Embree reference against analytic scenes, sample by sample (1 spp,
// pinhole: a pixel is its one sample).

TEST_CASE("embree bounce: a plane mirror floor shows the wall where the mirror image of the camera sees it") {
    // Mirror floor y = -1 up to a wall at z = -20, red above y = 1, green below.
    Scene scene = empty_scene("analytic mirror");
    scene.materials = {kind_material(MaterialKind::mirror, 1.5f), diffuse(kRed), diffuse(kGreen)};
    add_quad(scene, {-100, -1, 0}, {100, -1, 0}, {100, -1, -20}, {-100, -1, -20}, glm::vec3(0.0f), 0);
    add_quad(scene, {-100, 1, -20}, {100, 1, -20}, {100, 30, -20}, {-100, 30, -20}, glm::vec3(0.0f), 1);
    add_quad(scene, {-100, -1, -20}, {100, -1, -20}, {100, 1, -20}, {-100, 1, -20}, glm::vec3(0.0f), 2);
    const int size = 48;
    const RenderSettings settings = quiet_settings(size, size, 1);
    const RenderResult result = render_embree(scene, settings);
    CHECK(result.stats.secondary_rays > 0);
    const CameraModel model(scene.camera, size, size);
    int checked_in_mirror = 0;
    for (int py = 0; py < size; ++py) {
        for (int px = 0; px < size; ++px) {
            const Ray ray = sample_ray(model, px, py, 0, 1, settings.seed, settings.sampler);
            const double dy = ray.direction.y;  // direction.z = -1
            // Direct: the wall at height 20 dy. Mirrored (floor hit before
            // the wall when |dy| > 0.05): height 20 |dy| - 2, as seen from the
            // camera's mirror image at y = -2.
            double height = dy > -0.05 ? 20.0 * dy : 20.0 * -dy - 2.0;
            if (std::abs(height - 1.0) < 0.1 || std::abs(dy + 0.05) < 0.005) continue;  // on an edge
            const glm::vec3 expected = height > 1.0 ? kRed : kGreen;
            const glm::vec3 got = result.image.at(px, py);
            CAPTURE(px);
            CAPTURE(py);
            CHECK((got.x > got.y) == (expected.x > expected.y));
            CHECK(std::max(got.x, got.y) > 0.15f);  // lit, never the black background
            checked_in_mirror += dy < -0.05 ? 1 : 0;
        }
    }
    CHECK(checked_in_mirror > 200);
}

TEST_CASE("embree bounce: a plane of glass shows the floor where Snell's law puts it, weighted 1 - R") {
    // Glass surface y = -1 (index 1.5), floor y = -3: red beyond z = -10, green nearer.
    Scene scene = empty_scene("analytic glass");
    const float ior = 1.5f;
    scene.materials = {kind_material(MaterialKind::dielectric, ior), diffuse(kRed), diffuse(kGreen)};
    add_quad(scene, {-100, -1, 0}, {100, -1, 0}, {100, -1, -200}, {-100, -1, -200}, glm::vec3(0.0f), 0);
    add_quad(scene, {-100, -3, -10}, {100, -3, -10}, {100, -3, -200}, {-100, -3, -200}, glm::vec3(0.0f), 1);
    add_quad(scene, {-100, -3, 5}, {100, -3, 5}, {100, -3, -10}, {-100, -3, -10}, glm::vec3(0.0f), 2);
    scene.light_direction = glm::vec3(0.0f, 1.0f, 0.0f);  // the floor is fully lit: colour = base colour
    const int size = 48;
    const RenderSettings settings = quiet_settings(size, size, 1);
    const RenderResult result = render_embree(scene, settings);
    const CameraModel model(scene.camera, size, size);
    int checked = 0;
    for (int py = size / 2 + 2; py < size; ++py) {
        for (int px = 0; px < size; ++px) {
            const Ray ray = sample_ray(model, px, py, 0, 1, settings.seed, settings.sampler);
            const glm::dvec3 d = glm::normalize(glm::dvec3(ray.direction));
            const double s = -1.0 / d.y;
            const glm::dvec3 hit = s * d;
            const double sin_i = std::sqrt(d.x * d.x + d.z * d.z);
            const double sin_t = sin_i / ior;
            const double tan_t = sin_t / std::sqrt(1.0 - sin_t * sin_t);
            const double floor_z = hit.z + d.z / sin_i * 2.0 * tan_t;  // 2 = the depth of the floor under the glass
            if (std::abs(floor_z + 10.0) < 0.2) continue;
            const double transmitted = 1.0 - textbook_fresnel(-d.y, 1.0, ior);
            const glm::vec3 expected = static_cast<float>(transmitted) * (floor_z < -10.0 ? kRed : kGreen);
            const glm::vec3 got = result.image.at(px, py);
            CAPTURE(px);
            CAPTURE(py);
            CHECK(got.x == doctest::Approx(expected.x).epsilon(1e-4));
            CHECK(got.y == doctest::Approx(expected.y).epsilon(1e-4));
            ++checked;
        }
    }
    CHECK(checked > 500);
    // The primary-only image has no floor in it: glass shows the environment only.
    EmbreeOptions none;
    none.secondary = EmbreeSecondary::none;
    const RenderResult primary = render_embree(scene, settings, none);
    CHECK(primary.stats.secondary_rays == 0);
    CHECK(primary.image.at(size / 2, size - 1) == glm::vec3(0.0f));  // R black + (1 - R) black background
}

TEST_CASE("embree bounce: deterministic, thread-count independent; a diffuse scene is the same with or without") {
    SceneOptions options;
    options.aspect = 64.0f / 48.0f;
    const Scene scene = make_builtin_scene("mirror-sphere", options);
    RenderSettings settings = quiet_settings(64, 48, 4);
    settings.threads = 1;
    const RenderResult one = render_embree(scene, settings);
    settings.threads = 3;
    const RenderResult three = render_embree(scene, settings);
    CHECK(same_pixels(one.image, three.image));
    CHECK(one.stats.secondary_rays == three.stats.secondary_rays);
    CHECK(one.stats.secondary_rays > 0);
    EmbreeOptions none;
    none.secondary = EmbreeSecondary::none;
    const RenderResult primary = render_embree(scene, settings, none);
    CHECK_FALSE(same_pixels(one.image, primary.image));
    CHECK(primary.stats.samples_hit == one.stats.samples_hit);

    const Scene hand = make_builtin_scene("hand", options);
    CHECK(same_pixels(render_embree(hand, settings).image, render_embree(hand, settings, none).image));
}

TEST_CASE("primary-only image: the cpu backend equals embree --secondary none on the secondary-ray scenes") {
    const int width = 96, height = 72;
    EmbreeOptions none;
    none.secondary = EmbreeSecondary::none;
    for (const std::string& name : secondary_scene_names()) {
        CAPTURE(name);
        SceneOptions options;
        options.aspect = static_cast<float>(width) / static_cast<float>(height);
        const Scene scene = make_builtin_scene(name, options);
        const RenderSettings settings = quiet_settings(width, height, 16);
        const RenderResult cpu = render_cpu(scene, settings);
        const RenderResult ray = render_embree(scene, settings, none);
        // The metric of the thesis scenes' cpu/embree test (test_frontend_cpu.cpp).
        CHECK(fraction_close(cpu.image, ray.image) >= 0.995);
    }
}

TEST_CASE("primary-only image: the gl backend equals the cpu backend in float on the secondary-ray scenes") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    CpuOptions float_options;
    float_options.precision = KernelPrecision::float32;
    for (const std::string& name : secondary_scene_names()) {
        CAPTURE(name);
        SceneOptions options;
        options.aspect = 64.0f / 48.0f;
        const Scene scene = make_builtin_scene(name, options);
        const RenderSettings settings = quiet_settings(64, 48, 4);
        const RenderResult cpu = render_cpu(scene, settings, float_options);
        const RenderResult image = gl->render(scene, settings);
        CHECK(fraction_close(cpu.image, image.image) >= 0.995);
    }
}

// ---------------------------------------------------------------------------
// Bad input

TEST_CASE("bad input: index of refraction and environment are validated, one line each") {
    Scene scene = empty_scene("bad optics");
    scene.materials = {kind_material(MaterialKind::dielectric, 0.0f)};
    add_quad(scene, {-1, -1, -5}, {1, -1, -5}, {1, 1, -5}, {-1, 1, -5}, glm::vec3(0.0f), 0);
    CHECK_THROWS_WITH_AS(validate_scene(scene),
                         "scene 'bad optics': material 0 has index of refraction 0.000000 (must be positive and finite)",
                         SceneError);
    scene.materials[0].ior = NAN;
    CHECK_THROWS_AS(validate_scene(scene), SceneError);
    scene.materials[0].ior = 1.5f;
    scene.environment = 7;
    CHECK_THROWS_WITH_AS(validate_scene(scene), "scene 'bad optics': environment 7 is unknown (0 background, 1 sky)",
                         SceneError);
    scene.environment = BC_ENVIRONMENT_NONE;
    CHECK_NOTHROW(validate_scene(scene));
}

TEST_CASE("bad input: a mirror with no environment reflects the background colour, with a warning") {
    Scene scene = empty_scene("mirror without environment");
    scene.background = glm::vec3(0.25f, 0.5f, 0.75f);
    scene.materials = {kind_material(MaterialKind::mirror, 1.5f)};
    add_quad(scene, {-10, -10, -5}, {10, -10, -5}, {10, 10, -5}, {-10, 10, -5}, glm::vec3(0.0f), 0);
    const RenderResult result = render_embree(scene, quiet_settings(8, 8, 2));
    for (const glm::vec3& pixel : result.image.pixels) CHECK(pixel == scene.background);
    REQUIRE(result.warnings.size() == 1);
    CHECK(result.warnings[0].find("no environment") != std::string::npos);
    // The primary-only rule gives the background too, in every backend.
    CHECK(shade(scene, 0) == scene.background);
    // With the sky, the mirror faces the camera: it shows the sky behind it.
    scene.environment = BC_ENVIRONMENT_SKY;
    const RenderResult sky = render_embree(scene, quiet_settings(8, 8, 2));
    CHECK(sky.warnings.empty());
    CHECK(sky.image.at(4, 4) != scene.background);
}

namespace {

// A one-triangle glTF file whose material has the given JSON body; it
// declares the two material extensions as used and required, as exporters do.
std::string write_gltf(const std::string& file_name, const std::string& material_json) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / ("blurcull_mat_" + file_name);
    std::ofstream out(path);
    out << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        << R"("extensionsUsed":["KHR_materials_transmission","KHR_materials_ior"],)"
        << R"("extensionsRequired":["KHR_materials_transmission"],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
        << R"("materials":[)" << material_json << "],"
        << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
        << R"("min":[0,0,-2],"max":[1,1,-2]}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
        << R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
        << R"(AAAAAAAAAAAAAADAAACAPwAAAAAAAADAAAAAAAAAgD8AAADA"}]})";
    return path.string();
}

struct Loaded {
    Scene scene;
    std::string warnings;
    std::string error;
};

Loaded load_material(const std::string& file_name, const std::string& material_json) {
    Loaded loaded;
    const std::string path = write_gltf(file_name, material_json);
    try {
        loaded.scene = load_gltf_scene(path, GltfOptions{},
                                       [&](const std::string& line) { loaded.warnings += line + "\n"; });
    } catch (const SceneError& error) {
        loaded.error = error.what();
    }
    std::filesystem::remove(path);
    return loaded;
}

}  // namespace

TEST_CASE("glTF materials: metallic 1 roughness 0 is a mirror, transmission is glass with KHR_materials_ior") {
    const Loaded mirror =
        load_material("mirror.gltf", R"({"pbrMetallicRoughness":{"metallicFactor":1,"roughnessFactor":0}})");
    REQUIRE(mirror.error.empty());
    CHECK(mirror.scene.materials.at(0).kind == MaterialKind::mirror);
    CHECK(mirror.warnings.find("glTF has no environment") != std::string::npos);
    CHECK(mirror.scene.environment == BC_ENVIRONMENT_NONE);

    const Loaded rough =
        load_material("rough.gltf", R"({"pbrMetallicRoughness":{"metallicFactor":1,"roughnessFactor":0.2}})");
    CHECK(rough.scene.materials.at(0).kind == MaterialKind::diffuse);
    CHECK(rough.warnings.empty());  // no "not read" warning for the declared extensions either
    const Loaded plain = load_material("plain.gltf", R"({"pbrMetallicRoughness":{}})");
    CHECK(plain.scene.materials.at(0).kind == MaterialKind::diffuse);  // glTF's default roughness is 1

    const Loaded glass = load_material(
        "glass.gltf", R"({"extensions":{"KHR_materials_transmission":{"transmissionFactor":1},)"
                      R"("KHR_materials_ior":{"ior":1.7}}})");
    REQUIRE(glass.error.empty());
    CHECK(glass.scene.materials.at(0).kind == MaterialKind::dielectric);
    CHECK(glass.scene.materials.at(0).ior == doctest::Approx(1.7f));
    CHECK(glass.warnings.find("is not read") == std::string::npos);  // both extensions are implemented
    const Loaded default_ior =
        load_material("glass15.gltf", R"({"extensions":{"KHR_materials_transmission":{"transmissionFactor":0.5}}})");
    CHECK(default_ior.scene.materials.at(0).kind == MaterialKind::dielectric);
    CHECK(default_ior.scene.materials.at(0).ior == doctest::Approx(1.5f));
    const Loaded ior_only = load_material("ioronly.gltf", R"({"extensions":{"KHR_materials_ior":{"ior":1.7}}})");
    CHECK(ior_only.scene.materials.at(0).kind == MaterialKind::diffuse);
}

TEST_CASE("glTF materials: out-of-range factors are clamped with a warning, a bad ior is one error line") {
    const Loaded over =
        load_material("over.gltf", R"({"pbrMetallicRoughness":{"metallicFactor":1.5,"roughnessFactor":-0.5}})");
    REQUIRE(over.error.empty());
    CHECK(over.scene.materials.at(0).kind == MaterialKind::mirror);  // clamped to 1 and 0
    CHECK(over.warnings.find("material 0 metallicFactor 1.500000 is outside [0, 1]; clamped") != std::string::npos);
    CHECK(over.warnings.find("material 0 roughnessFactor -0.500000 is outside [0, 1]; clamped") != std::string::npos);

    const Loaded transmission = load_material(
        "overt.gltf", R"({"extensions":{"KHR_materials_transmission":{"transmissionFactor":-2}}})");
    CHECK(transmission.scene.materials.at(0).kind == MaterialKind::diffuse);  // clamped to 0: no glass
    CHECK(transmission.warnings.find("transmissionFactor -2.000000 is outside [0, 1]; clamped") != std::string::npos);

    const Loaded low_ior = load_material(
        "lowior.gltf", R"({"extensions":{"KHR_materials_transmission":{"transmissionFactor":1},)"
                       R"("KHR_materials_ior":{"ior":0.5}}})");
    CHECK(low_ior.error.find("material 0 KHR_materials_ior ior 0.500000 is not in [1, 1e6]") != std::string::npos);
    CHECK(low_ior.error.find('\n') == std::string::npos);

    const Loaded text_ior = load_material(
        "textior.gltf", R"({"extensions":{"KHR_materials_transmission":{"transmissionFactor":1},)"
                        R"("KHR_materials_ior":{"ior":"glass"}}})");
    CHECK(text_ior.error.find("material 0 KHR_materials_ior ior is not a number") != std::string::npos);
}
