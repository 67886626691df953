// The robustness corpus of malformed and extreme glTF files
// (tests/data/gltf/, written by make_test_files.py; docs/robustness.md lists
// each with its message): every file either loads with a documented warning
// (handed to the caller, never printed) or throws one SceneError line naming
// the file and the problem. Also the conformance cases (versions, required
// extensions, KHR_mesh_quantization, missing images) and morph targets as
// motion, on files of its own and on the Khronos SparseMorphCube
// (tests/data/khronos; docs/scenes.md, "glTF support").
#include "render/cpu/cpu_backend.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "test_data_dirs.hpp"

#include <doctest/doctest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

using namespace blurcull::frontend;

namespace {

const std::string kDataDir = std::string(BLURCULL_SOURCE_DIR) + "/tests/data/gltf/";

// Loads a file; returns the SceneError message ("" when it loaded) and the
// warning lines the loader handed back, each ending in a newline as the
// command prints them. The loader itself must print nothing on std::cerr.
struct Outcome {
    std::string error;
    std::string warnings;
    std::size_t triangles = 0;
};

Outcome load(const std::string& path, const GltfOptions& options = GltfOptions{}) {
    Outcome outcome;
    std::ostringstream captured;
    std::streambuf* saved = std::cerr.rdbuf(captured.rdbuf());
    const WarningSink collect = [&](const std::string& line) { outcome.warnings += line + "\n"; };
    try {
        outcome.triangles = load_gltf_scene(path, options, collect).triangles.size();
    } catch (const SceneError& error) {
        outcome.error = error.what();
    } catch (...) {
        std::cerr.rdbuf(saved);
        throw;
    }
    std::cerr.rdbuf(saved);
    CHECK(captured.str().empty());
    return outcome;
}

}  // namespace

TEST_CASE("glTF corpus: each malformed file is one SceneError line naming the file and the problem") {
    const std::pair<const char*, const char*> cases[] = {
        {"bad_json.gltf", "cannot parse glTF"},
        {"bad_truncated.glb", "GLB header says 796 bytes but the file has 200"},
        {"bad_glb_chunk.glb", "GLB JSON chunk runs past the end of the file"},
        {"bad_accessor_index.gltf", "refers to accessor 7, which does not exist"},
        {"bad_buffer_view_index.gltf", "accessor 0 refers to buffer view 9, which does not exist"},
        {"bad_accessor_past_end.gltf", "accessor 0 reads past the end of buffer view 0"},
        {"bad_index_count_past_end.gltf", "accessor 1 reads past the end of buffer view 1"},
        {"bad_count_overflow.gltf", "accessor 0 reads past the end of buffer view 0"},
        {"bad_count_no_view.gltf", "accessor 0 has no buffer view and count 1152921504606846976 (limit 16777216)"},
        {"bad_buffer_view_past_end.gltf", "reads past the end of buffer 0"},
        {"bad_index_value.gltf", "index value 5 (at 2) is not below the vertex count 3"},
        {"bad_stride_small.gltf", "buffer view 0 stride 4 is smaller than an element (12 bytes)"},
        {"bad_stride_huge.gltf", "byteStride"},
        {"bad_mode.gltf", "mesh 0 primitive 0 has unknown mode 9"},
        {"bad_lines_only.gltf", "no triangles to render"},
        {"bad_all_inf.gltf", "no triangles to render"},
        {"bad_camera_yfov.gltf", "camera 0 has yfov 0"},
        {"bad_camera_yfov_negative.gltf", "camera 0 has yfov -0.5"},
        {"bad_camera_znear.gltf", "camera 0 has znear 0"},
        {"bad_camera_zfar.gltf", "camera 0 has zfar 0.500000 (must be greater than znear 1.000000)"},
        {"bad_missing_buffer.gltf", "does_not_exist.bin"},
        {"bad_node_cycle.gltf", "node cycle"},
        {"bad_node_self_child.gltf", "node cycle: node 0 is its own child"},
        {"bad_node_two_parents.gltf", "node 2 has two parents"},
        {"bad_node_depth.gltf", "levels deep (limit 1000)"},
        {"bad_keyframes_order.gltf", "keyframe times are not increasing"},
        {"bad_keyframes_nan.gltf", "keyframe time 1 is not finite"},
        // Conformance (issue 14 item 6): the version or the extension named.
        {"bad_version_1.gltf", "glTF version 1.0 is not supported (blurcull reads glTF 2.x)"},
        {"bad_version_3.gltf", "glTF version 3.0 is not supported (blurcull reads glTF 2.x)"},
        {"bad_version_text.gltf", "asset.version 'two' is not a glTF version"},
        {"bad_min_version.gltf", "asset.minVersion 2.1 is not supported (blurcull reads glTF 2.0)"},
        {"bad_glb_version_1.glb", "GLB container version 1 is not supported"},
        // Draco is read now (issue 25 item 1): this file's buffer view is
        // plain triangle data, not a Draco mesh.
        {"bad_required_draco.gltf",
         "mesh 0 primitive 0: KHR_draco_mesh_compression data (36 bytes) cannot be decoded: Not a Draco file."},
        {"bad_required_newline.gltf", "required extension EXT_line?break is not supported"},
        // Morph targets (issue 14 item 5).
        {"bad_morph_node_weights.gltf", "node 0 has 3 weights but mesh 0 has 2 morph targets"},
        {"bad_morph_channel.gltf", "animation 0 channel 0 has 1 weights per key for node 0's 2 morph targets"},
        {"bad_morph_target_count.gltf", "mesh 0 primitive 0 morph target 0 POSITION has 2 elements for 3 vertices"},
        {"bad_morph_primitives.gltf", "mesh 0 primitive 1 has 0 morph targets, primitive 0 has 2"},
    };
    for (const auto& c : cases) {
        const std::string path = kDataDir + c.first;
        CAPTURE(path);
        const Outcome outcome = load(path);
        CHECK(outcome.error.rfind(path + ": ", 0) == 0);
        CHECK(outcome.error.find(c.second) != std::string::npos);
        CHECK(outcome.error.find('\n') == std::string::npos);
    }
}

