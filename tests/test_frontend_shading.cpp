// The shading contract (docs/reference-renderer.md, "Shading"): texture
// lookup (wrap modes, bilinear, sRGB), per-hit shading from barycentrics,
// alpha masks in the raster decision, KHR_lights_punctual, and the glTF
// loader's surface attributes and texture fallbacks; CPU = Embree on a
// textured Khronos model and on a file with COLOR_0, NORMAL and MASK.
#include "frontend_test_helpers.hpp"
#include "test_data_dirs.hpp"

#include "render/common/method_plan.hpp"
#include "render/common/render_method.hpp"
#include "render/common/shading.hpp"
#include "render/common/surface_shading.hpp"
#include "render/common/texture_sampling.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/cpu/methods.hpp"
#include "render/embree/embree_backend.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/scene_checks.hpp"
#include "scene/load_scene.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;

namespace {

const std::string kData = std::string(BLURCULL_SOURCE_DIR) + "/tests/data/shading/";
// The Khronos Cube: a .bin and two PNG files beside it, its base colour
// reduced to 64x64 (tests/data/khronos/README.md).
const std::string kCube = blurcull::testing::khronos_test_dir() + "/Cube/Cube.gltf";

std::uint32_t rgba(int r, int g, int b, int a) {
    return static_cast<std::uint32_t>(r) | static_cast<std::uint32_t>(g) << 8 | static_cast<std::uint32_t>(b) << 16 |
           static_cast<std::uint32_t>(a) << 24;
}

// A 2 x 1 texture: black and white (alpha 0 and 255).
Texture two_texels(TextureWrap wrap) {
    Texture t;
    t.width = 2;
    t.height = 1;
    t.texels = {rgba(0, 0, 0, 0), rgba(255, 255, 255, 255)};
    t.wrap_s = t.wrap_t = wrap;
    return t;
}

Scene load(const std::string& file, std::vector<std::string>* warnings = nullptr) {
    GltfOptions options;
    return load_gltf_scene(kData + file, options, [warnings](const std::string& w) {
        if (warnings) warnings->push_back(w);
    });
}

bool has_warning(const std::vector<std::string>& warnings, const std::string& part) {
    for (const std::string& w : warnings)
        if (w.find(part) != std::string::npos) return true;
    return false;
}

// The CPU vs Embree rule of test_frontend_cpu.cpp ("CPU rasterizer and Embree
// agree on every built-in scene"): RMSE below 0.002 and 99.5% of the pixels
// within 1/255.
void check_cpu_equals_embree(const Scene& scene, int width, int height) {
    RenderSettings settings = quiet_settings(width, height, 16);
    const RenderResult cpu = render_cpu(scene, settings);
    const RenderResult ray = render_embree(scene, settings);
    std::size_t close = 0;
    for (std::size_t i = 0; i < cpu.image.pixels.size(); ++i) {
        const glm::vec3 d = glm::abs(cpu.image.pixels[i] - ray.image.pixels[i]);
        if (d.x <= 1.0f / 255.0f && d.y <= 1.0f / 255.0f && d.z <= 1.0f / 255.0f) ++close;
    }
    const double fraction = double(close) / double(cpu.image.pixels.size());
    const double error = rmse(cpu.image, ray.image);
    MESSAGE(scene.name << ": cpu vs embree RMSE " << error << ", " << 100.0 * fraction << "% of pixels within 1/255");
    CHECK(error < 0.002);
    CHECK(fraction >= 0.995);
    // With the float kernel the CPU backend shades the same hits the same.
    CpuOptions float_kernel;
    float_kernel.precision = KernelPrecision::float32;
    CHECK(rmse(render_cpu(scene, settings, float_kernel).image, cpu.image) < 0.002);
}

// Distinct colours among the pixels: a flat-shaded quad has one or two.
std::size_t distinct_colours(const Image& image) {
    std::vector<glm::vec3> seen;
    for (const glm::vec3& p : image.pixels) {
        bool known = false;
        for (const glm::vec3& q : seen) known = known || glm::all(glm::lessThan(glm::abs(p - q), glm::vec3(1e-3f)));
        if (!known) seen.push_back(p);
        if (seen.size() > 100) break;
    }
    return seen.size();
}

}  // namespace

