// The scene library: the four procedural scenes (size, determinism, blur
// class, blur_scale), the glTF loader on the Khronos sample models and on
// small hand-written files, and its one-line errors for malformed input; the
// one rule for scene file names and load_scene's settings, validated once.
#include "scene/builtin_scenes.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_checks.hpp"
#include "scene/scene_name.hpp"
#include "test_data_dirs.hpp"

#include <doctest/doctest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

using namespace blurcull::frontend;

namespace {

const std::string kDataDir = std::string(BLURCULL_SOURCE_DIR) + "/tests/data/gltf/";
// The Khronos sample models the tests read (tests/data/khronos/README.md).
const std::string kKhronosDir = blurcull::testing::khronos_test_dir() + "/";

bool same_scene(const Scene& a, const Scene& b) {
    if (a.position_open != b.position_open || a.position_close != b.position_close ||
        a.triangles != b.triangles || a.triangle_material != b.triangle_material ||
        a.materials.size() != b.materials.size()) {
        return false;
    }
    for (std::size_t i = 0; i < a.materials.size(); ++i) {
        if (a.materials[i].base_color != b.materials[i].base_color || a.materials[i].name != b.materials[i].name) {
            return false;
        }
    }
    return a.camera.view_open == b.camera.view_open && a.camera.view_close == b.camera.view_close &&
           a.camera.yfov == b.camera.yfov && a.camera.znear == b.camera.znear &&
           a.camera.lens_radius == b.camera.lens_radius && a.camera.focus_distance == b.camera.focus_distance &&
           a.light_direction == b.light_direction && a.background == b.background;
}

std::uint32_t material_index(const Scene& scene, const std::string& name) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (scene.materials[i].name == name) return static_cast<std::uint32_t>(i);
    }
    FAIL("scene '" << scene.name << "' has no material '" << name << "'");
    return 0;
}

// View depths of every vertex used by triangles of one material, at open.
std::vector<float> material_depths(const Scene& scene, const std::string& name) {
    const std::uint32_t material = material_index(scene, name);
    std::vector<float> depths;
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        if (scene.triangle_material[t] != material) continue;
        for (int c = 0; c < 3; ++c) {
            const glm::vec3& p = scene.position_open[scene.triangles[t][c]];
            depths.push_back(-(scene.camera.view_open * glm::vec4(p, 1.0f)).z);
        }
    }
    return depths;
}

// Runs `load` and returns the SceneError message ("" if it loaded). Any other
// exception type fails the test.
template <typename Load>
std::string error_of(Load load) {
    try {
        load();
    } catch (const SceneError& error) {
        return error.what();
    } catch (const std::exception& error) {
        FAIL("not a SceneError: " << error.what());
    }
    return "";
}

GltfOptions shutter(float open, float close) {
    GltfOptions options;
    options.shutter_open = open;
    options.shutter_close = close;
    return options;
}

std::vector<char> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

// ---------------------------------------------------------------------------
// Built-in scenes

TEST_CASE("built-in scenes: the catalogue lists every scene once, its description's triangle count true") {
    const std::vector<BuiltinSceneInfo> catalogue = builtin_scene_catalogue();
    std::vector<std::string> expected = builtin_scene_names();
    for (const std::string& name : secondary_scene_names()) expected.push_back(name);
    for (const std::string& name : large_scene_names()) expected.push_back(name);
    std::vector<std::string> names;
    for (const BuiltinSceneInfo& scene : catalogue) {
        CAPTURE(scene.name);
        names.push_back(scene.name);
        if (scene.name == "forest-10m") continue;  // its own test below builds it once
        CHECK(scene.description.find('\n') == std::string::npos);
        // "(... 54k triangles)": within 1k (rounding) of the scene's count.
        const std::size_t at = scene.description.find("k triangles)");
        REQUIRE(at != std::string::npos);
        std::size_t digits = at;
        while (digits > 0 && std::isdigit(static_cast<unsigned char>(scene.description[digits - 1]))) --digits;
        REQUIRE(digits < at);
        const double thousands = std::stod(scene.description.substr(digits, at - digits));
        const auto triangles = static_cast<double>(make_builtin_scene(scene.name, SceneOptions{}).triangles.size());
        CHECK(std::abs(triangles / 1000.0 - thousands) <= 1.0);
    }
    CHECK(names == expected);
    CHECK(expected.size() == 9);
}