TEST_CASE("glTF corpus: documented fallbacks load and say so in a warning") {
    // NaN and +-Inf positions: that primitive is skipped with one warning.
    for (const char* name : {"nan_position.gltf", "inf_position.gltf"}) {
        const std::string path = kDataDir + name;
        CAPTURE(path);
        const Outcome outcome = load(path);
        CHECK(outcome.error.empty());
        CHECK(outcome.triangles == 1);
        CHECK(outcome.warnings == path + ": warning: mesh 0 primitive 1 has non-finite positions; skipped\n");
    }
    // Points are skipped with a warning; the triangles load.
    const Outcome modes = load(kDataDir + "modes.gltf");
    CHECK(modes.triangles == 7);
    CHECK(modes.warnings.find("points primitives are skipped") != std::string::npos);
    // Skipped lines warn before the error that nothing is left.
    CHECK(load(kDataDir + "bad_lines_only.gltf").warnings.find("line primitives are skipped") != std::string::npos);
    // A negative byteStride is dropped by tinygltf (read as absent: tightly
    // packed); the data is still bounds-checked and the file loads.
    CHECK(load(kDataDir + "bad_stride_negative.gltf").triangles == 1);
}

namespace {

Scene load_scene_file(const std::string& path, const GltfOptions& options = GltfOptions{}) {
    return load_gltf_scene(path, options, {});
}

GltfOptions shutter(float open, float close) {
    GltfOptions options;
    options.shutter_open = open;
    options.shutter_close = close;
    return options;
}

void check_positions(const std::vector<glm::vec3>& actual, std::size_t first, const std::vector<glm::vec3>& expected,
                     float tolerance = 1e-6f) {
    REQUIRE(actual.size() >= first + expected.size());
    for (std::size_t v = 0; v < expected.size(); ++v) {
        CAPTURE(v);
        CAPTURE(actual[first + v].x);
        CAPTURE(actual[first + v].y);
        CAPTURE(actual[first + v].z);
        CHECK(glm::all(glm::lessThanEqual(glm::abs(actual[first + v] - expected[v]), glm::vec3(tolerance))));
    }
}

// The triangle of make_test_files.py morphed by its two targets (MORPH_DENSE:
// +1 z everywhere; MORPH_SPARSE: vertex 1 +2 y) with weights w0, w1.
std::vector<glm::vec3> morphed_triangle(float w0, float w1, glm::vec3 offset = glm::vec3(0.0f)) {
    return {glm::vec3(0, 0, w0) + offset, glm::vec3(1, 2 * w1, w0) + offset, glm::vec3(0, 1, w0) + offset};
}

// morph_animated.gltf's weights: keys at 0, 1, 2 s of (0, 0), (1, 0.5), (1, 1), LINEAR.
glm::vec2 animated_weights(float t) {
    if (t <= 1.0f) return glm::vec2(t, 0.5f * t);
    return glm::vec2(1.0f, 0.5f + 0.5f * (t - 1.0f));
}

}  // namespace