TEST_CASE("texture lookup: sRGB decode, bilinear filtering, wrap modes") {
    const std::array<float, 256>& table = srgb_decode_table();
    CHECK(table[0] == 0.0f);
    CHECK(table[255] == doctest::Approx(1.0f).epsilon(1e-6));
    CHECK(table[188] == doctest::Approx(0.5029).epsilon(1e-3));  // sRGB 188 is about half the light
    CHECK(table[10] == doctest::Approx(10.0 / 255.0 / 12.92).epsilon(1e-5));  // the linear segment

    const Texture repeat = two_texels(TextureWrap::repeat);
    // Texel centres at u = 0.25 and 0.75; halfway between them is the mean.
    CHECK(sample_texture(repeat, {0.25f, 0.5f}).x == 0.0f);
    CHECK(sample_texture(repeat, {0.75f, 0.5f}).x == doctest::Approx(1.0f));
    CHECK(sample_texture(repeat, {0.5f, 0.5f}).x == doctest::Approx(0.5f));
    CHECK(sample_texture(repeat, {0.5f, 0.5f}).w == doctest::Approx(0.5f));  // alpha is filtered linearly
    // Repeat: u = 0 lies between the last and first texel; 1.25 is 0.25.
    CHECK(sample_texture(repeat, {0.0f, 0.5f}).x == doctest::Approx(0.5f));
    CHECK(sample_texture(repeat, {1.25f, 0.5f}).x == doctest::Approx(0.0f));
    CHECK(sample_texture(repeat, {-0.25f, 0.5f}).x == doctest::Approx(1.0f));
    // Clamp: left of the first centre stays the first texel.
    const Texture clamp = two_texels(TextureWrap::clamp);
    CHECK(sample_texture(clamp, {0.0f, 0.5f}).x == 0.0f);
    CHECK(sample_texture(clamp, {-5.0f, 0.5f}).x == 0.0f);
    CHECK(sample_texture(clamp, {7.0f, 0.5f}).x == doctest::Approx(1.0f));
    // Mirror: [1, 2] is [0, 1] backwards, so 1.25 reads what 0.75 reads.
    const Texture mirror = two_texels(TextureWrap::mirror);
    CHECK(sample_texture(mirror, {1.25f, 0.5f}).x == doctest::Approx(1.0f));
    CHECK(sample_texture(mirror, {1.75f, 0.5f}).x == doctest::Approx(0.0f));
    CHECK(sample_texture(mirror, {-0.25f, 0.5f}).x == doctest::Approx(0.0f));
    // NaN and far coordinates: a texel, never a crash.
    const float nan = std::nanf("");
    const glm::vec4 at_nan = sample_texture(repeat, {nan, nan});
    CHECK(std::isfinite(at_nan.x));
    CHECK(std::isfinite(sample_texture(mirror, {1e30f, -1e30f}).x));
    CHECK(std::isfinite(sample_texture(clamp, {-1e30f, 1e30f}).x));
}

TEST_CASE("shade_hit without attributes is the flat colour, bit for bit, anywhere on the triangle") {
    Scene scene = make_builtin_scene("car", SceneOptions{});
    for (std::size_t t = 0; t < scene.triangles.size(); t += 97) {
        CHECK_FALSE(shades_per_hit(scene, t));
        const glm::vec3 flat = shade(scene, t);
        for (glm::vec3 b : {glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.2f, 0.3f, 0.5f)}) {
            const glm::vec3 hit = shade_hit(scene, t, b, glm::vec3(0.0f, 0.0f, -1.0f));
            CHECK(std::memcmp(&hit, &flat, sizeof hit) == 0);
        }
    }
}

TEST_CASE("shade_hit: vertex colours, smooth normals, emission and the light colour") {
    Scene scene;
    scene.name = "hand-made";
    scene.position_open = scene.position_close = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    scene.triangles = {{0u, 1u, 2u}};
    scene.triangle_material = {0u};
    scene.materials.emplace_back();
    scene.materials[0].base_color = glm::vec3(1.0f);
    scene.light_direction = glm::vec3(0, 0, 1);
    const glm::vec3 centre(1.0f / 3.0f);
    CHECK(shade_hit(scene, 0, centre, {}).x == doctest::Approx(1.0f));  // facing the light
    scene.vertex_color = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};
    CHECK(shades_per_hit(scene, 0));
    const glm::vec3 red_corner = shade_hit(scene, 0, {1, 0, 0}, {});
    CHECK(red_corner.x == doctest::Approx(1.0f));
    CHECK(red_corner.y == 0.0f);
    // A normal perpendicular to the light leaves the ambient term only.
    scene.vertex_color.clear();
    scene.normal = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
    CHECK(shade_hit(scene, 0, centre, {}).x == doctest::Approx(shading_ambient));
    // Normals half way: the interpolated normal is used (|n . l| = cos 45 degrees).
    scene.normal = {{1, 0, 1}, {1, 0, 1}, {1, 0, 1}};
    CHECK(shade_hit(scene, 0, centre, {}).x == doctest::Approx(shading_ambient + shading_diffuse * std::sqrt(0.5f)));
    // Emission adds; the light colour scales the diffuse term.
    scene.normal.clear();
    scene.materials[0].emissive = glm::vec3(0.25f, 0, 0);
    scene.light_color = glm::vec3(0.5f);
    CHECK(shade_hit(scene, 0, centre, {}).x == doctest::Approx(shading_ambient + 0.5f * shading_diffuse + 0.25f));
    CHECK(shade(scene, 0).x == doctest::Approx(shading_ambient + 0.5f * shading_diffuse + 0.25f));
}

