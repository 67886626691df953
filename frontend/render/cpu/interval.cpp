#include "render/cpu/methods.hpp"

#include "render/common/camera_model.hpp"
#include "render/common/progress.hpp"
#include "render/cpu/method_runner.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace blurcull::frontend {

using cpu_methods::Clock;
using cpu_methods::Counters;
using cpu_methods::K;

RenderResult render_interval(const Scene& scene, const RenderSettings& settings, std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point start = Clock::now();
    Clock::time_point phase = Clock::now();
    RenderSettings interval_settings = settings;
    interval_settings.method = RenderMethod::interval;
    const MethodPlan plan = make_method_plan(scene, interval_settings);
    const CameraModel& model = plan.model;
    const int width = settings.width, height = settings.height, strata = settings.spp;
    const std::size_t sample_count = static_cast<std::size_t>(width) * height * strata;
    std::vector<double> depth(sample_count, std::numeric_limits<double>::infinity());
    std::vector<std::uint32_t> hits(sample_count, no_sample_hit);
    RenderResult result;
    result.stats.triangles = scene.triangles.size();
    result.stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    // One work item per stratum: sample j of every pixel belongs to stratum j.
    phase = Clock::now();
    const double near = model.znear;
    Progress progress(settings.progress, start, strata);
    const Counters counters = cpu_methods::run_items(settings, strata, [&](int j, Counters& local) {
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
        for (std::size_t index = 0; index < plan.triangles.size(); ++index) {
            if (!plan.visible[index]) continue;
            const K::MovingTriangle& tri = plan.triangles[index];
            const PassBox box = method_pass_box(plan, j, index);
            ++local.bounded;
            const CellRect& r = box.rect;
            if (r.empty()) {
                ++local.bounded_empty;
                continue;
            }
            for (int py = r.y0; py <= r.y1; ++py) {
                for (int px = r.x0; px <= r.x1; ++px) {
                    const cpu_methods::Sample& s = plane[static_cast<std::size_t>(py) * width + px];
                    const std::size_t sample = (static_cast<std::size_t>(py) * width + px) * strata + static_cast<std::size_t>(j);
                    cpu_methods::test_pass_sample(tri, box.bound, s.ndc, s.lens, s.time, near,
                                                  static_cast<std::uint32_t>(index), local, depth[sample], hits[sample]);
                }
            }
        }
        progress.advance();
    });
    progress.finish();
    result.stats.ms_per_phase.emplace_back("raster", ms_since(phase));

    cpu_methods::finish_render(result, scene, plan, hits, counters, width, height, start, sample_ids);
    return result;
}

}  // namespace blurcull::frontend