TEST_CASE("glTF conformance: glTF 2.1 loads; unread extensions, missing images warn and fall back") {
    CHECK(load(kDataDir + "version_2_1.gltf").triangles == 1);

    const std::string unknown = kDataDir + "unknown_extension_used.gltf";
    const Outcome used = load(unknown);
    CHECK(used.triangles == 1);
    CHECK(used.warnings == unknown + ": warning: extension EXT_blurcull_unknown is not read; ignored\n");

    const std::string odd = kDataDir + "extension_names_odd.gltf";
    CHECK(load(odd).warnings == odd + ": warning: extension EXT_line?break is not read; ignored\n" + odd +
                                    ": warning: extension EXT_" + std::string(116, 'x') + "... is not read; ignored\n");

    // A missing texture image: one warning naming it, the factor stays.
    const std::string textured = kDataDir + "missing_texture.gltf";
    const Outcome missing = load(textured);
    CHECK(missing.error.empty());
    CHECK(missing.triangles == 1);
    CHECK(missing.warnings == textured + ": warning: image 0 ('missing_texture.png') cannot be read; its textures "
                                         "fall back to their factors\n");
    const std::string empty = kDataDir + "empty_texture.gltf";
    const Outcome truncated = load(empty);
    CHECK(truncated.triangles == 1);
    CHECK(truncated.warnings == empty + ": warning: image 0 ('empty_texture.png') cannot be read; its textures fall "
                                        "back to their factors\n");
    const Scene scene = load_scene_file(textured);
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].base_color == glm::vec3(0.2f, 0.4f, 0.8f));
}

TEST_CASE("glTF conformance: KHR_mesh_quantization's integer positions, dequantised by the node transform") {
    const std::string path = kDataDir + "quantized.gltf";
    const Outcome outcome = load(path);
    CHECK(outcome.error.empty());
    CHECK(outcome.warnings.empty());
    const Scene scene = load_scene_file(path);
    REQUIRE(scene.position_open.size() == 12);
    // SHORT 0/1000, node scale 1/1000, with a normalized SHORT morph target
    // (0, 0, 32767 -> 1) at mesh weight 0.5 before the scale.
    check_positions(scene.position_open, 0, {{0, 0, 0.0005f}, {1, 0, 0.0005f}, {0, 1, 0.0005f}});
    // Normalized BYTE (127 -> 1, -127 -> -1), translated +2 x.
    check_positions(scene.position_open, 3, {{2, 0, 0}, {3, 0, 0}, {2, -1, 0}});
    // Normalized UNSIGNED_SHORT (65535 -> 1), translated +4 x.
    check_positions(scene.position_open, 6, {{4, 0, 0}, {5, 0, 0}, {4, 1, 0}});
    // UNSIGNED_BYTE 0/2, scale 0.5, translated +6 x.
    check_positions(scene.position_open, 9, {{6, 0, 0}, {7, 0, 0}, {6, 1, 0}});
    CHECK(scene.position_close == scene.position_open);
}

