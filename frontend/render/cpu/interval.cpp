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

RenderResult render_interval(const Scene& scene, const RenderSettings& settings, std::vector<std::uint32_t>* sample_ids) {
    cpu_methods::MethodRender render(scene, settings, RenderMethod::interval);
    const MethodPlan& plan = render.plan();
    const CameraModel& model = plan.model;
    const int width = settings.width, height = settings.height, strata = settings.spp;
    const std::size_t sample_count = static_cast<std::size_t>(width) * height * strata;
    std::vector<double> depth(sample_count, std::numeric_limits<double>::infinity());
    std::vector<std::uint32_t> hits(sample_count, no_sample_hit);

    // One work item per stratum: sample j of every pixel belongs to stratum j.
    const double near = model.znear;
    const SurfaceShader& shader = *plan.shader;
    const Counters counters = render.run_raster(strata, [&](int j, Counters& local) {
        // Sample j of every pixel, computed once per stratum.
        std::vector<cpu_methods::Sample> plane(static_cast<std::size_t>(width) * height);
        for (int py = 0; py < height; ++py) {
            for (int px = 0; px < width; ++px) {
                const kernelf::PixelSample s =
                    patternsf::interval_sample(static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py),
                                               static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(strata),
                                               settings.seed);
                plane[static_cast<std::size_t>(py) * width + px] =
                    cpu_methods::Sample{K::vec2(model.sample_ndc(px, py, s.offset)), K::vec2(s.lens), double(s.time)};
            }
        }
        cpu_methods::for_each_pass_box(plan, j, local, [&](std::uint32_t triangle, const K::MovingTriangle& tri,
                                                           const PassBox& box) {
            const CellRect& r = box.rect;
            for (int py = r.y0; py <= r.y1; ++py) {
                for (int px = r.x0; px <= r.x1; ++px) {
                    const cpu_methods::Sample& s = plane[static_cast<std::size_t>(py) * width + px];
                    const std::size_t sample = (static_cast<std::size_t>(py) * width + px) * strata + static_cast<std::size_t>(j);
                    cpu_methods::test_pass_sample(tri, box.bound, s.ndc, s.lens, s.time, near, triangle, shader, local,
                                                  depth[sample], hits[sample]);
                }
            }
        });
    });
    return render.finish(hits, counters, sample_ids);
}

}  // namespace blurcull::frontend