TEST_CASE("built-in scenes: forest-10m is the forest's walk at 10 million triangles") {
    const Scene big = make_builtin_scene("forest-10m", SceneOptions{});
    const Scene forest = make_builtin_scene("forest", SceneOptions{});
    CHECK(big.name == "forest-10m");
    CHECK(big.triangles.size() >= 10'000'000);
    CHECK(big.triangles.size() <= 10'001'000);  // the catalogue's "10000k", a tree past the target at most
    std::string description;
    for (const BuiltinSceneInfo& scene : builtin_scene_catalogue())
        if (scene.name == "forest-10m") description = scene.description;
    CHECK(description.find("(10000k triangles)") != std::string::npos);
    const std::vector<std::string> iterated = builtin_scene_names();  // what the tests and benchmarks walk
    CHECK(std::find(iterated.begin(), iterated.end(), "forest-10m") == iterated.end());
    // The same camera, blur and materials as the forest: every triangle moves on screen.
    CHECK(big.camera.view_open == forest.camera.view_open);
    CHECK(big.camera.view_close == forest.camera.view_close);
    CHECK(big.camera.lens_radius == forest.camera.lens_radius);
    REQUIRE(big.materials.size() == forest.materials.size());
    for (std::size_t m = 0; m < big.materials.size(); ++m) CHECK(big.materials[m].name == forest.materials[m].name);
    const SceneStats stats = describe(big);
    CHECK(stats.camera_motion);
    CHECK_FALSE(stats.object_motion);
    CHECK_NOTHROW(validate_scene(big));
}

TEST_CASE("built-in scenes: names, sizes near the thesis workloads, determinism, validity") {
    const std::vector<std::string> names = builtin_scene_names();
    REQUIRE(names == std::vector<std::string>{"hand", "car", "dragonfly", "forest"});
    const std::size_t targets[] = {15000, 54000, 85000, 170000};
    for (std::size_t i = 0; i < names.size(); ++i) {
        CAPTURE(names[i]);
        const Scene first = make_builtin_scene(names[i], SceneOptions{});
        const Scene second = make_builtin_scene(names[i], SceneOptions{});
        CHECK(same_scene(first, second));
        CHECK(first.name == names[i]);
        const auto triangles = static_cast<double>(first.triangles.size());
        CHECK(triangles >= 0.9 * static_cast<double>(targets[i]));
        CHECK(triangles <= 1.1 * static_cast<double>(targets[i]));
        CHECK(first.materials.size() >= 3);
        CHECK_NOTHROW(validate_scene(first));
        // Readable images: materials differ in colour.
        CHECK(first.materials[0].base_color != first.materials[1].base_color);
    }
}

TEST_CASE("built-in scenes: each has its thesis blur class") {
    const SceneStats hand = describe(make_builtin_scene("hand", SceneOptions{}));
    CHECK_FALSE(hand.object_motion);
    CHECK_FALSE(hand.camera_motion);
    CHECK(hand.lens_radius > 0.0f);

    const SceneStats car = describe(make_builtin_scene("car", SceneOptions{}));
    CHECK(car.object_motion);
    CHECK_FALSE(car.camera_motion);
    CHECK(car.lens_radius == 0.0f);

    const SceneStats dragonfly = describe(make_builtin_scene("dragonfly", SceneOptions{}));
    CHECK_FALSE(dragonfly.object_motion);
    CHECK(dragonfly.camera_motion);
    CHECK(dragonfly.camera_displacement > 0.0f);
    CHECK(dragonfly.camera_rotation > 0.0f);
    CHECK(dragonfly.lens_radius == 0.0f);

    const SceneStats forest = describe(make_builtin_scene("forest", SceneOptions{}));
    CHECK_FALSE(forest.object_motion);
    CHECK(forest.camera_motion);
    CHECK(forest.lens_radius > 0.0f);
}

TEST_CASE("make_mostly_static: lens closed, camera still, one triangle in ten moving") {
    for (const std::string& name : {std::string("forest"), std::string("car"), std::string("hand")}) {
        const Scene source = make_builtin_scene(name, SceneOptions{});
        const Scene scene = make_mostly_static(source, 10);
        INFO(name);
        validate_scene(scene);
        CHECK(scene.camera.lens_radius == 0.0f);
        CHECK(scene.camera.view_close == scene.camera.view_open);
        REQUIRE(scene.triangles.size() == source.triangles.size());
        std::size_t moving = 0, moving_slots = 0;
        bool still_ones_still = true, open_kept = true;
        for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
            bool moves = false;
            for (int i = 0; i < 3; ++i) {
                const std::uint32_t v = scene.triangles[t][i];
                open_kept = open_kept && scene.position_open[v] == source.position_open[source.triangles[t][i]];
                moves = moves || scene.position_open[v] != scene.position_close[v];
            }
            if (t % 10 == 0) {
                ++moving_slots;
                moving += moves ? 1 : 0;
            } else if (moves) {
                still_ones_still = false;
            }
        }
        CHECK(still_ones_still);
        CHECK(open_kept);
        // The forest moves by its camera, the car by its own motion, the hand not at all.
        if (name == "hand") {
            CHECK(moving == 0);
        } else {
            CHECK(moving >= moving_slots * 9 / 10);
        }
    }
    CHECK_THROWS_AS(make_mostly_static(make_builtin_scene("car", SceneOptions{}), 0), SceneError);
}