TEST_CASE("glTF morph targets: weights animation inside one keyframe segment is exact linear motion") {
    const std::string path = kDataDir + "morph_animated.gltf";
    const Outcome outcome = load(path, shutter(0.25f, 0.75f));
    CHECK(outcome.error.empty());
    CHECK(outcome.warnings.empty());  // morph targets are read, not ignored

    const Scene scene = load_scene_file(path, shutter(0.25f, 0.75f));
    const glm::vec2 w_open = animated_weights(0.25f), w_close = animated_weights(0.75f);
    check_positions(scene.position_open, 0, morphed_triangle(w_open.x, w_open.y));
    check_positions(scene.position_close, 0, morphed_triangle(w_close.x, w_close.y));
    // Inside one segment the morph is linear in time: the shutter's midpoint
    // is where the linear motion between the two ends puts it.
    const Scene middle = load_scene_file(path, shutter(0.5f, 0.5f));
    for (std::size_t v = 0; v < 3; ++v) {
        CHECK(glm::length(middle.position_open[v] - glm::mix(scene.position_open[v], scene.position_close[v], 0.5f)) <
              1e-6f);
    }
    // blur_scale stretches the interval as for node animation.
    GltfOptions longer = shutter(0.25f, 0.5f);
    longer.blur_scale = 2.0f;
    check_positions(load_scene_file(path, longer).position_close, 0, morphed_triangle(w_close.x, w_close.y));
}

TEST_CASE("glTF morph targets: a shutter across keyframes, defaults, and no animation") {
    const std::string path = kDataDir + "morph_animated.gltf";
    // Across the key at 1 s: the two ends are sampled, the key in between is
    // not (the rule node animation follows: linear motion between the ends).
    const Scene across = load_scene_file(path, shutter(0.5f, 1.5f));
    const glm::vec2 w_open = animated_weights(0.5f), w_close = animated_weights(1.5f);
    check_positions(across.position_open, 0, morphed_triangle(w_open.x, w_open.y));
    check_positions(across.position_close, 0, morphed_triangle(w_close.x, w_close.y));
    // Before the first and after the last key the end weights hold.
    const Scene after = load_scene_file(path, shutter(3.0f, 4.0f));
    check_positions(after.position_open, 0, morphed_triangle(1.0f, 1.0f));
    check_positions(after.position_close, 0, morphed_triangle(1.0f, 1.0f));
    // No animation: the mesh's weights (0.5, 0), static.
    GltfOptions still;
    still.animation_index = -1;
    const Scene unanimated = load_scene_file(path, still);
    check_positions(unanimated.position_open, 0, morphed_triangle(0.5f, 0.0f));
    CHECK(unanimated.position_close == unanimated.position_open);

    // node.weights over mesh.weights; the second node uses the mesh's.
    const Scene defaults = load_scene_file(kDataDir + "morph_defaults.gltf");
    check_positions(defaults.position_open, 0, morphed_triangle(0.0f, 1.0f));
    check_positions(defaults.position_open, 3, morphed_triangle(0.5f, 0.0f, glm::vec3(5, 0, 0)));
}

TEST_CASE("glTF morph targets: morph, then skin, then node animation, in glTF's order") {
    // Without a skin: morph, then the node's animated TRS (scale 2, then +5 x per second).
    const Scene node = load_scene_file(kDataDir + "morph_node_animated.gltf", shutter(0.25f, 0.75f));
    for (const float t : {0.25f, 0.75f}) {
        const glm::vec2 w = animated_weights(t);
        std::vector<glm::vec3> expected = morphed_triangle(w.x, w.y);
        for (glm::vec3& p : expected) p = 2.0f * p + glm::vec3(5.0f * t, 0, 0);
        check_positions(t < 0.5f ? node.position_open : node.position_close, 0, expected, 1e-5f);
    }

    // The target moves every vertex +1 x (weight 1); the only joint turns 90
    // degrees about z and moves +1 y over the shutter [0, 1]. Morph first:
    // the offset turns with the joint; the skinned node's own +50 x is ignored.
    const Scene scene = load_scene_file(kDataDir + "morph_skinned.gltf", shutter(0.0f, 1.0f));
    check_positions(scene.position_open, 0, {{1, 0, 0}, {2, 0, 0}, {1, 1, 0}}, 1e-5f);
    check_positions(scene.position_close, 0, {{0, 2, 0}, {0, 3, 0}, {-1, 2, 0}}, 1e-5f);
}

