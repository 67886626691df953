#include "render/cpu/methods.hpp"

#include "render/common/camera_model.hpp"
#include "render/cpu/method_runner.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace blurcull::frontend {

using cpu_methods::Counters;
using cpu_methods::K;

RenderResult render_accum(const Scene& scene, const RenderSettings& settings, std::vector<std::uint32_t>* sample_ids) {
    cpu_methods::MethodRender render(scene, settings, RenderMethod::accum);
    const MethodPlan& plan = render.plan();
    const CameraModel& model = plan.model;
    const int width = settings.width, height = settings.height, passes = settings.spp;
    const std::size_t pixel_count = static_cast<std::size_t>(width) * height;
    // hits[pixel * K + k]: what pass k saw, so the passes can run in any
    // order and the resolve still sums them in order 0 .. K-1.
    std::vector<std::uint32_t> hits(pixel_count * static_cast<std::size_t>(passes), no_sample_hit);

    const double near = model.znear;
    const SurfaceShader& shader = *plan.shader;
    const Counters counters = render.run_raster(passes, [&](int k, Counters& local) {
        const kernelf::PixelSample& pass_sample = plan.pass_samples[static_cast<std::size_t>(k)];
        const K::vec2 uv(pass_sample.lens);
        const double t = pass_sample.time;
        const glm::vec2 offset = pass_sample.offset;
        std::vector<double> depth(pixel_count, std::numeric_limits<double>::infinity());
        std::vector<std::uint32_t> pass(pixel_count, no_sample_hit);
        cpu_methods::for_each_pass_box(plan, k, local, [&](std::uint32_t triangle, const K::MovingTriangle& tri,
                                                           const PassBox& box) {
            const CellRect& r = box.rect;
            for (int py = r.y0; py <= r.y1; ++py) {
                for (int px = r.x0; px <= r.x1; ++px) {
                    const K::vec2 ndc(model.sample_ndc(px, py, offset));
                    const std::size_t pixel = static_cast<std::size_t>(py) * width + px;
                    cpu_methods::test_pass_sample(tri, box.bound, ndc, uv, t, near, triangle, shader, local, depth[pixel],
                                                  pass[pixel]);
                }
            }
        });
        for (std::size_t pixel = 0; pixel < pixel_count; ++pixel) {
            hits[pixel * static_cast<std::size_t>(passes) + static_cast<std::size_t>(k)] = pass[pixel];
        }
    });
    return render.finish(hits, counters, sample_ids);
}

}  // namespace blurcull::frontend
