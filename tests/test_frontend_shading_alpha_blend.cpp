// alphaMode BLEND as stochastic transparency (docs/reference-renderer.md,
// "Shading"): a covered sample of a blended triangle stays covered with
// probability alpha, by a hash of the sample and the triangle shared by every
// backend (surface_shared.h, bc_alpha_test), then the depth rule. Checked:
// the hash's decision rate; cpu = embree (= gl) on the same samples of a
// moving, defocused blended scene; the loader and --alpha-blend opaque; and
// convergence to sorted alpha compositing, computed per pixel, as 1/sqrt(spp).
#include "frontend_test_helpers.hpp"

#include "render/common/camera_model.hpp"
#include "render/common/shading.hpp"
#include "render/common/surface_shared.h"
#include "render/cpu/cpu_backend.hpp"
#include "render/cpu/methods.hpp"
#include "render/embree/embree_backend.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_builder.hpp"

#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;
namespace fs = std::filesystem;

namespace {

const std::string kData = std::string(BLURCULL_SOURCE_DIR) + "/tests/data/shading/";

// An emissive-only material: its flat colour is `colour` whatever the light.
Material emissive(glm::vec3 colour, float alpha, AlphaMode mode) {
    Material m;
    m.base_color = glm::vec3(0.0f);
    m.emissive = colour;
    m.base_alpha = alpha;
    m.alpha_mode = mode;
    return m;
}

// One blended layer of the convergence scene: an NDC rectangle at a view depth.
struct Layer {
    glm::vec4 ndc;  // x0, y0, x1, y1
    float depth;
    glm::vec3 colour;
    float alpha;
};

// A static pinhole scene of `layers` (view space = world space: the camera at
// the origin looking down -z), each a quad filling its NDC rectangle.
Scene layered_scene(const std::vector<Layer>& layers, int width, int height) {
    Scene scene;
    scene.name = "blend_layers";
    scene.camera.yfov = 0.8f;
    scene.background = glm::vec3(0.1f, 0.2f, 0.3f);
    const CameraModel model(scene.camera, width, height);
    for (const Layer& layer : layers) {
        const std::uint32_t material = add_material(scene, emissive(layer.colour, layer.alpha, AlphaMode::blend));
        // x_ndc = k_x x / w, y_ndc = k_y y / w at view depth w.
        const float w = layer.depth;
        const auto at = [&](float x, float y) { return glm::vec3(x * w / model.k_x, y * w / model.k_y, -w); };
        add_quad(scene, at(layer.ndc.x, layer.ndc.y), at(layer.ndc.z, layer.ndc.y), at(layer.ndc.z, layer.ndc.w),
                 at(layer.ndc.x, layer.ndc.w), glm::vec3(0.0f), material);
    }
    return scene;
}

// Sorted alpha compositing ("over", front to back) of the layers covering
// the whole of pixel (px, py); false where a layer's edge crosses the pixel.
bool composite(const std::vector<Layer>& layers, glm::vec3 background, const CameraModel& model, int px, int py,
               glm::vec3& out) {
    const glm::vec4 r = model.pixel_ndc_bounds(px, py);
    std::vector<const Layer*> covering;
    for (const Layer& layer : layers) {
        const bool inside = r.x >= layer.ndc.x && r.z <= layer.ndc.z && r.y >= layer.ndc.y && r.w <= layer.ndc.w;
        const bool outside = r.z <= layer.ndc.x || r.x >= layer.ndc.z || r.w <= layer.ndc.y || r.y >= layer.ndc.w;
        if (!inside && !outside) return false;
        if (inside) covering.push_back(&layer);
    }
    std::sort(covering.begin(), covering.end(), [](const Layer* a, const Layer* b) { return a->depth < b->depth; });
    double transmitted = 1.0;
    glm::dvec3 sum(0.0);
    for (const Layer* layer : covering) {
        sum += transmitted * double(layer->alpha) * glm::dvec3(layer->colour);
        transmitted *= 1.0 - double(layer->alpha);
    }
    out = glm::vec3(sum + transmitted * glm::dvec3(background));
    return true;
}

// A moving, defocused blended scene: an opaque grey quad at the back, two
// blended quads (alpha 0.35 and 0.6, one moving) and a masked one in front.
Scene moving_blend_scene() {
    Scene scene;
    scene.name = "blend_moving";
    scene.camera.lens_radius = 0.05f;
    scene.camera.focus_distance = 4.0f;
    Material grey;
    grey.base_color = glm::vec3(0.6f);
    const std::uint32_t back = add_material(scene, grey);
    Material red;
    red.base_color = glm::vec3(0.9f, 0.2f, 0.1f);
    red.base_alpha = 0.35f;
    red.alpha_mode = AlphaMode::blend;
    const std::uint32_t first = add_material(scene, red);
    Material blue = red;
    blue.base_color = glm::vec3(0.1f, 0.3f, 0.9f);
    blue.base_alpha = 0.6f;
    const std::uint32_t second = add_material(scene, blue);
    add_quad(scene, {-2.0f, -1.5f, -6.0f}, {2.0f, -1.5f, -6.0f}, {2.0f, 1.5f, -6.0f}, {-2.0f, 1.5f, -6.0f}, {},
             back);
    add_quad(scene, {-1.2f, -0.8f, -4.5f}, {0.4f, -0.8f, -4.5f}, {0.4f, 0.8f, -4.5f}, {-1.2f, 0.8f, -4.5f},
             {0.6f, 0.1f, 0.0f}, first);
    add_quad(scene, {-0.3f, -0.6f, -3.5f}, {0.9f, -0.6f, -3.5f}, {0.9f, 0.5f, -3.5f}, {-0.3f, 0.5f, -3.5f},
             {0.0f, 0.0f, 0.3f}, second);
    return scene;
}

Scene with_mode(Scene scene, AlphaMode from, AlphaMode to) {
    for (Material& m : scene.materials)
        if (m.alpha_mode == from) m.alpha_mode = to;
    return scene;
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// tests/data/shading/`name` (attributes.gltf by default) with its MASK
// material made BLEND, in a temporary folder.
std::string blend_attributes_file(const fs::path& folder, const std::string& name = "attributes.gltf") {
    std::string text = read_file(kData + name);
    const std::size_t at = text.find("\"MASK\"");
    REQUIRE(at != std::string::npos);
    text.replace(at, 6, "\"BLEND\"");
    fs::create_directories(folder);
    const fs::path file = folder / ("blend_" + name);
    std::ofstream(file, std::ios::binary) << text;
    return file.string();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("bc_blend_kept keeps a fraction alpha of samples; the hash depends on every input") {
    namespace s = surface;
    const float alphas[] = {0.0f, 0.1f, 0.5f, 0.9f, 1.0f};
    for (float alpha : alphas) {
        std::size_t kept = 0;
        const std::size_t n = 200000;
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec2 ndc(float(i % 400) / 200.0f - 1.0f, float(i / 400) / 250.0f - 1.0f);
            kept += s::bc_blend_kept(alpha, s::bc_blend_hash(7u, ndc, 0.5f)) ? 1 : 0;
        }
        const double rate = double(kept) / double(n);
        MESSAGE("alpha " << alpha << ": kept " << rate);
        // 4 standard deviations of a binomial of n draws, and exact at 0 and 1.
        CHECK(std::abs(rate - double(alpha)) <= 4.0 * std::sqrt(double(alpha) * (1.0 - alpha) / double(n)) + 1e-12);
    }
    const std::uint32_t h = s::bc_blend_hash(3u, {0.25f, -0.5f}, 0.3f);
    CHECK(h != s::bc_blend_hash(4u, {0.25f, -0.5f}, 0.3f));
    CHECK(h != s::bc_blend_hash(3u, {0.2500001f, -0.5f}, 0.3f));
    CHECK(h != s::bc_blend_hash(3u, {0.25f, -0.5000001f}, 0.3f));
    CHECK(h != s::bc_blend_hash(3u, {0.25f, -0.5f}, 0.3000001f));
    CHECK(h != s::bc_blend_hash(3u, {-0.5f, 0.25f}, 0.3f));
    // -0 and +0 are one sample.
    CHECK(s::bc_blend_hash(3u, {0.0f, -0.0f}, 0.0f) == s::bc_blend_hash(3u, {-0.0f, 0.0f}, -0.0f));
    // Pinned values: a change of the hash changes every backend's images.
    CHECK(s::bc_mix32(0u) == 0u);
    CHECK(s::bc_mix32(1u) == 0x688990c0u);
}

TEST_CASE("BLEND in motion and defocus: cpu = embree on the same samples; opaque and other seeds differ") {
    const auto start = std::chrono::steady_clock::now();
    const Scene scene = moving_blend_scene();
    const RenderSettings settings = quiet_settings(64, 48, 16);
    const RenderResult cpu = render_cpu(scene, settings);
    const RenderResult ray = render_embree(scene, settings);
    CpuOptions float_kernel;
    float_kernel.precision = KernelPrecision::float32;
    const RenderResult cpu_float = render_cpu(scene, settings, float_kernel);
    RenderSettings other_seed = settings;
    other_seed.seed = 2;
    const RenderResult reseeded_cpu = render_cpu(scene, other_seed);
    const RenderResult reseeded_ray = render_embree(scene, other_seed);
    const Scene opaque = with_mode(scene, AlphaMode::blend, AlphaMode::opaque);
    const RenderResult opaque_cpu = render_cpu(opaque, settings);
    MESSAGE("cpu vs embree RMSE " << rmse(cpu.image, ray.image) << " (" << 100.0 * fraction_close(cpu.image, ray.image)
                                  << "% within 1/255), cpu vs cpu float " << rmse(cpu.image, cpu_float.image)
                                  << ", seed 1 vs 2 " << rmse(cpu.image, reseeded_cpu.image) << ", vs opaque "
                                  << rmse(cpu.image, opaque_cpu.image) << "; hits " << cpu.stats.samples_hit
                                  << " blend, " << opaque_cpu.stats.samples_hit << " opaque");
    // The CPU vs Embree rule of test_frontend_cpu.cpp: same samples, same hits.
    CHECK(rmse(cpu.image, ray.image) < 0.002);
    CHECK(fraction_close(cpu.image, ray.image) >= 0.995);
    CHECK(rmse(reseeded_cpu.image, reseeded_ray.image) < 0.002);
    CHECK(rmse(cpu.image, cpu_float.image) < 0.002);
    // The noise the agreement is measured against: another seed's samples.
    CHECK(rmse(cpu.image, reseeded_cpu.image) > 0.01);
    CHECK(rmse(cpu.image, opaque_cpu.image) > 0.03);
    CHECK(cpu.stats.samples_hit < opaque_cpu.stats.samples_hit);
    // Every Embree tracing shape filters with the right sample (ray id).
    for (EmbreeTracing tracing : {EmbreeTracing::single, EmbreeTracing::packet8, EmbreeTracing::stream}) {
        EmbreeOptions options;
        options.tracing = tracing;
        INFO(tracing_name(tracing));
        CHECK(same_pixels(render_embree(scene, settings, options).image, ray.image));
    }
    MESSAGE("took " << seconds_since(start) << " s");
}

TEST_CASE("gltf BLEND is read as stochastic transparency, without a warning; --alpha-blend opaque draws it opaque") {
    const fs::path folder = fs::temp_directory_path() / ("blurcull_alpha_blend_" + std::to_string(::getpid()));
    const std::string file = blend_attributes_file(folder);
    std::vector<std::string> warnings;
    const WarningSink sink = [&](const std::string& w) { warnings.push_back(w); };
    const Scene blended = load_scene(file, SceneSettings{}, sink);
    for (const std::string& w : warnings) MESSAGE(w);
    CHECK(warnings.empty());
    REQUIRE(blended.materials.size() == 2);
    CHECK(blended.materials[0].alpha_mode == AlphaMode::blend);
    SceneSettings opaque_settings;
    opaque_settings.blend_opaque = true;
    const Scene opaque = load_scene(file, opaque_settings, sink);
    CHECK(opaque.materials[0].alpha_mode == AlphaMode::opaque);
    CHECK(warnings.empty());
    const RenderSettings settings = quiet_settings(96, 72, 8);
    const RenderResult blend_image = render_cpu(blended, settings);
    const RenderResult opaque_image = render_cpu(opaque, settings);
    // The front quad's alpha falls from 1 (left) to 0 (right): the right
    // shows the back quad through it; the left edge stays (nearly) opaque.
    CHECK(blend_image.stats.samples_hit < opaque_image.stats.samples_hit);
    CHECK(rmse(blend_image.image, opaque_image.image) > 0.02);
    CHECK(rmse(blend_image.image, render_embree(blended, settings).image) < 0.002);
    fs::remove_all(folder);
}

TEST_CASE("BLEND converges to sorted alpha compositing as 1/sqrt(spp)") {
    const auto start = std::chrono::steady_clock::now();
    const int width = 48, height = 36;
    // Three overlapping layers at depths 3, 4, 5, over the background.
    const std::vector<Layer> layers{
        {{-0.8f, -0.7f, 0.3f, 0.5f}, 4.0f, {0.9f, 0.1f, 0.1f}, 0.5f},
        {{-0.3f, -0.5f, 0.8f, 0.8f}, 3.0f, {0.1f, 0.8f, 0.2f}, 0.3f},
        {{-0.5f, -0.9f, 0.6f, 0.1f}, 5.0f, {0.2f, 0.3f, 1.0f}, 0.7f},
    };
    Scene scene = layered_scene(layers, width, height);
    const CameraModel model(scene.camera, width, height);
    std::vector<glm::vec3> reference(std::size_t(width) * height);
    std::vector<char> valid(reference.size(), 0);
    std::size_t valid_pixels = 0;
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            const std::size_t i = std::size_t(py) * width + px;
            valid[i] = composite(layers, scene.background, model, px, py, reference[i]) ? 1 : 0;
            valid_pixels += std::size_t(valid[i]);
        }
    REQUIRE(valid_pixels > reference.size() / 2);
    std::vector<double> spps, errors;
    std::printf("BLEND convergence, %dx%d, 3 layers, %zu pixels compared (cpu backend):\n", width, height,
                valid_pixels);
    std::printf("  spp   RMSE       RMSE x sqrt(spp)  mean error\n");
    for (int spp : {16, 64, 256, 1024}) {
        const RenderResult cpu = render_cpu(scene, quiet_settings(width, height, spp));
        double squares = 0.0, signed_sum = 0.0;
        for (std::size_t i = 0; i < reference.size(); ++i) {
            if (!valid[i]) continue;
            const glm::dvec3 d = glm::dvec3(cpu.image.pixels[i]) - glm::dvec3(reference[i]);
            squares += glm::dot(d, d) / 3.0;
            signed_sum += (d.x + d.y + d.z) / 3.0;
        }
        const double error = std::sqrt(squares / double(valid_pixels));
        const double mean = signed_sum / double(valid_pixels);
        std::printf("  %4d  %.6f   %.4f            %+.6f\n", spp, error, error * std::sqrt(double(spp)), mean);
        // No bias: the mean error is within 4 standard errors of 0.
        CHECK(std::abs(mean) < 4.0 * error / std::sqrt(double(valid_pixels)));
        spps.push_back(spp);
        errors.push_back(error);
    }
    // The least-squares slope of log error against log spp: -1/2 for Monte Carlo.
    double mx = 0.0, my = 0.0;
    for (std::size_t k = 0; k < spps.size(); ++k) {
        mx += std::log(spps[k]) / double(spps.size());
        my += std::log(errors[k]) / double(spps.size());
    }
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t k = 0; k < spps.size(); ++k) {
        sxy += (std::log(spps[k]) - mx) * (std::log(errors[k]) - my);
        sxx += (std::log(spps[k]) - mx) * (std::log(spps[k]) - mx);
    }
    const double slope = sxy / sxx;
    std::printf("  log-log slope %.3f (1/sqrt(spp): -0.5)\n", slope);
    CHECK(slope > -0.6);
    CHECK(slope < -0.4);
    for (std::size_t k = 1; k < errors.size(); ++k) {
        // Each 4x the samples halves the error, within sampling noise.
        CHECK(errors[k - 1] / errors[k] > 1.6);
        CHECK(errors[k - 1] / errors[k] < 2.5);
    }
    // Embree on the same samples converges to the same image.
    const RenderSettings last = quiet_settings(width, height, 1024);
    CHECK(rmse(render_embree(scene, last).image, render_cpu(scene, last).image) < 0.002);
    MESSAGE("took " << seconds_since(start) << " s");
}