TEST_CASE("built-in scenes: blur_scale 2 doubles motion and lens, 0 removes all blur") {
    for (const std::string& name : builtin_scene_names()) {
        CAPTURE(name);
        const Scene base_scene = make_builtin_scene(name, SceneOptions{1.0f, 4.0f / 3.0f});
        const Scene double_scene = make_builtin_scene(name, SceneOptions{2.0f, 4.0f / 3.0f});
        const SceneStats base = describe(base_scene);
        const SceneStats twice = describe(double_scene);
        CHECK(twice.lens_radius == doctest::Approx(2.0f * base.lens_radius));
        CHECK(twice.max_vertex_displacement == doctest::Approx(2.0f * base.max_vertex_displacement).epsilon(1e-4));
        CHECK(twice.camera_displacement == doctest::Approx(2.0f * base.camera_displacement).epsilon(1e-3));
        CHECK(twice.camera_rotation == doctest::Approx(2.0f * base.camera_rotation).epsilon(1e-3));
        // Same geometry, same framing: only the blur changes.
        CHECK(base_scene.triangles == double_scene.triangles);
        CHECK(base_scene.camera.yfov == double_scene.camera.yfov);
        CHECK(base_scene.camera.view_open == double_scene.camera.view_open);

        const SceneStats none = describe(make_builtin_scene(name, SceneOptions{0.0f, 4.0f / 3.0f}));
        CHECK_FALSE(none.object_motion);
        CHECK_FALSE(none.camera_motion);
        CHECK(none.lens_radius == 0.0f);
    }
}

TEST_CASE("built-in scenes: hand straddles the focus plane") {
    const Scene hand = make_builtin_scene("hand", SceneOptions{});
    const std::vector<float> depths = material_depths(hand, "skin");
    REQUIRE(!depths.empty());
    std::size_t nearer = 0;
    std::size_t farther = 0;
    for (float depth : depths) {
        if (depth < 0.95f * hand.camera.focus_distance) ++nearer;
        if (depth > 1.05f * hand.camera.focus_distance) ++farther;
    }
    CHECK(nearer > depths.size() / 10);
    CHECK(farther > depths.size() / 20);
}

TEST_CASE("built-in scenes: the car moves sideways by a few percent of the image width") {
    const Scene car = make_builtin_scene("car", SceneOptions{});
    const float k = 1.0f / std::tan(0.5f * car.camera.yfov);
    const float aspect = 4.0f / 3.0f;
    const std::uint32_t paint = material_index(car, "paint");
    std::size_t moving = 0;
    std::size_t static_count = 0;
    for (std::size_t t = 0; t < car.triangles.size(); ++t) {
        const std::uint32_t v = car.triangles[t][0];
        const bool moves = car.position_open[v] != car.position_close[v];
        if (car.triangle_material[t] == paint) {
            REQUIRE(moves);
            ++moving;
            const glm::vec4 a = car.camera.view_open * glm::vec4(car.position_open[v], 1.0f);
            const glm::vec4 b = car.camera.view_open * glm::vec4(car.position_close[v], 1.0f);
            // NDC x spans 2 units of image width.
            const float screen_fraction = std::abs(k / aspect * (b.x / -b.z - a.x / -a.z)) / 2.0f;
            CHECK(screen_fraction > 0.02f);
            CHECK(screen_fraction < 0.15f);
            CHECK(car.position_close[v].y == car.position_open[v].y);
        } else if (!moves) {
            ++static_count;
        }
    }
    CHECK(moving > 1000);
    CHECK(static_count > 1000);  // road and buildings stay put
}