namespace {

// SparseMorphCube/singleBlendshapeCube_sparse.glb read without the loader:
// the GLB's JSON and binary chunks, POSITION and the sparse target decoded
// here, so the expected positions do not come from the code under test.
struct Glb {
    nlohmann::json json;
    std::vector<unsigned char> bin;
};

std::uint32_t u32_at(const std::vector<unsigned char>& bytes, std::size_t offset) {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes.data() + offset, sizeof v);
    return v;
}

Glb read_glb(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    REQUIRE(bytes.size() > 28);
    const std::uint32_t json_length = u32_at(bytes, 12);
    Glb glb;
    glb.json = nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + json_length);
    const std::size_t bin_start = 20 + json_length + 8;
    glb.bin.assign(bytes.begin() + static_cast<std::ptrdiff_t>(bin_start),
                   bytes.begin() + static_cast<std::ptrdiff_t>(bin_start + u32_at(bytes, 20 + json_length)));
    return glb;
}

void write_glb(const std::string& path, const Glb& glb) {
    std::string text = glb.json.dump();
    text.append((4 - text.size() % 4) % 4, ' ');
    std::vector<unsigned char> bin = glb.bin;
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    std::vector<unsigned char> out;
    const auto put = [&](std::uint32_t v) {
        const auto* b = reinterpret_cast<const unsigned char*>(&v);
        out.insert(out.end(), b, b + 4);
    };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    put(2);
    put(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    put(static_cast<std::uint32_t>(text.size()));
    put(0x4E4F534Au);
    out.insert(out.end(), text.begin(), text.end());
    put(static_cast<std::uint32_t>(bin.size()));
    put(0x004E4942u);
    out.insert(out.end(), bin.begin(), bin.end());
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(out.data()),
                                                static_cast<std::streamsize>(out.size()));
}

float float_at(const std::vector<unsigned char>& bin, std::size_t offset) {
    float v = 0.0f;
    std::memcpy(&v, bin.data() + offset, sizeof v);
    return v;
}

std::size_t view_offset(const nlohmann::json& json, std::size_t view) {
    return json["bufferViews"][view].value("byteOffset", std::size_t{0});
}

// Base positions plus weight * the sparse target, decoded by hand (float
// VEC3 tightly packed; uint16 sparse indices; float VEC3 sparse values).
std::vector<glm::vec3> expected_cube(const Glb& glb, float weight) {
    const nlohmann::json& json = glb.json;
    const nlohmann::json& primitive = json["meshes"][0]["primitives"][0];
    const nlohmann::json& base = json["accessors"][primitive["attributes"]["POSITION"].get<std::size_t>()];
    const std::size_t count = base["count"];
    const std::size_t base_offset = view_offset(json, base["bufferView"]) + base.value("byteOffset", std::size_t{0});
    std::vector<glm::vec3> positions(count);
    for (std::size_t v = 0; v < count; ++v) {
        for (std::size_t c = 0; c < 3; ++c) positions[v][static_cast<int>(c)] = float_at(glb.bin, base_offset + 12 * v + 4 * c);
    }
    const nlohmann::json& sparse = json["accessors"][primitive["targets"][0]["POSITION"].get<std::size_t>()]["sparse"];
    REQUIRE(sparse["indices"]["componentType"] == 5123);
    const std::size_t indices = view_offset(json, sparse["indices"]["bufferView"]);
    const std::size_t values = view_offset(json, sparse["values"]["bufferView"]);
    for (std::size_t k = 0; k < sparse["count"].get<std::size_t>(); ++k) {
        std::uint16_t index = 0;
        std::memcpy(&index, glb.bin.data() + indices + 2 * k, 2);
        for (std::size_t c = 0; c < 3; ++c) {
            positions[index][static_cast<int>(c)] += weight * float_at(glb.bin, values + 12 * k + 4 * c);
        }
    }
    return positions;
}

}  // namespace