TEST_CASE("gltf: COLOR_0, NORMAL, MASK, a texture with a transform and a directional light are read") {
    std::vector<std::string> warnings;
    const Scene scene = load("attributes.gltf", &warnings);
    for (const std::string& w : warnings) MESSAGE(w);
    CHECK(warnings.empty());
    REQUIRE(scene.materials.size() == 2);
    CHECK(scene.materials[0].alpha_mode == AlphaMode::mask);
    CHECK(scene.materials[0].alpha_cutoff == doctest::Approx(0.5f));
    REQUIRE(scene.textures.size() == 1);
    CHECK(scene.textures[0].width == 4);
    CHECK(scene.textures[0].wrap_s == TextureWrap::mirror);
    CHECK(scene.materials[1].base_color_texture.texture == 0);
    // T R S of offset (0.25, 0), rotation 90 degrees, scale 3: u maps to 3 v' (the spec's rotation sense).
    const glm::mat3& m = scene.materials[1].base_color_texture.transform;
    CHECK(m[0][0] == doctest::Approx(0.0f).epsilon(1e-6));
    CHECK(m[0][1] == doctest::Approx(3.0f));
    CHECK(m[1][0] == doctest::Approx(-3.0f));
    CHECK(scene.materials[1].base_color_texture.transform[2][0] == doctest::Approx(0.25f));
    CHECK(scene.materials[1].emissive.x == doctest::Approx(0.05f));
    CHECK(scene.texcoord.size() == scene.position_open.size());
    CHECK(scene.vertex_color.size() == scene.position_open.size());
    CHECK(scene.normal.size() == scene.position_open.size());
    CHECK(scene.vertex_color[4] == glm::vec4(1.0f));  // the back quad has no COLOR_0: white
    CHECK(scene.normal[4] == glm::vec3(0.0f));        // nor NORMAL: flat
    // The light is rotated -45 degrees about x: it shines along (0, -1, -1) / sqrt 2.
    CHECK(scene.light_direction.y == doctest::Approx(std::sqrt(0.5f)).epsilon(1e-4));
    CHECK(scene.light_direction.z == doctest::Approx(std::sqrt(0.5f)).epsilon(1e-4));
    CHECK(scene.light_color.y == doctest::Approx(0.9f));
}

TEST_CASE("alpha mask: masked-out samples lose the depth test, and CPU = Embree") {
    const Scene scene = load("attributes.gltf");
    const int width = 96, height = 72;
    RenderSettings settings = quiet_settings(width, height, 4);
    const RenderResult cpu = render_cpu(scene, settings);
    // The front quad's alpha falls from 1 (left) to 0 (right): the right half
    // of the screen shows the textured back quad, the left the front quad.
    Scene opaque = scene;
    opaque.materials[0].alpha_mode = AlphaMode::opaque;
    const RenderResult without_mask = render_cpu(opaque, settings);
    const glm::vec3 left = cpu.image.at(width / 2 - 12, height / 2);
    const glm::vec3 right = cpu.image.at(width / 2 + 12, height / 2);
    CHECK(glm::length(left - without_mask.image.at(width / 2 - 12, height / 2)) < 1e-6f);
    CHECK(glm::length(right - without_mask.image.at(width / 2 + 12, height / 2)) > 0.05f);
    CHECK(cpu.stats.samples_hit < without_mask.stats.samples_hit);  // masked-out samples are not hits
    check_cpu_equals_embree(scene, width, height);
    check_cpu_equals_embree(opaque, width, height);
    // Every tracing shape runs the mask filter with the right sample (ray id).
    const RenderResult packets = render_embree(scene, settings);
    for (EmbreeTracing tracing : {EmbreeTracing::single, EmbreeTracing::packet4, EmbreeTracing::packet8,
                                  EmbreeTracing::stream}) {
        EmbreeOptions options;
        options.tracing = tracing;
        INFO(tracing_name(tracing));
        CHECK(same_pixels(render_embree(scene, settings, options).image, packets.image));
    }
}