TEST_CASE("built-in scenes: forest ground runs behind the camera (near-plane crossings)") {
    const Scene forest = make_builtin_scene("forest", SceneOptions{});
    const std::vector<float> ground = material_depths(forest, "grass");
    bool behind = false;
    bool in_front = false;
    for (float depth : ground) {
        behind = behind || depth < 0.0f;
        in_front = in_front || depth > 50.0f;
    }
    CHECK(behind);
    CHECK(in_front);
    // Trees from near to far: foliage at many depths.
    const std::vector<float> pines = material_depths(forest, "pine");
    float nearest = 1e9f;
    float farthest = 0.0f;
    for (float depth : pines) {
        if (depth > 0.0f) nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    CHECK(nearest < 10.0f);
    CHECK(farthest > 80.0f);
    CHECK(forest.camera.focus_distance > nearest);
    CHECK(forest.camera.focus_distance < farthest);
}

TEST_CASE("built-in scenes: the camera frames the subject for the aspect") {
    const Scene wide = make_builtin_scene("car", SceneOptions{1.0f, 2.5f});
    const Scene narrow = make_builtin_scene("car", SceneOptions{1.0f, 0.6f});
    // A narrow image needs a taller field of view to fit the car's length.
    CHECK(narrow.camera.yfov > wide.camera.yfov);
    const Scene forest_wide = make_builtin_scene("forest", SceneOptions{1.0f, 2.0f});
    CHECK(forest_wide.camera.yfov < make_builtin_scene("forest", SceneOptions{}).camera.yfov);
}

TEST_CASE("built-in scenes: bad names and options are one-line SceneErrors") {
    CHECK(error_of([] { make_builtin_scene("x", SceneOptions{}); }) ==
          "unknown scene 'x' (known: hand, car, dragonfly, forest, mirror-sphere, water, curved-mirror, mirror-motion, forest-10m)");
    CHECK(error_of([] { make_builtin_scene("hand", SceneOptions{-1.0f, 1.0f}); }).find("blur scale") !=
          std::string::npos);
    CHECK(error_of([] { make_builtin_scene("hand", SceneOptions{1.0f, 0.0f}); }).find("aspect") !=
          std::string::npos);
    CHECK(error_of([] { make_builtin_scene("hand", SceneOptions{NAN, 1.0f}); }).find("blur scale") !=
          std::string::npos);
}

// ---------------------------------------------------------------------------
// validate_scene / describe

TEST_CASE("validate_scene rejects inconsistent scenes, describe summarises") {
    Scene scene;
    scene.name = "tiny";
    scene.position_open = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    scene.position_close = {{0, 0, 0}, {1, 0, 0}, {0, 1, 3}};
    scene.triangles = {{0, 1, 2}};
    scene.triangle_material = {0};
    scene.materials = {Material{}};
    CHECK_NOTHROW(validate_scene(scene));
    const SceneStats stats = describe(scene);
    CHECK(stats.triangles == 1);
    CHECK(stats.vertices == 3);
    CHECK(stats.object_motion);
    CHECK(stats.max_vertex_displacement == doctest::Approx(3.0f));
    CHECK_FALSE(stats.camera_motion);
    CHECK(stats.bounds_max == glm::vec3(1, 1, 3));

    Scene bad = scene;
    bad.triangles[0][2] = 3;
    CHECK(error_of([&] { validate_scene(bad); }).find("scene 'tiny': triangle 0 uses vertex 3") == 0);
    bad = scene;
    bad.position_close.pop_back();
    CHECK(error_of([&] { validate_scene(bad); }).find("close positions") != std::string::npos);
    bad = scene;
    bad.triangle_material[0] = 1;
    CHECK(error_of([&] { validate_scene(bad); }).find("material 1") != std::string::npos);
    bad = scene;
    bad.position_open[1].x = NAN;
    CHECK(error_of([&] { validate_scene(bad); }).find("non-finite") != std::string::npos);
    bad = scene;
    bad.camera.yfov = 0.0f;
    CHECK(error_of([&] { validate_scene(bad); }).find("yfov") != std::string::npos);
    bad = scene;
    bad.camera.znear = -1.0f;
    CHECK(error_of([&] { validate_scene(bad); }).find("znear") != std::string::npos);
}

// ---------------------------------------------------------------------------
// glTF: Khronos sample models

TEST_CASE("glTF: the Khronos sample models load with their triangle counts") {
    const std::pair<const char*, std::size_t> models[] = {
        {"AnimatedTriangle.gltf", 1}, {"BoxAnimated.gltf", 254}, {"RiggedSimple.gltf", 188},
        {"Cameras.gltf", 2}, {"RiggedFigure.gltf", 256}};
    for (const auto& model : models) {
        CAPTURE(model.first);
        const Scene scene = load_gltf_scene(kKhronosDir + model.first, GltfOptions{});
        CHECK(scene.triangles.size() == model.second);
        CHECK_NOTHROW(validate_scene(scene));
    }
}

// The team's scene folder (../shared/scenes/khronos, optional; a clone
// outside the team has none): every model in it, whatever it holds.
TEST_CASE("glTF: every model of the shared scene folder loads and validates, when there is one") {
    const std::filesystem::path folder = blurcull::testing::shared_dir() + "/scenes/khronos";
    if (!std::filesystem::is_directory(folder)) {
        MESSAGE("skipped: no shared scene folder " << folder.string()
                                                   << " (optional; BLURCULL_SHARED_DIR names another)");
        return;
    }
    std::size_t models = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
        const std::string extension = entry.path().extension().string();
        if (extension != ".gltf" && extension != ".glb") continue;
        CAPTURE(entry.path().string());
        Scene scene;
        CHECK_NOTHROW(scene = load_gltf_scene(entry.path().string(), GltfOptions{}));
        CHECK(!scene.triangles.empty());
        CHECK_NOTHROW(validate_scene(scene));
        ++models;
    }
    MESSAGE(models << " models in " << folder.string());
    CHECK(models > 0);
}