TEST_CASE("glTF morph targets: Khronos SparseMorphCube (a sparse target), as the file's weights say") {
    const std::string path =
        blurcull::testing::khronos_test_dir() + "/SparseMorphCube/singleBlendshapeCube_sparse.glb";
    Glb glb = read_glb(path);
    // The file's own weights: mesh.weights and an animation of one key; a
    // single key holds at every time, so the cube is morphed but static.
    const nlohmann::json& sampler = glb.json["animations"][0]["samplers"][0];
    const nlohmann::json& output = glb.json["accessors"][sampler["output"].get<std::size_t>()];
    REQUIRE(glb.json["accessors"][sampler["input"].get<std::size_t>()]["count"] == 1);
    const float file_weight = float_at(glb.bin, view_offset(glb.json, output["bufferView"]));
    const Outcome outcome = load(path, shutter(0.0f, 0.5f));
    CHECK(outcome.error.empty());
    CHECK(outcome.warnings.empty());
    CHECK(outcome.triangles == 12);
    const Scene scene = load_scene_file(path, shutter(0.0f, 0.5f));
    check_positions(scene.position_open, 0, expected_cube(glb, file_weight));
    check_positions(scene.position_close, 0, expected_cube(glb, file_weight));

    // The same file with the weight animated 0 -> 1 over 1 s (two keys
    // appended to its binary chunk): the sparse target becomes motion.
    const std::size_t keys_offset = (glb.bin.size() + 3) / 4 * 4;
    glb.bin.resize(keys_offset + 16, 0);
    const float keys[4] = {0.0f, 1.0f, 0.0f, 1.0f};  // times 0, 1; weights 0, 1
    std::memcpy(glb.bin.data() + keys_offset, keys, sizeof keys);
    nlohmann::json& json = glb.json;
    json["buffers"][0]["byteLength"] = glb.bin.size();
    const std::size_t views = json["bufferViews"].size(), accessors = json["accessors"].size();
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", keys_offset}, {"byteLength", 8}});
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", keys_offset + 8}, {"byteLength", 8}});
    json["accessors"].push_back({{"bufferView", views}, {"componentType", 5126}, {"count", 2}, {"type", "SCALAR"}});
    json["accessors"].push_back({{"bufferView", views + 1}, {"componentType", 5126}, {"count", 2}, {"type", "SCALAR"}});
    json["animations"][0]["samplers"][0]["input"] = accessors;
    json["animations"][0]["samplers"][0]["output"] = accessors + 1;
    const std::string animated = (std::filesystem::temp_directory_path() /
                                  ("blurcull_sparse_morph_" + std::to_string(::getpid()) + ".glb")).string();
    write_glb(animated, glb);
    const Scene moving = load_scene_file(animated, shutter(0.25f, 0.5f));
    std::filesystem::remove(animated);
    const std::vector<glm::vec3> at_open = expected_cube(glb, 0.25f), at_close = expected_cube(glb, 0.5f);
    check_positions(moving.position_open, 0, at_open);
    check_positions(moving.position_close, 0, at_close);
    std::size_t moved = 0;
    for (std::size_t v = 0; v < at_open.size(); ++v) moved += moving.position_open[v] != moving.position_close[v];
    // It renders with that blur: the moving cube's image is neither the
    // cube held at shutter open nor at close (same camera, same samples).
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.spp = 16;
    settings.progress = false;
    Scene held_open = moving, held_close = moving;
    held_open.position_close = held_open.position_open;
    held_close.position_open = held_close.position_close;
    held_open.validated = held_close.validated = false;
    const Image blurred = render_cpu(moving, settings).image;
    CHECK(blurred.pixels != render_cpu(held_open, settings).image.pixels);
    CHECK(blurred.pixels != render_cpu(held_close, settings).image.pixels);
    const std::size_t target = glb.json["meshes"][0]["primitives"][0]["targets"][0]["POSITION"];
    CHECK(moved == glb.json["accessors"][target]["sparse"]["count"].get<std::size_t>());
}