TEST_CASE("a textured Khronos model (Cube) renders its texture, CPU = Embree") {
    std::vector<std::string> warnings;
    GltfOptions options;
    const Scene scene = load_gltf_scene(kCube, options,
                                        [&](const std::string& w) { warnings.push_back(w); });
    REQUIRE(scene.textures.size() == 1);
    CHECK(scene.textures[0].width > 16);
    CHECK(scene.materials[0].base_color_texture.texture == 0);
    CHECK(scene.texcoord.size() == scene.position_open.size());
    const RenderResult cpu = render_cpu(scene, quiet_settings(96, 72, 4));
    Scene untextured = scene;
    untextured.materials[0].base_color_texture.texture = -1;
    untextured.normal.clear();
    const RenderResult flat = render_cpu(untextured, quiet_settings(96, 72, 4));
    MESSAGE("distinct colours: textured " << distinct_colours(cpu.image) << ", flat " << distinct_colours(flat.image));
    CHECK(distinct_colours(cpu.image) > distinct_colours(flat.image) + 20);
    check_cpu_equals_embree(scene, 96, 72);
}

TEST_CASE("bad textures and texture coordinates: one warning each, the factor or a fallback, never a failure") {
    struct Case {
        const char* file;
        const char* warning;
    };
    for (const Case& c : {Case{"bad_texture_missing.gltf", "cannot be read; its textures fall back to their factors"},
                          Case{"bad_texture_truncated.gltf", "cannot decode"},
                          Case{"bad_texture_format.gltf", "cannot decode"},
                          Case{"bad_texture_huge.gltf", "over the texture budget"}}) {
        INFO(c.file);
        std::vector<std::string> warnings;
        const Scene scene = load(c.file, &warnings);
        for (const std::string& w : warnings) MESSAGE(w);
        CHECK(warnings.size() == 1);  // one line per bad texture
        CHECK(has_warning(warnings, c.warning));
        // The factor stays, without a texture: the quad renders in its flat colour.
        CHECK(scene.materials[0].base_color_texture.texture == -1);
        CHECK(scene.materials[0].base_color.y == doctest::Approx(0.6f));
        CHECK(render_cpu(scene, quiet_settings(16, 12, 1)).stats.samples_hit > 0);
    }
    std::vector<std::string> warnings;
    const Scene nan_uv = load("bad_texcoord_nan.gltf", &warnings);
    CHECK(has_warning(warnings, "non-finite texture coordinates; 0 is used"));
    CHECK(nan_uv.texcoord[0].x == 0.0f);
    warnings.clear();
    const Scene far_uv = load("bad_texcoord_far.gltf", &warnings);
    CHECK(has_warning(warnings, "beyond +-65536; they are clamped"));
    CHECK(far_uv.texcoord[0].x == 65536.0f);
    CHECK(far_uv.texcoord[1].y == -65536.0f);
    const RenderResult far = render_cpu(far_uv, quiet_settings(16, 12, 4));
    for (const glm::vec3& p : far.image.pixels) CHECK(std::isfinite(p.x + p.y + p.z));
}

TEST_CASE("scene validation refuses attribute arrays and texture indices that do not fit") {
    Scene scene = load("attributes.gltf");
    scene.validated = false;
    Scene short_uv = scene;
    short_uv.texcoord.pop_back();
    CHECK_THROWS_WITH_AS(validate_scene(short_uv), doctest::Contains("texture coordinates for"), SceneError);
    Scene bad_index = scene;
    bad_index.materials[1].base_color_texture.texture = 5;
    CHECK_THROWS_WITH_AS(validate_scene(bad_index), doctest::Contains("uses texture 5"), SceneError);
    Scene bad_texels = scene;
    bad_texels.textures[0].texels.pop_back();
    CHECK_THROWS_WITH_AS(validate_scene(bad_texels), doctest::Contains("texels for 4x4"), SceneError);
}

