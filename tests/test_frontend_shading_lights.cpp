// KHR_lights_punctual's point and spot lights, KHR_materials_emissive_strength
// and KHR_materials_unlit (docs/reference-renderer.md, "Shading"): the
// falloff formulas of surface_shared.h against hand-computed values, a glTF
// file with a point and a spot light loaded and shaded alike by cpu, embree
// and gl, the light limit's warning, and unknown extensions still warned.
#include "frontend_test_helpers.hpp"

#include "render/common/shading.hpp"
#include "render/common/surface_shared.h"
#include "render/cpu/cpu_backend.hpp"
#include "render/embree/embree_backend.hpp"
#include "scene/gltf/gltf_loader.hpp"

#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;
namespace fs = std::filesystem;
namespace s = blurcull::frontend::surface;

namespace {

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const unsigned v = unsigned(bytes[i]) << 16 | (i + 1 < bytes.size() ? unsigned(bytes[i + 1]) << 8 : 0u) |
                           (i + 2 < bytes.size() ? unsigned(bytes[i + 2]) : 0u);
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[v & 63] : '=';
    }
    return out;
}

// Two quads as 12 non-indexed vertices: a wall at z = 0 (x in [-2, 2], y in
// [-1.5, 1.5]) and a small card in front of it at z = 0.5.
std::vector<unsigned char> quad_bytes() {
    const float wall[] = {-2, -1.5f, 0, 2, -1.5f, 0, 2, 1.5f, 0, -2, -1.5f, 0, 2, 1.5f, 0, -2, 1.5f, 0};
    const float card[] = {-1.6f, -1.2f, 0.5f, -0.9f, -1.2f, 0.5f, -0.9f, -0.5f, 0.5f,
                          -1.6f, -1.2f, 0.5f, -0.9f, -0.5f, 0.5f,  -1.6f, -0.5f, 0.5f};
    std::vector<unsigned char> bytes(sizeof wall + sizeof card);
    std::memcpy(bytes.data(), wall, sizeof wall);
    std::memcpy(bytes.data() + sizeof wall, card, sizeof card);
    return bytes;
}

// A glTF file: the wall (lit, emissive 0.05 x strength 2), the card
// (KHR_materials_unlit), a camera at z = 5, and `lights` (the JSON of
// KHR_lights_punctual's "lights" array), each on a node of `light_nodes`
// (JSON objects without the extension, which is added: node k holds light k).
std::string lit_file(const std::string& lights, const std::vector<std::string>& light_nodes,
                     const std::string& extra_used = "") {
    std::string nodes = R"({"mesh": 0}, {"mesh": 1}, {"camera": 0, "translation": [0, 0, 5]})";
    std::string scene_nodes = "0, 1, 2";
    for (std::size_t k = 0; k < light_nodes.size(); ++k) {
        std::string node = light_nodes[k];
        node.insert(node.size() - 1, std::string(node.size() > 2 ? ", " : "") +
                                         R"("extensions": {"KHR_lights_punctual": {"light": )" + std::to_string(k) +
                                         "}}");
        nodes += ", " + node;
        scene_nodes += ", " + std::to_string(3 + k);
    }
    return R"({"asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_unlit")" +
           extra_used + R"(],
  "extensions": {"KHR_lights_punctual": {"lights": [)" + lights + R"(]}},
  "buffers": [{"byteLength": 144, "uri": "data:application/octet-stream;base64,)" + base64(quad_bytes()) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72}, {"buffer": 0, "byteOffset": 72, "byteLength": 72}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [-2, -1.5, 0], "max": [2, 1.5, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3", "min": [-1.6, -1.2, 0.5], "max": [-0.9, -0.5, 0.5]}],
  "materials": [
    {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}, "emissiveFactor": [0.05, 0, 0],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}}},
    {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.1, 1]}, "extensions": {"KHR_materials_unlit": {}}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]},
             {"primitives": [{"attributes": {"POSITION": 1}, "material": 1}]}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
  "nodes": [)" + nodes + R"(],
  "scenes": [{"nodes": [)" + scene_nodes + R"(]}], "scene": 0})";
}

// The point light at (-1, 0, 1) and the spot light at (1, 0.5, 1.5) shining down -z.
const std::string kPointAndSpot =
    R"({"type": "point", "color": [1, 0.9, 0.7], "intensity": 3, "range": 4},
       {"type": "spot", "color": [0.2, 0.4, 1], "intensity": 8, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}})";
