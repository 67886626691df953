// dof-secondary's GL build against its CPU build on a small scene: the GL
// rasterizer's per-sample winners and the compute pass of the image-space
// trace (render/gl/gl_layer_trace.hpp) give the CPU build's image. Stated
// tolerance: every channel of every pixel within 1e-6 (both run the kernel's
// text in float, llvmpipe rounding like the host; measured: identical).
//
// No GL context (no Mesa): fails when CI=true, else skips with a message.
#include "gl_parity_helpers.hpp"

#include "dof_secondary_scenes.hpp"
#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_layer_trace.hpp"
#include "render/secondary/dof_secondary.hpp"

#include <doctest/doctest.h>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;

TEST_CASE("dof-secondary: the GL build gives the CPU build's image") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    const GlLayerTracer gl_tracer(*context);
    GlRenderer rasterizer;
    const LayerTracer tracer = [&](const blurcull::kernelf::LayerView& view, const std::vector<float>& depth, int layers,
                                   float thickness, const std::vector<blurcull::kernelf::LayerSegment>& segments) {
        context->make_current();
        return gl_tracer.trace(view, depth, layers, thickness, segments);
    };
    const RenderSettings settings = quiet_settings(48, 36, 8);
    for (const Scene& scene : {mirror_sphere_scene(), plane_mirror_scene(0.1f)}) {
        CAPTURE(scene.name);
        const PrimaryPass same_scene = [&](const RenderSettings& s, std::vector<std::uint32_t>& ids) {
            GlOptions options;
            options.keep_sample_ids = true;
            return rasterizer.render(scene, s, options, &ids);
        };
        SecondaryStats cpu_stats, gl_stats;
        const Image cpu = render_dof_secondary(scene, settings, small_options(), &cpu_stats).image;
        const Image gpu = render_dof_secondary(scene, settings, small_options(), &gl_stats, &tracer, &same_scene).image;
        const ImageError e = compare(cpu, gpu);
        MESSAGE("GL against CPU build: max difference " << e.max_abs);
        CHECK(e.max_abs <= 1e-6);
        CHECK(gl_stats.rays == cpu_stats.rays);
        CHECK(gl_stats.trace_steps == cpu_stats.trace_steps);
        CHECK(gl_stats.rays_hit == cpu_stats.rays_hit);
        CHECK(gl_stats.rays_image_space > 0);
    }
}