TEST_CASE("glTF: AnimatedTriangle moves inside its animation, not for a zero-length shutter") {
    const std::string path = kKhronosDir + "AnimatedTriangle.gltf";
    const SceneStats moving = describe(load_gltf_scene(path, shutter(0.1f, 0.3f)));
    CHECK(moving.object_motion);
    // A rotation about z: z never changes, x/y do.
    const Scene scene = load_gltf_scene(path, shutter(0.1f, 0.3f));
    for (std::size_t v = 0; v < scene.position_open.size(); ++v) {
        CHECK(scene.position_open[v].z == doctest::Approx(scene.position_close[v].z));
    }
    CHECK_FALSE(describe(load_gltf_scene(path, shutter(0.2f, 0.2f))).object_motion);
    GltfOptions no_blur = shutter(0.1f, 0.3f);
    no_blur.blur_scale = 0.0f;
    CHECK_FALSE(describe(load_gltf_scene(path, no_blur)).object_motion);
    GltfOptions no_animation = shutter(0.1f, 0.3f);
    no_animation.animation_index = -1;
    CHECK_FALSE(describe(load_gltf_scene(path, no_animation)).object_motion);
    GltfOptions missing = shutter(0.1f, 0.3f);
    missing.animation_index = 3;
    CHECK(error_of([&] { load_gltf_scene(path, missing); }).find("animation 3 does not exist") != std::string::npos);
    // blur_scale 2 doubles the interval: the triangle turns further.
    GltfOptions longer = shutter(0.1f, 0.2f);
    longer.blur_scale = 2.0f;
    const SceneStats doubled = describe(load_gltf_scene(path, longer));
    CHECK(doubled.max_vertex_displacement == doctest::Approx(moving.max_vertex_displacement).epsilon(1e-4));
}

TEST_CASE("glTF: Cameras.gltf uses its perspective camera, rejects the orthographic one") {
    const std::string path = kKhronosDir + "Cameras.gltf";
    const Scene scene = load_gltf_scene(path, GltfOptions{});
    CHECK(scene.camera.yfov == doctest::Approx(0.7f));
    CHECK(scene.camera.znear == doctest::Approx(0.01f));
    // The camera sits at (0.5, 0.5, 3) looking down -z.
    const glm::vec3 eye(glm::inverse(scene.camera.view_open)[3]);
    CHECK(eye.x == doctest::Approx(0.5f));
    CHECK(eye.y == doctest::Approx(0.5f));
    CHECK(eye.z == doctest::Approx(3.0f));
    GltfOptions orthographic;
    orthographic.camera_index = 1;
    const std::string message = error_of([&] { load_gltf_scene(path, orthographic); });
    CHECK(message.find(path + ": camera 1 is orthographic") == 0);
    GltfOptions missing;
    missing.camera_index = 5;
    CHECK(error_of([&] { load_gltf_scene(path, missing); }).find("camera 5 does not exist") != std::string::npos);
}

TEST_CASE("glTF: skinned vertices of RiggedSimple and RiggedFigure move") {
    const Scene simple = load_gltf_scene(kKhronosDir + "RiggedSimple.gltf", shutter(0.5f, 0.7f));
    const SceneStats stats = describe(simple);
    CHECK(stats.object_motion);
    CHECK(stats.max_vertex_displacement > 0.05f);
    // Only the part bound to the animated bone moves: some vertices stay.
    std::size_t still = 0;
    for (std::size_t v = 0; v < simple.position_open.size(); ++v) {
        if (glm::length(simple.position_close[v] - simple.position_open[v]) < 1e-4f) ++still;
    }
    CHECK(still > 0);
    CHECK(still < simple.position_open.size());
    CHECK(describe(load_gltf_scene(kKhronosDir + "RiggedFigure.gltf", shutter(0.2f, 0.6f))).object_motion);
    CHECK(describe(load_gltf_scene(kKhronosDir + "BoxAnimated.gltf", shutter(1.5f, 1.7f))).object_motion);
}

