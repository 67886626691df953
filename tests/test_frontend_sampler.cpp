// RenderSettings::sampler (--sampler) on every backend: the CPU rasterizer,
// the Embree ray tracer and the GL backend draw the same samples of the
// chosen pattern (the GL backend's sample ids equal the CPU's in float),
// the CPU's time-sorted footprints still visit only a time run and every
// cull gives the same image with the Sobol patterns, and a bad id is refused.
// No GL context: the GL part is SKIPPED, or a failure when CI=true.
#include "gl_render_reference.hpp"  // first: it keeps the host from contracting a*b+c
#include "render/cpu/cpu_backend.hpp"
#include "render/embree/embree_backend.hpp"
#include "scene/builtin_scenes.hpp"

#include <blurcull/pattern_names.hpp>

#include <doctest/doctest.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;

namespace {

RenderSettings with_sampler(int width, int height, int spp, int sampler) {
    RenderSettings settings = quiet_settings(width, height, spp);
    settings.sampler = sampler;
    settings.seed = 5;
    return settings;
}

}  // namespace

TEST_CASE("cpu and embree draw the same samples of every sampler, and the sampler changes them") {
    const int width = 64, height = 48;
    for (const std::string& name : {std::string("hand"), std::string("forest")}) {
        const Scene scene = small_scene(name, width, height);
        std::vector<Image> cpu_images;
        for (int sampler = 0; sampler < BC_PATTERN_COUNT; ++sampler) {
            const RenderSettings settings = with_sampler(width, height, 4, sampler);
            const RenderResult cpu = render_cpu(scene, settings);
            const RenderResult ray = render_embree(scene, settings);
            const double error = rmse(cpu.image, ray.image);
            INFO(name, " ", blurcull::sample_pattern_name(sampler), ": cpu vs embree rmse ", error);
            // The same samples: equal but for a rare float tie (tests/test_frontend_cpu.cpp's bound).
            CHECK(error < 0.002);
            CHECK(fraction_close(cpu.image, ray.image) >= 0.995);
            cpu_images.push_back(cpu.image);
        }
        // Another pattern's samples: a different noisy image, far beyond that bound.
        for (int a = 0; a < BC_PATTERN_COUNT; ++a) {
            for (int b = a + 1; b < BC_PATTERN_COUNT; ++b) {
                INFO(name, " ", blurcull::sample_pattern_name(a), " vs ", blurcull::sample_pattern_name(b));
                CHECK(rmse(cpu_images[std::size_t(a)], cpu_images[std::size_t(b)]) > 0.005);
            }
        }
    }
}

TEST_CASE("sobol samplers on the cpu: every cull, footprint and thread count gives the same image") {
    const int width = 64, height = 48;
    for (int sampler : {BC_PATTERN_SOBOL, BC_PATTERN_PADDED_SOBOL}) {
        for (const std::string& name : builtin_scene_names()) {
            const Scene scene = small_scene(name, width, height);
            RenderSettings settings = with_sampler(width, height, 16, sampler);
            settings.cull = CullMethod::bbox;
            // Occlusion culling off: samples_hit counts every covered sample
            // (with it, those its path left to test).
            CpuOptions every_hit;
            every_hit.occlusion = false;
            const RenderResult reference = render_cpu(scene, settings, every_hit);
            REQUIRE(reference.stats.samples_hit > 0);
            for (CullMethod cull : {CullMethod::hull, CullMethod::dualspace, CullMethod::two_stage, CullMethod::edges}) {
                for (int footprint : {1, CpuOptions{}.footprint}) {
                    RenderSettings culled = settings;
                    culled.cull = cull;
                    culled.threads = footprint == 1 ? 1 : 0;
                    CpuOptions options = every_hit;
                    options.footprint = footprint;
                    const RenderResult result = render_cpu(scene, culled, options);
                    INFO(name, " ", blurcull::sample_pattern_name(sampler), " ", to_string(cull), " footprint ",
                         footprint);
                    CHECK(result.stats.samples_hit == reference.stats.samples_hit);
                    CHECK(same_pixels(result.image, reference.image));
                    CHECK(result.stats.samples_tested <= reference.stats.samples_tested);
                }
            }
        }
    }
}