namespace {

// The GL tests' rule: RMSE below 0.001 against the CPU backend's float kernel
// (whose winners the GL backend's equal), below 0.005 against double, and
// 99.5% of the pixels within 1/255 of double. Returns the GL render.
RenderResult check_gl_equals_cpu(GlRenderer& gl, const Scene& scene, const RenderSettings& settings,
                                 const GlOptions& gl_options = {}) {
    const RenderResult on_gl = gl.render(scene, settings, gl_options);
    const RenderResult cpu = render_cpu(scene, settings);
    CpuOptions float_kernel;
    float_kernel.precision = KernelPrecision::float32;
    const RenderResult cpu_float = render_cpu(scene, settings, float_kernel);
    MESSAGE(scene.name << ": gl vs cpu float RMSE " << rmse(on_gl.image, cpu_float.image) << ", vs cpu double "
                       << rmse(on_gl.image, cpu.image) << "; samples hit gl " << on_gl.stats.samples_hit
                       << ", cpu float " << cpu_float.stats.samples_hit);
    CHECK(rmse(on_gl.image, cpu_float.image) < 0.001);
    CHECK(rmse(on_gl.image, cpu.image) < 0.005);
    CHECK(fraction_close(on_gl.image, cpu.image) >= 0.995);
    return on_gl;
}

Scene without_mask(const Scene& scene) {
    Scene opaque = scene;
    for (Material& material : opaque.materials) material.alpha_mode = AlphaMode::opaque;
    return opaque;
}

}  // namespace

TEST_CASE("gl: textures, vertex colours and normals shade as on the cpu backend (the gl tests' tolerances)") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    GltfOptions options;
    const Scene opaque = without_mask(load("attributes.gltf"));
    const Scene cube = load_gltf_scene(kCube, options);
    for (const Scene* scene : std::initializer_list<const Scene*>{&opaque, &cube}) {
        INFO(scene->name);
        check_gl_equals_cpu(*gl, *scene, quiet_settings(96, 72, 8));
    }
}

TEST_CASE("alpha mask from a texture (wrap modes, transform, factor and COLOR_0 alpha): CPU = Embree") {
    const Scene scene = load("mask_texture.gltf");
    REQUIRE(scene.textures.size() == 1);
    CHECK(scene.textures[0].wrap_s == TextureWrap::repeat);
    CHECK(scene.textures[0].wrap_t == TextureWrap::clamp);
    const RenderSettings settings = quiet_settings(96, 72, 4);
    const RenderResult masked = render_cpu(scene, settings);
    const RenderResult opaque = render_cpu(without_mask(scene), settings);
    // The holes show the green quad behind.
    CHECK(masked.stats.samples_hit < opaque.stats.samples_hit);
    CHECK(rmse(masked.image, opaque.image) > 0.05);
    check_cpu_equals_embree(scene, 96, 72);
}

TEST_CASE("gl: alpha masks decide coverage before the depth test, as on the cpu backend") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    for (const char* file : {"attributes.gltf", "mask_texture.gltf"}) {
        Scene scene = load(file);
        for (int variant = 0; variant < 4; ++variant) {
            // The static path drawn per pass (4 spp) and per group of passes
            // (16 spp), every triangle on the moving path, and defocus (the
            // moving path for the defocused quad behind).
            RenderSettings settings = quiet_settings(96, 72, variant == 1 ? 16 : 4);
            GlOptions gl_options;
            gl_options.force_full_path = variant == 2;
            Scene variant_scene = scene;
            if (variant == 3) {
                variant_scene.camera.lens_radius = 0.08f;
                variant_scene.camera.focus_distance = 4.0f;
            }
            INFO(file << ", variant " << variant);
            const RenderResult on_gl = check_gl_equals_cpu(*gl, variant_scene, settings, gl_options);
            CHECK(on_gl.warnings.empty());
            // Drawn opaque, the masked-out samples would hide the quad behind.
            const RenderResult opaque = gl->render(without_mask(variant_scene), settings, gl_options);
            CHECK(on_gl.stats.samples_hit < opaque.stats.samples_hit);
            CHECK(rmse(on_gl.image, opaque.image) > 0.05);
        }
    }
}