// ---------------------------------------------------------------------------
// glTF: hand-written files

TEST_CASE("glTF: small valid files (gltf, glb, modes, animation, skipped primitives)") {
    const Scene triangle = load_gltf_scene(kDataDir + "triangle.gltf", GltfOptions{});
    REQUIRE(triangle.triangles.size() == 1);
    CHECK(triangle.name == "triangle");
    CHECK(triangle.materials[triangle.triangle_material[0]].base_color == glm::vec3(0.2f, 0.4f, 0.8f));
    CHECK(triangle.position_open[triangle.triangles[0][1]] == glm::vec3(1, 0, 0));
    // No camera in the file: the automatic camera sees the whole triangle.
    for (const glm::vec3& p : triangle.position_open) {
        const glm::vec4 q = triangle.camera.view_open * glm::vec4(p, 1.0f);
        CHECK(-q.z > triangle.camera.znear);
        CHECK(std::abs(q.y / q.z) < std::tan(0.5f * triangle.camera.yfov));
    }

    const Scene binary = load_gltf_scene(kDataDir + "triangle.glb", GltfOptions{});
    CHECK(binary.position_open == triangle.position_open);
    CHECK(binary.triangles == triangle.triangles);

    // Translation 0 -> 2 in x over one second: 0.25 s .. 0.75 s moves by 1.
    const Scene animated = load_gltf_scene(kDataDir + "triangle_animated.gltf", shutter(0.25f, 0.75f));
    for (std::size_t v = 0; v < animated.position_open.size(); ++v) {
        CHECK(animated.position_close[v].x - animated.position_open[v].x == doctest::Approx(1.0f));
        CHECK(animated.position_close[v].y == animated.position_open[v].y);
    }

    // 1 indexed + 2 strip + 3 fan + 1 uint8-indexed triangles; points skipped.
    const Scene modes = load_gltf_scene(kDataDir + "modes.gltf", GltfOptions{});
    REQUIRE(modes.triangles.size() == 7);
    // Strip triangles keep one winding: both face +z like the first.
    for (std::size_t t = 1; t <= 2; ++t) {
        const glm::uvec3 tri = modes.triangles[t];
        const glm::vec3 normal = glm::cross(modes.position_open[tri[1]] - modes.position_open[tri[0]],
                                            modes.position_open[tri[2]] - modes.position_open[tri[0]]);
        CHECK(normal.z > 0.0f);
    }

    // The NaN primitive is skipped with a warning; the good one loads.
    CHECK(load_gltf_scene(kDataDir + "nan_position.gltf", GltfOptions{}).triangles.size() == 1);

    // load_scene dispatches on the extension.
    CHECK(load_scene(kDataDir + "triangle.gltf").triangles.size() == 1);
    CHECK(load_scene("hand").name == "hand");
    CHECK(error_of([] { load_scene("model.obj"); }) ==
          "model.obj: unsupported scene file type (expected .gltf or .glb)");
}

