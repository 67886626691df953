// --method interleave, interval and accum on the GL backend
// (frontend/render/gl/gl_sampling_methods.cpp) against the CPU renderers
// (interleaved_backend.hpp): the same samples decided the same way, the same
// resolved image, the same box statistics. No GL context: SKIPPED, or a
// failure when CI=true.
#include "frontend_test_helpers.hpp"
#include "render/cpu/methods.hpp"
#include "render/gl/gl_backend.hpp"
#include "scene/builtin_scenes.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;

namespace {

RenderResult render_cpu_method(const Scene& scene, const RenderSettings& settings, std::vector<std::uint32_t>& ids) {
    if (settings.method == RenderMethod::interleave) return render_interleave(scene, settings, {}, &ids);
    if (settings.method == RenderMethod::interval) return render_interval(scene, settings, &ids);
    return render_accum(scene, settings, &ids);
}

RenderSettings small_settings(const std::string& method, int spp) {
    RenderSettings settings = quiet_settings(48, 36, spp);
    settings.seed = 3;
    settings.method = parse_render_method(method);
    return settings;
}

}  // namespace

TEST_CASE("gl methods: interleave, interval and accum agree with the cpu renderers on every built-in scene") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    struct Case {
        const char* method;
        int spp;
    };
    const Case cases[] = {{"interleave", 4}, {"interval", 4}, {"accum", 4}};
    for (const std::string& name : builtin_scene_names()) {
        SceneOptions options;
        options.aspect = 48.0f / 36.0f;
        const Scene scene = make_builtin_scene(name, options);
        for (const Case& c : cases) {
            const RenderSettings settings = small_settings(c.method, c.spp);
            std::vector<std::uint32_t> cpu_ids, gl_ids;
            const RenderResult cpu = render_cpu_method(scene, settings, cpu_ids);
            GlOptions gl_options;
            gl_options.keep_sample_ids = true;
            const auto start = std::chrono::steady_clock::now();
            const RenderResult result = gl->render(scene, settings, gl_options, &gl_ids);
            const double gl_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            const double same = fraction_equal(gl_ids, cpu_ids);
            const double error = rmse(result.image, cpu.image);
            const double close = fraction_close(result.image, cpu.image);
            const double hits_cpu = static_cast<double>(cpu.stats.samples_hit);
            const double hits_gl = static_cast<double>(result.stats.samples_hit);
            const double tested_cpu = static_cast<double>(cpu.stats.samples_tested);
            const double tested_gl = static_cast<double>(result.stats.samples_tested);
            INFO(name, " ", c.method, " spp ", c.spp, ": samples identical ", same, ", rmse ", error,
                 ", pixels within 1/255 ", close, ", hits gl ", hits_gl, " cpu ", hits_cpu, ", tested gl ", tested_gl,
                 " cpu ", tested_cpu);
            std::printf("%-9s %-10s spp %d  samples identical %.6f  rmse %.6f  pixels within 1/255 %.5f  "
                        "hits gl %.0f cpu %.0f  tested gl %.0f cpu %.0f  gl %.0f ms\n",
                        name.c_str(), c.method, c.spp, same, error, close, hits_gl, hits_cpu, tested_gl, tested_cpu,
                        gl_ms);
            // Coverage is decided by covers() in float here and double on the
            // CPU; a sample may differ where the two round differently, and a
            // near-coincident pair of surfaces may be ordered differently.
            CHECK(same >= 0.998);
            CHECK(error < 0.005);
            CHECK(close >= 0.995);
            CHECK(std::abs(hits_gl - hits_cpu) <= 0.0001 * hits_cpu + 1.0);
            // The same samples against the same boxes (rounded inwards to
            // float exactly): the same tests.
            CHECK(std::abs(tested_gl - tested_cpu) <= 0.0001 * tested_cpu + 1.0);
            CHECK(result.stats.bounds_computed == cpu.stats.bounds_computed);
            CHECK(result.stats.bounds_empty == cpu.stats.bounds_empty);
            CHECK(result.stats.triangles == scene.triangles.size());
        }
    }
}

TEST_CASE("gl methods: the seed moves the samples as on the cpu; bad settings are refused") {
    GlRenderer* gl = renderer_or_skip();
    if (gl == nullptr) return;
    const Scene scene = make_builtin_scene("dragonfly", SceneOptions{});
    RenderSettings settings = small_settings("accum", 4);
    settings.width = 24;
    settings.height = 18;
    const RenderResult first = gl->render(scene, settings);
    settings.seed = 4;
    const RenderResult other = gl->render(scene, settings);
    CHECK(rmse(first.image, other.image) > 0.0);
    CHECK(rmse(other.image, render_accum(scene, settings).image) < 0.005);

    settings = small_settings("interleave", 8);  // not a square
    CHECK_THROWS_AS(gl->render(scene, settings), std::invalid_argument);
    CHECK_THROWS_AS(parse_render_method("stratified"), std::invalid_argument);  // no such RenderMethod
    settings = small_settings("interval", 4);
    settings.width = 0;
    CHECK_THROWS_AS(gl->render(scene, settings), std::invalid_argument);
    // The lattice is width*s x height*s: past the context's framebuffer limit.
    settings = small_settings("interleave", 1024);
    settings.width = 20000;
    settings.height = 1;
    CHECK_THROWS(gl->render(scene, settings));
}