TEST_CASE("the time-sorted footprints visit a time run as short with the sobol samplers as with hashed") {
    // Motion blur (the dragonfly's wings) and a time bound: each footprint's
    // samples sorted by time, a bound visits only the run inside its shutter
    // interval. Every power-of-two block of a pixel's Sobol samples is
    // stratified in time like hashed's strata, so the runs are as short.
    const int width = 64, height = 48;
    const Scene scene = small_scene("dragonfly", width, height);
    RenderSettings settings = with_sampler(width, height, 16, BC_PATTERN_HASHED);
    settings.cull = CullMethod::two_stage;
    const RenderResult hashed = render_cpu(scene, settings);
    REQUIRE(hashed.stats.samples_visited > 0);
    for (int sampler : {BC_PATTERN_SOBOL, BC_PATTERN_PADDED_SOBOL}) {
        settings.sampler = sampler;
        settings.cull = CullMethod::bbox;
        const RenderResult bbox = render_cpu(scene, settings);
        settings.cull = CullMethod::two_stage;
        const RenderResult timed = render_cpu(scene, settings);
        const double ratio = double(timed.stats.samples_visited) / double(hashed.stats.samples_visited);
        INFO(blurcull::sample_pattern_name(sampler), ": visited ", timed.stats.samples_visited, " (hashed ",
             hashed.stats.samples_visited, "), tested ", timed.stats.samples_tested);
        CHECK(timed.stats.samples_visited >= timed.stats.samples_tested);
        CHECK(ratio > 0.9);
        CHECK(ratio < 1.1);
        CHECK(double(timed.stats.samples_tested) < 1.1 * double(hashed.stats.samples_tested));
        CHECK(same_pixels(timed.image, bbox.image));
    }
}

TEST_CASE("a sampler id out of range is refused in one line naming the valid ones") {
    const Scene scene = small_scene("hand", 16, 12);
    RenderSettings settings = with_sampler(16, 12, 4, BC_PATTERN_COUNT);
    CHECK_THROWS_WITH_AS(render_cpu(scene, settings),
                         "unknown sampler id 5 (valid: hashed, random, jittered, sobol, padded-sobol)",
                         std::invalid_argument);
    settings.sampler = -1;
    CHECK_THROWS_AS(render_embree(scene, settings), std::invalid_argument);
}

TEST_CASE("gl backend: the same samples as the cpu backend for every sampler") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    const int width = 40, height = 30;
    const Scene scene = small_scene("hand", width, height);
    CpuOptions float_options;
    float_options.precision = KernelPrecision::float32;
    std::vector<std::vector<std::uint32_t>> cpu_ids;
    for (int sampler = 0; sampler < BC_PATTERN_COUNT; ++sampler) {
        const RenderSettings settings = with_sampler(width, height, 4, sampler);
        std::vector<std::uint32_t> cpu, ids;
        const RenderResult on_cpu = render_cpu(scene, settings, float_options, &cpu);
        GlOptions options;
        options.keep_sample_ids = true;
        const RenderResult on_gl = gl->render(scene, settings, options, &ids);
        const double same = fraction_equal(ids, cpu);
        std::printf("gl vs cpu float, %s: same triangle %.6f, hits %llu vs %llu\n", blurcull::sample_pattern_name(sampler),
                    same, static_cast<unsigned long long>(on_gl.stats.samples_hit),
                    static_cast<unsigned long long>(on_cpu.stats.samples_hit));
        INFO(blurcull::sample_pattern_name(sampler), ": same triangle ", same);
        if (render_probe(*gl).tolerant()) {
            // A GPU that does not compute as the host: each differing sample
            // explained by the model (tests/gl_render_reference.hpp), the
            // hits within the pairs near an edge, the image within what the
            // explained samples can move.
            const SampleReference<float> ref = reference_samples<float>(scene, settings, true);
            const SampleIdComparison cmp = compare_sample_ids(scene, ref, ids, settings.spp);
            const double error = rmse(on_gl.image, ref.image);
            std::printf("  tolerant: %ld near an edge, %ld depth ties, %ld outside the model; %ld pairs near an "
                        "edge; rmse %.6f, limit %.6f\n",
                        cmp.near_edge, cmp.depth_tie, cmp.outside, ref.pairs_near_edge, error, cmp.image_rmse_limit);
            INFO("first outside the model: ", cmp.first_outside);
            CHECK(cmp.outside == 0);
            CHECK(std::abs(double(on_gl.stats.samples_hit) - double(on_cpu.stats.samples_hit)) <=
                  double(ref.pairs_near_edge));
            CHECK(error <= cmp.image_rmse_limit + 1e-6);
        } else {
            // As tests/test_frontend_gl_render.cpp: equal but for depth ties between paths.
            CHECK(same >= 0.999);
            CHECK(on_gl.stats.samples_hit == on_cpu.stats.samples_hit);
        }
        cpu_ids.push_back(cpu);
    }
    // The check can fail: another pattern's samples see other triangles.
    for (int sampler = 1; sampler < BC_PATTERN_COUNT; ++sampler) {
        CHECK(fraction_equal(cpu_ids[0], cpu_ids[std::size_t(sampler)]) < 0.99);
    }
}