TEST_CASE("glTF: malformed files give one-line SceneErrors naming the file and the problem") {
    const std::pair<const char*, const char*> cases[] = {
        {"bad_json.gltf", "cannot parse glTF"},
        {"bad_accessor_index.gltf", "refers to accessor 7, which does not exist"},
        {"bad_accessor_past_end.gltf", "accessor 0 reads past the end of buffer view 0"},
        {"bad_buffer_view_past_end.gltf", "buffer view 1 (offset 36, length 4000) reads past the end of buffer 0"},
        {"bad_index_value.gltf", "index value 5 (at 2) is not below the vertex count 3"},
        {"bad_camera_yfov.gltf", "camera 0 has yfov 0"},
        {"bad_camera_znear.gltf", "camera 0 has znear 0"},
        {"bad_node_cycle.gltf", "node cycle"},
        {"bad_node_two_parents.gltf", "node 2 has two parents"},
        {"bad_node_depth.gltf", "levels deep (limit 1000)"},
        {"bad_keyframes_order.gltf", "keyframe times are not increasing"},
        {"bad_keyframes_nan.gltf", "keyframe time 1 is not finite"},
        {"bad_missing_buffer.gltf", "does_not_exist.bin"},
        {"bad_truncated.glb", "GLB header says"},
        {"no_such_file.gltf", "cannot open file"},
    };
    for (const auto& c : cases) {
        const std::string path = kDataDir + c.first;
        CAPTURE(path);
        const std::string message = error_of([&] { load_gltf_scene(path, GltfOptions{}); });
        CHECK(message.rfind(path + ": ", 0) == 0);
        CHECK(message.find(c.second) != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}

TEST_CASE("glTF: bad options are SceneErrors") {
    const std::string path = kDataDir + "triangle.gltf";
    CHECK(error_of([&] { load_gltf_scene(path, shutter(1.0f, 0.0f)); }).find("shutter interval") != std::string::npos);
    GltfOptions options;
    options.aspect = -1.0f;
    CHECK(error_of([&] { load_gltf_scene(path, options); }).find("aspect") != std::string::npos);
    options = GltfOptions{};
    options.lens_radius = 0.1f;
    options.focus_distance = 4.0f;
    const Scene scene = load_gltf_scene(path, options);
    CHECK(scene.camera.lens_radius == 0.1f);
    CHECK(scene.camera.focus_distance == 4.0f);
}

TEST_CASE("glTF: truncated and corrupted files never crash") {
    const std::string scratch =
        (std::filesystem::temp_directory_path() / ("blurcull_scenes_fuzz_" + std::to_string(::getpid()))).string();
    std::size_t failures = 0;
    std::size_t loads = 0;
    for (const char* name : {"triangle.gltf", "triangle.glb", "triangle_animated.gltf"}) {
        const std::vector<char> original = read_bytes(kDataDir + name);
        REQUIRE(!original.empty());
        const std::string target = scratch + (std::string(name).find(".glb") != std::string::npos ? ".glb" : ".gltf");
        auto attempt = [&](const std::vector<char>& bytes) {
            write_bytes(target, bytes);
            const std::string message = error_of([&] { load_gltf_scene(target, GltfOptions{}); });
            if (message.empty()) {
                ++loads;
            } else {
                ++failures;
                CHECK(message.rfind(target + ": ", 0) == 0);
            }
        };
        for (std::size_t length = 0; length < original.size(); length += 11) {
            attempt(std::vector<char>(original.begin(), original.begin() + static_cast<std::ptrdiff_t>(length)));
        }
        for (std::size_t at = 0; at < original.size(); at += 6) {
            for (char replacement : {'9', '-', '"', '}', '\0'}) {
                std::vector<char> bytes = original;
                bytes[at] = replacement;
                attempt(bytes);
            }
        }
        std::filesystem::remove(target);
    }
    CHECK(failures > 0);
    CHECK(loads > 0);
}

// ---------------------------------------------------------------------------
// Scene names and load_scene

TEST_CASE("scene names: one rule for glTF files, other files and built-in names") {
    CHECK(scene_file_type("a.gltf") == SceneFileType::gltf);
    CHECK(scene_file_type("scenes/A.GLTF") == SceneFileType::gltf);
    CHECK(scene_file_type("a.glb") == SceneFileType::glb);
    CHECK(scene_file_type("dir/Model.GlB") == SceneFileType::glb);
    CHECK(scene_file_type("dir/.glb") == SceneFileType::glb);
    CHECK(scene_file_type("model.obj") == SceneFileType::unsupported);
    CHECK(scene_file_type("hand.") == SceneFileType::unsupported);
    CHECK(scene_file_type("hand") == SceneFileType::none);
    CHECK(scene_file_type("dir.v2/hand") == SceneFileType::none);
    CHECK(scene_file_type("x.gltf/") == SceneFileType::none);
    CHECK(is_gltf_file("A.GLB"));
    CHECK(is_gltf_file("a.gltf"));
    CHECK_FALSE(is_gltf_file("a.obj"));
    CHECK_FALSE(is_gltf_file("forest"));

    CHECK(stem("scenes/a.gltf") == "a");
    CHECK(stem("a.b.GLB") == "a.b");
    CHECK(stem("hand") == "hand");
    CHECK(stem("dir.v2/hand") == "hand");
    CHECK(stem("dir/.glb") == ".glb");
}

TEST_CASE("load_scene: upper-case extensions load the file; other extensions are refused") {
    const std::string scratch =
        (std::filesystem::temp_directory_path() / ("blurcull_scenes_case_" + std::to_string(::getpid()))).string();
    std::filesystem::create_directories(scratch);
    for (const char* name : {"triangle.gltf", "triangle.glb"}) {
        const std::string upper = scratch + "/" + (std::string(name).find(".glb") != std::string::npos ? "TRIANGLE.GLB"
                                                                                                      : "TRIANGLE.GLTF");
        write_bytes(upper, read_bytes(kDataDir + name));
        CAPTURE(upper);
        const Scene scene = load_scene(upper);
        CHECK(scene.triangles.size() == 1);
        CHECK(scene.name == "TRIANGLE");
        CHECK(same_scene(scene, load_gltf_scene(kDataDir + name, GltfOptions{})));
    }
    std::filesystem::remove_all(scratch);
    CHECK(error_of([] { load_scene("scenes/car.OBJ"); }) ==
          "scenes/car.OBJ: unsupported scene file type (expected .gltf or .glb)");
    CHECK(error_of([] { load_scene("nowhere"); }) ==
          "unknown scene 'nowhere' (known: hand, car, dragonfly, forest, mirror-sphere, water, curved-mirror, mirror-motion, forest-10m)");
}

TEST_CASE("load_scene: settings over the scene's own, validated once at the end") {
    // No settings: exactly the scene the makers give.
    CHECK(same_scene(load_scene("hand"), make_builtin_scene("hand", SceneOptions{})));
    CHECK(same_scene(load_scene(kDataDir + "triangle.gltf"), load_gltf_scene(kDataDir + "triangle.gltf", GltfOptions{})));

    SceneSettings settings;
    settings.blur_scale = 2.0;
    settings.lens_radius = 0.05;
    settings.focus = 3.0;
    const Scene car = load_scene("car", settings);
    CHECK(car.camera.lens_radius == static_cast<float>(0.05 * 2.0));
    CHECK(car.camera.focus_distance == 3.0f);
    CHECK(describe(car).max_vertex_displacement ==
          doctest::Approx(2.0f * describe(load_scene("car")).max_vertex_displacement).epsilon(1e-4));

    settings = SceneSettings{};
    settings.fstop = 2.8;
    const Scene hand = load_scene("hand", settings);
    CHECK(hand.camera.lens_radius == lens_radius_for_fstop(hand.camera.yfov, 2.8));
    CHECK(lens_radius_for_fstop(2.0f * std::atan(0.5f), 2.0) == doctest::Approx(0.006f));

    // A built-in scene's shutter re-samples its motion: a zero-length one stands still.
    settings = SceneSettings{};
    settings.has_shutter = true;
    settings.shutter_open = 0.5f;
    settings.shutter_close = 0.5f;
    CHECK_FALSE(describe(load_scene("car", settings)).object_motion);
    CHECK_FALSE(describe(load_scene("forest", settings)).camera_motion);
    // A shutter that throws the car to infinity fails the one validation.
    settings.shutter_open = 0.0f;
    settings.shutter_close = 1e38f;
    CHECK(error_of([&] { load_scene("car", settings); }).find("scene 'car': vertex ") == 0);

    // glTF: the shutter is in animation seconds; warnings go to the sink only.
    settings = SceneSettings{};
    settings.has_shutter = true;
    settings.shutter_open = 0.1f;
    settings.shutter_close = 0.3f;
    CHECK(same_scene(load_scene(kKhronosDir + "AnimatedTriangle.gltf", settings),
                     load_gltf_scene(kKhronosDir + "AnimatedTriangle.gltf", shutter(0.1f, 0.3f))));
    std::vector<std::string> warnings;
    const Scene modes = load_scene(kDataDir + "modes.gltf", SceneSettings{},
                                   [&](const std::string& line) { warnings.push_back(line); });
    CHECK(modes.triangles.size() == 7);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0] == kDataDir + "modes.gltf: warning: points primitives are skipped");
}