namespace {

RenderResult render_cpu_method(const Scene& scene, const RenderSettings& settings, std::vector<std::uint32_t>& ids) {
    switch (settings.method) {
        case RenderMethod::interleave: return render_interleave(scene, settings, {}, &ids);
        case RenderMethod::interval: return render_interval(scene, settings, &ids);
        default: return render_accum(scene, settings, &ids);
    }
}

// Every sample the CPU method kept is covered by its winner at method_sample's
// position (the double test the CPU method decided by): the resolve shades
// each sample where it was tested, not at the centroid of the fallback.
void check_samples_where_tested(const Scene& scene, const RenderSettings& settings,
                                const std::vector<std::uint32_t>& ids) {
    const MethodPlan plan = make_method_plan(scene, settings);
    const std::vector<std::int32_t> tuple_of_cell = method_tuple_of_cell(plan, settings.width, settings.height);
    std::size_t kept = 0, covered = 0;
    for (int py = 0; py < settings.height; ++py) {
        for (int px = 0; px < settings.width; ++px) {
            for (int j = 0; j < settings.spp; ++j) {
                const std::uint32_t id = ids[(static_cast<std::size_t>(py) * settings.width + px) * settings.spp + j];
                if (id == no_sample_hit) continue;
                ++kept;
                const MethodSample s = method_sample(plan, tuple_of_cell, px, py, j);
                double depth = 0.0;
                covered += blurcull::kerneld::covers(plan.triangles[id], blurcull::kerneld::vec2(s.ndc),
                                                     blurcull::kerneld::vec2(s.lens), double(s.time),
                                                     double(plan.model.znear), depth)
                               ? 1
                               : 0;
            }
        }
    }
    REQUIRE(kept > 0);
    CHECK(covered == kept);
}

}  // namespace

TEST_CASE("interleave, interval, accum: textures, COLOR_0, NORMAL and MASK per sample, cpu = gl") {
    GlRenderer* gl = renderer_or_skip();
    GltfOptions cube_options;
    const std::vector<Scene> scenes{load("attributes.gltf"), load("mask_texture.gltf"),
                                    load_gltf_scene(kCube, cube_options)};
    for (const RenderMethod method : {RenderMethod::interleave, RenderMethod::interval, RenderMethod::accum}) {
        for (const Scene& scene : scenes) {
            RenderSettings settings = quiet_settings(96, 72, 4);
            settings.method = method;
            INFO(std::string(to_string(method)) << " on " << scene.name);
            std::vector<std::uint32_t> cpu_ids;
            const RenderResult cpu = render_cpu_method(scene, settings, cpu_ids);
            CHECK(cpu.warnings.empty());
            check_samples_where_tested(scene, settings, cpu_ids);
            // Shaded per sample: more than the few colours of flat facets.
            Scene flat = without_mask(scene);
            for (Material& material : flat.materials) material.base_color_texture.texture = -1;
            flat.vertex_color.clear();
            flat.normal.clear();
            std::vector<std::uint32_t> flat_ids;
            const RenderResult flat_image = render_cpu_method(flat, settings, flat_ids);
            MESSAGE(std::string(to_string(method)) << " on " << scene.name << ": distinct colours " << distinct_colours(cpu.image)
                                      << ", flat " << distinct_colours(flat_image.image));
            CHECK(distinct_colours(cpu.image) > distinct_colours(flat_image.image) + 20);
            // The mask: the masked-out samples show what is behind.
            std::vector<std::uint32_t> opaque_ids;
            const RenderResult opaque = render_cpu_method(without_mask(scene), settings, opaque_ids);
            const bool masked = scene.name != "Cube";
            if (masked) {
                CHECK(cpu.stats.samples_hit < opaque.stats.samples_hit);
                CHECK(rmse(cpu.image, opaque.image) > 0.05);
            }
            if (gl == nullptr) continue;
            // The GL tests' method rule (test_frontend_gl_methods.cpp).
            GlOptions gl_options;
            gl_options.keep_sample_ids = true;
            std::vector<std::uint32_t> gl_ids;
            const RenderResult on_gl = gl->render(scene, settings, gl_options, &gl_ids);
            const double same = fraction_equal(gl_ids, cpu_ids);
            MESSAGE("  gl: samples identical " << same << ", RMSE " << rmse(on_gl.image, cpu.image) << ", hits gl "
                                               << on_gl.stats.samples_hit << " cpu " << cpu.stats.samples_hit);
            CHECK(on_gl.warnings.empty());
            CHECK(same >= 0.998);
            CHECK(rmse(on_gl.image, cpu.image) < 0.005);
            CHECK(fraction_close(on_gl.image, cpu.image) >= 0.995);
            const double hits_cpu = static_cast<double>(cpu.stats.samples_hit);
            CHECK(std::abs(static_cast<double>(on_gl.stats.samples_hit) - hits_cpu) <= 0.0001 * hits_cpu + 1.0);
            if (masked) CHECK(on_gl.stats.samples_hit < opaque.stats.samples_hit);
        }
    }
}