TEST_CASE("gl: BLEND keeps the cpu backend's samples (stochastic path, full path, defocus, methods)") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    const auto start = std::chrono::steady_clock::now();
    // The moving quads, and BLEND materials from glTF: alpha from COLOR_0
    // (attributes.gltf), from a texture with wrap modes and a transform (mask_texture.gltf).
    const fs::path folder = fs::temp_directory_path() / ("blurcull_alpha_blend_gl_" + std::to_string(::getpid()));
    const std::vector<Scene> scenes{moving_blend_scene(), load_scene(blend_attributes_file(folder)),
                                    load_scene(blend_attributes_file(folder, "mask_texture.gltf"))};
    fs::remove_all(folder);
    for (const Scene& scene : scenes) {
        INFO(scene.name);
        for (int variant = 0; variant < 3; ++variant) {
            // Per pass (4 spp), per group of passes (16 spp), every triangle on the moving path.
            RenderSettings settings = quiet_settings(64, 48, variant == 1 ? 16 : 4);
            GlOptions gl_options;
            gl_options.force_full_path = variant == 2;
            gl_options.keep_sample_ids = true;
            INFO("variant " << variant);
            std::vector<std::uint32_t> gl_ids, cpu_ids;
            CpuOptions float_kernel;
            float_kernel.precision = KernelPrecision::float32;
            const RenderResult on_gl = gl->render(scene, settings, gl_options, &gl_ids);
            const RenderResult cpu = render_cpu(scene, settings, float_kernel, &cpu_ids);
            const double same = fraction_equal(gl_ids, cpu_ids);
            MESSAGE("variant " << variant << ": gl vs cpu float RMSE " << rmse(on_gl.image, cpu.image)
                               << ", samples identical " << same);
            CHECK(on_gl.warnings.empty());
            CHECK(same >= 0.998);
            CHECK(rmse(on_gl.image, cpu.image) < 0.001);
        }
        for (const RenderMethod method : {RenderMethod::interleave, RenderMethod::interval, RenderMethod::accum}) {
            RenderSettings settings = quiet_settings(64, 48, 4);
            settings.method = method;
            INFO(std::string(to_string(method)));
            std::vector<std::uint32_t> cpu_ids, gl_ids;
            RenderResult cpu;
            if (method == RenderMethod::interleave) cpu = render_interleave(scene, settings, {}, &cpu_ids);
            if (method == RenderMethod::interval) cpu = render_interval(scene, settings, &cpu_ids);
            if (method == RenderMethod::accum) cpu = render_accum(scene, settings, &cpu_ids);
            GlOptions gl_options;
            gl_options.keep_sample_ids = true;
            const RenderResult on_gl = gl->render(scene, settings, gl_options, &gl_ids);
            const double same = fraction_equal(gl_ids, cpu_ids);
            MESSAGE(std::string(to_string(method)) << ": samples identical " << same << ", RMSE " << rmse(on_gl.image, cpu.image));
            CHECK(same >= 0.998);
            CHECK(rmse(on_gl.image, cpu.image) < 0.005);
        }
    }
    MESSAGE("took " << seconds_since(start) << " s");
}