TEST_CASE("glTF: warnings reach the sink in order, before the error of the same load") {
    std::vector<std::string> lines;
    const std::string path = kDataDir + "bad_lines_only.gltf";
    const std::string message =
        error_of([&] { load_gltf_scene(path, GltfOptions{}, [&](const std::string& line) { lines.push_back(line); }); });
    CHECK(message == path + ": no triangles to render");
    REQUIRE(lines.size() == 1);
    CHECK(lines[0] == path + ": warning: line primitives are skipped");
}

TEST_CASE("validated once: the makers mark their scenes, require_valid_scene checks only the others") {
    const std::string triangle = kDataDir + "triangle.gltf";
    CHECK(make_builtin_scene("hand", SceneOptions{}).validated);
    CHECK(load_gltf_scene(triangle, GltfOptions{}).validated);
    CHECK(load_scene("car").validated);
    CHECK(load_scene(triangle).validated);
    CHECK(make_mostly_static(make_builtin_scene("car", SceneOptions{}), 10).validated);
    CHECK_FALSE(Scene{}.validated);

    Scene edited = make_builtin_scene("hand", SceneOptions{});
    edited.triangle_material[0] = 99;
    CHECK_NOTHROW(require_valid_scene(edited));  // trusted: its maker checked it, the edit did not say so
    edited.validated = false;
    CHECK(error_of([&] { require_valid_scene(edited); }).find("triangle 0 uses material 99") != std::string::npos);
}