const std::vector<std::string> kPointAndSpotNodes{R"({"translation": [-1, 0, 1]})",
                                                  R"({"translation": [1, 0.5, 1.5]})"};

struct TempFile {
    fs::path folder = fs::temp_directory_path() / ("blurcull_lights_" + std::to_string(::getpid()));
    std::string write(const std::string& name, const std::string& text) {
        fs::create_directories(folder);
        const fs::path file = folder / name;
        std::ofstream(file, std::ios::binary) << text;
        return file.string();
    }
    ~TempFile() {
        std::error_code ignored;
        fs::remove_all(folder, ignored);
    }
};

Scene load(const std::string& path, std::vector<std::string>& warnings) {
    GltfOptions options;
    return load_gltf_scene(path, options, [&](const std::string& w) { warnings.push_back(w); });
}

bool has_warning(const std::vector<std::string>& warnings, const std::string& part) {
    for (const std::string& w : warnings)
        if (w.find(part) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("light falloffs: the range window, the spot cones and the punctual term against hand-computed values") {
    // Inverse square, and the README's window max(min(1 - (d / r)^4, 1), 0) / d^2.
    CHECK(s::bc_range_attenuation(4.0f, 0.0f) == doctest::Approx(0.25));
    CHECK(s::bc_range_attenuation(4.0f, 4.0f) == doctest::Approx((1.0 - 1.0 / 16.0) / 4.0));  // d = 2, r = 4
    CHECK(s::bc_range_attenuation(9.0f, 6.0f) == doctest::Approx((1.0 - 1.0 / 16.0) / 9.0));  // d = 3, r = 6
    CHECK(s::bc_range_attenuation(16.0f, 4.0f) == 0.0f);   // at the range
    CHECK(s::bc_range_attenuation(25.0f, 4.0f) == 0.0f);   // beyond it
    CHECK(s::bc_range_attenuation(0.0f, 4.0f) == 0.0f);    // on the light
    // Spot: t = (cos a - cos outer) / (cos inner - cos outer), clamped, squared.
    const float ci = std::cos(0.2f), co = std::cos(0.5f);
    CHECK(s::bc_spot_attenuation(std::cos(0.1f), ci, co) == 1.0f);
    CHECK(s::bc_spot_attenuation(std::cos(0.6f), ci, co) == 0.0f);
    const double t = (std::cos(0.35) - std::cos(0.5)) / (std::cos(0.2) - std::cos(0.5));
    CHECK(s::bc_spot_attenuation(std::cos(0.35f), ci, co) == doctest::Approx(t * t).epsilon(1e-4));
    // Equal cones: a hard edge, the gap held at 0.001.
    CHECK(s::bc_spot_attenuation(0.9f, 0.9f, 0.9f) == 0.0f);
    CHECK(s::bc_spot_attenuation(0.902f, 0.9f, 0.9f) == 1.0f);
    // Point light 2 above a point facing it: 0.8 (diffuse) x 1 (cosine) x 1/4 x colour.
    const glm::vec3 colour(10.0f, 5.0f, 0.0f);
    glm::vec3 lit = s::bc_punctual_light(BC_LIGHT_POINT, {0, 0, 2}, {0, 0, -1}, colour, 0.0f, 1.0f, 1.0f, {0, 0, 0},
                                         {0, 0, 1}, 0.8f);
    CHECK(lit.x == doctest::Approx(2.0));
    CHECK(lit.y == doctest::Approx(1.0));
    CHECK(lit.z == 0.0f);
    // Tilted 60 degrees: half of it; the back side sees it too (two-sided).
    lit = s::bc_punctual_light(BC_LIGHT_POINT, {0, 0, 2}, {0, 0, -1}, colour, 0.0f, 1.0f, 1.0f, {0, 0, 0},
                               {std::sin(1.0471976f), 0, -std::cos(1.0471976f)}, 0.8f);
    CHECK(lit.x == doctest::Approx(1.0).epsilon(1e-5));
    // Spot at (0, 0, 2) shining down -z, cones 0.2 / 0.5; a point at (x, 0, 0) is at angle atan(x / 2).
    const auto spot_at = [&](float x) {
        return s::bc_punctual_light(BC_LIGHT_SPOT, {0, 0, 2}, {0, 0, -1}, colour, 0.0f, ci, co, {x, 0, 0}, {0, 0, 1},
                                    0.8f)
            .x;
    };
    const double d2 = 4.0 + 0.25;  // x = 0.5
    const double a = std::atan(0.25);
    const double ts = std::clamp((std::cos(a) - std::cos(0.5)) / (std::cos(0.2) - std::cos(0.5)), 0.0, 1.0);
    CHECK(spot_at(0.0f) == doctest::Approx(0.8 * 10.0 / 4.0));
    CHECK(spot_at(0.5f) == doctest::Approx(0.8 * 10.0 * (2.0 / std::sqrt(d2)) / d2 * ts * ts).epsilon(1e-4));
    CHECK(spot_at(2.0f) == 0.0f);  // atan(1) = 0.785 > 0.5: outside the outer cone
    // Directional: the scene light's term, (diffuse x cosine) x colour.
    lit = s::bc_punctual_light(BC_LIGHT_DIRECTIONAL, {}, {0, 1, 1}, colour, 0.0f, 1.0f, 1.0f, {5, 5, 5}, {0, 1, 0},
                               0.8f);
    CHECK(lit.x == doctest::Approx(0.8 * 10.0 * std::sqrt(0.5)));
    // Unlit: the base colour as it is; lit: base x (ambient + light) + emission.
    CHECK(s::bc_material_colour(true, {0.3f, 0.4f, 0.5f}, glm::vec3(9.0f), glm::vec3(1.0f), 0.2f) ==
          glm::vec3(0.3f, 0.4f, 0.5f));
    const glm::vec3 c = s::bc_material_colour(false, {0.5f, 0.5f, 0.5f}, {0.8f, 0.0f, 0.4f}, {0.1f, 0.0f, 0.0f}, 0.2f);
    CHECK(c.x == doctest::Approx(0.6));
    CHECK(c.y == doctest::Approx(0.1));
    CHECK(c.z == doctest::Approx(0.3));
}

TEST_CASE("gltf: point and spot lights, emissive strength and unlit load, and shade alike on cpu, embree and gl") {
    TempFile temp;
    std::vector<std::string> warnings;
    const Scene scene = load(temp.write("lit.gltf", lit_file(kPointAndSpot, kPointAndSpotNodes)), warnings);
    for (const std::string& w : warnings) MESSAGE(w);
    CHECK(warnings.empty());
    REQUIRE(scene.lights.size() == 2);
    const PunctualLight& point = scene.lights[0];
    const PunctualLight& spot = scene.lights[1];
    CHECK(point.type == LightType::point);
    CHECK(point.position == glm::vec3(-1.0f, 0.0f, 1.0f));
    CHECK(point.range == 4.0f);
    CHECK(point.colour.y == doctest::Approx(2.7));
    CHECK(spot.type == LightType::spot);
    CHECK(spot.position == glm::vec3(1.0f, 0.5f, 1.5f));
    CHECK(spot.direction.z == doctest::Approx(-1.0));
    CHECK(spot.range == 0.0f);
    CHECK(spot.cos_inner == doctest::Approx(std::cos(0.2)));
    CHECK(spot.cos_outer == doctest::Approx(std::cos(0.5)));
    CHECK(spot.colour.z == doctest::Approx(8.0));
    // No directional light in the file: the default one is off.
    CHECK(scene.light_color == glm::vec3(0.0f));
    REQUIRE(scene.materials.size() == 2);
    CHECK(scene.materials[0].emissive.x == doctest::Approx(0.1));
    CHECK_FALSE(scene.materials[0].unlit);
    CHECK(scene.materials[1].unlit);

    const int width = 96, height = 72;
    const RenderSettings settings = quiet_settings(width, height, 8);
    const RenderResult cpu = render_cpu(scene, settings);
    // The lights light the wall: brighter under the point light than at the far corner.
    const glm::vec3 under_point = cpu.image.at(width / 2 - 14, height / 2);
    const glm::vec3 corner = cpu.image.at(width / 2 + 30, height / 2 + 22);
    MESSAGE("under the point light " << under_point.x << ", corner " << corner.x);
    CHECK(under_point.x > corner.x + 0.2f);
    Scene unlit_lights = scene;
    unlit_lights.lights.clear();
    unlit_lights.validated = false;
    CHECK(rmse(render_cpu(unlit_lights, settings).image, cpu.image) > 0.05);
    // The unlit card shows its base colour exactly (the pixel wholly on it).
    bool found_card = false;
    for (const glm::vec3& p : cpu.image.pixels)
        found_card = found_card || glm::all(glm::lessThan(glm::abs(p - glm::vec3(0.9f, 0.6f, 0.1f)), glm::vec3(1e-6f)));
    CHECK(found_card);
    // CPU = Embree (test_frontend_cpu.cpp's rule) and GL = CPU (the gl tests' rule).
    const RenderResult ray = render_embree(scene, settings);
    MESSAGE("cpu vs embree RMSE " << rmse(cpu.image, ray.image));
    CHECK(rmse(cpu.image, ray.image) < 0.002);
    CHECK(fraction_close(cpu.image, ray.image) >= 0.995);
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    const RenderResult on_gl = gl->render(scene, settings);
    CpuOptions float_kernel;
    float_kernel.precision = KernelPrecision::float32;
    const RenderResult cpu_float = render_cpu(scene, settings, float_kernel);
    MESSAGE("gl vs cpu float RMSE " << rmse(on_gl.image, cpu_float.image) << ", vs cpu double "
                                    << rmse(on_gl.image, cpu.image));
    CHECK(rmse(on_gl.image, cpu_float.image) < 0.001);
    CHECK(rmse(on_gl.image, cpu.image) < 0.005);
    CHECK(fraction_close(on_gl.image, cpu.image) >= 0.995);
}

TEST_CASE("gltf lights: a directional light keeps the default model, the limit warns once, bad lights warn") {
    TempFile temp;
    // A directional light and 20 point lights: the directional is the scene's light, 16 points are kept.
    std::string lights = R"({"type": "directional", "intensity": 2})";
    std::vector<std::string> nodes{R"({"rotation": [-0.3826834, 0, 0, 0.9238795]})"};
    for (int k = 0; k < 20; ++k) {
        lights += R"(, {"type": "point", "intensity": 1})";
        nodes.push_back(R"({"translation": [)" + std::to_string(k % 5 - 2) + ", 1, 2]}");
    }
    std::vector<std::string> warnings;
    const Scene many = load(temp.write("many.gltf", lit_file(lights, nodes)), warnings);
    for (const std::string& w : warnings) MESSAGE(w);
    CHECK(many.lights.size() == max_punctual_lights);
    CHECK(warnings.size() == 1);
    CHECK(has_warning(warnings, "only 16 lights besides the first directional one are used; 4 more are ignored"));
    CHECK(many.light_color == glm::vec3(2.0f));
    CHECK(many.light_direction.y == doctest::Approx(std::sqrt(0.5)).epsilon(1e-4));
    // Bad cones are clamped, a negative range is unlimited, an unknown type is ignored: one line each.
    warnings.clear();
    const Scene bad = load(temp.write("bad.gltf",
                                      lit_file(R"({"type": "spot", "range": -1, "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.5}},
                                                  {"type": "area"})",
                                               {"{}", "{}"})),
                           warnings);
    for (const std::string& w : warnings) MESSAGE(w);
    REQUIRE(bad.lights.size() == 1);
    CHECK(bad.lights[0].range == 0.0f);
    CHECK(bad.lights[0].cos_inner == doctest::Approx(std::cos(0.5)));
    CHECK(has_warning(warnings, "outside 0 <= inner < outer <= pi/2; they are clamped"));
    CHECK(has_warning(warnings, "range -1.000000 (must be > 0)"));
    CHECK(has_warning(warnings, "unknown type 'area'"));
    CHECK(warnings.size() == 3);
    CHECK(render_cpu(bad, quiet_settings(16, 12, 1)).stats.samples_hit > 0);
    // An emissive strength that is not a number in [0, 1e6]: one warning, the factor alone.
    for (const char* strength : {"-3", "\"big\"", "1e9"}) {
        INFO(strength);
        std::string text = lit_file(kPointAndSpot, kPointAndSpotNodes);
        const std::size_t at = text.find("\"emissiveStrength\": 2");
        REQUIRE(at != std::string::npos);
        text.replace(at, 21, std::string("\"emissiveStrength\": ") + strength);
        warnings.clear();
        const Scene strong = load(temp.write("strength.gltf", text), warnings);
        CHECK(warnings.size() == 1);
        CHECK(has_warning(warnings, "emissiveStrength is not a number in [0, 1e6]; 1 is used"));
        CHECK(strong.materials[0].emissive.x == doctest::Approx(0.05));
    }
    // An extension the loader does not read still warns, once.
    warnings.clear();
    load(temp.write("unknown.gltf", lit_file(kPointAndSpot, kPointAndSpotNodes, R"(, "EXT_not_a_thing")")), warnings);
    CHECK(warnings.size() == 1);
    CHECK(has_warning(warnings, "extension EXT_not_a_thing is not read; ignored"));
}
