// The robustness corpus of malformed and extreme glTF files
// (tests/data/gltf/, written by make_test_files.py; docs/robustness.md lists
// each with its message): every file either loads with a documented warning
// (handed to the caller, never printed) or throws one SceneError line naming
// the file and the problem.
#include "scene/gltf/gltf_loader.hpp"

#include <doctest/doctest.h>

#include <iostream>
#include <sstream>
#include <string>

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

Outcome load(const std::string& path) {
    Outcome outcome;
    std::ostringstream captured;
    std::streambuf* saved = std::cerr.rdbuf(captured.rdbuf());
    const WarningSink collect = [&](const std::string& line) { outcome.warnings += line + "\n"; };
    try {
        outcome.triangles = load_gltf_scene(path, GltfOptions{}, collect).triangles.size();
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
