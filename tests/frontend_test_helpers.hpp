// Helpers the frontend tests share: CI detection, scene building, image and
// sample-id comparison, and the one GL renderer a test file reuses.
#pragma once

#include "render/common/image.hpp"
#include "render/gl/gl_backend.hpp"
#include "scene/builtin_scenes.hpp"
#include "scene/scene.hpp"

#include "kernel_generators.hpp"
#include "test_cleanup.hpp"

#include <doctest/doctest.h>
#include <glm/glm.hpp>

#include <algorithm>

#include <cstdint>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace blurcull::frontend::test {

// CI=true (or 1): a missing context or display is a failure, not a skip.
inline bool is_ci() {
    const char* ci = std::getenv("CI");
    return ci != nullptr && (std::string(ci) == "true" || std::string(ci) == "1");
}

// Whether a sweep over scenes x variants runs the variant whose indices sum
// to `index_sum`: always in a full run; in a scaled-down one (CI's sanitizer
// pass, BLURCULL_PROPERTY_SCALE < 1) one in `stride`, rotated over the
// scenes so that every variant still runs on some scene.
inline bool sweeps_variant(std::size_t index_sum, std::size_t stride) {
    return blurcull::testing::property_scale() >= 1.0 || index_sum % stride == 0;
}

// A built-in scene framed for a width x height image, its blur scaled.
inline Scene small_scene(const std::string& name, int width, int height, float blur_scale = 1.0f) {
    SceneOptions options;
    options.blur_scale = blur_scale;
    options.aspect = float(width) / float(height);
    return make_builtin_scene(name, options);
}

// Two triangles a, b, c and a, c, d moving by `motion` over the shutter.
inline void add_quad(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 motion,
                     std::uint32_t material) {
    const auto base = static_cast<std::uint32_t>(scene.position_open.size());
    for (glm::vec3 p : {a, b, c, d}) {
        scene.position_open.push_back(p);
        scene.position_close.push_back(p + motion);
    }
    scene.triangles.push_back({base, base + 1, base + 2});
    scene.triangles.push_back({base, base + 2, base + 3});
    scene.triangle_material.push_back(material);
    scene.triangle_material.push_back(material);
}

// Bit-identical images.
inline bool same_pixels(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) return false;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (a.pixels[i] != b.pixels[i]) return false;
    }
    return true;
}

// A width x height render with spp samples and no progress output.
inline RenderSettings quiet_settings(int width, int height, int spp) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.spp = spp;
    settings.progress = false;
    return settings;
}

// The fraction of pixels whose every channel is within 1/255.
inline double fraction_close(const Image& a, const Image& b) {
    REQUIRE(a.pixels.size() == b.pixels.size());
    std::size_t close = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
        close += std::max({d.x, d.y, d.z}) <= 1.0f / 255.0f ? 1 : 0;
    }
    return static_cast<double>(close) / static_cast<double>(a.pixels.size());
}

// The fraction of samples showing the same triangle.
inline double fraction_equal(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
    REQUIRE(a.size() == b.size());
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == b[i] ? 1 : 0;
    return a.empty() ? 1.0 : static_cast<double>(same) / static_cast<double>(a.size());
}

// One renderer for the whole test file (compiling the programs is the slow
// part); null after saying why when no context can be made (a failure in CI).
// Destroyed at the end of main (test_cleanup.hpp), not with the statics: the
// GL driver may be shut down by then.
inline GlRenderer* renderer_or_skip() {
    static std::unique_ptr<GlRenderer> renderer;
    static std::string failure;
    if (!renderer && failure.empty()) {
        try {
            renderer = std::make_unique<GlRenderer>();
            at_end_of_main([] { renderer.reset(); });
            MESSAGE("GL: " << renderer->description());
        } catch (const std::exception& e) {
            failure = e.what();
        }
    }
    if (!renderer) {
        if (is_ci()) FAIL("no headless OpenGL 4.5 context in CI: " << failure);
        MESSAGE("SKIPPED: no headless OpenGL 4.5 context (" << failure << "); CI=true makes this a failure");
    }
    return renderer.get();
}

}  // namespace blurcull::frontend::test
