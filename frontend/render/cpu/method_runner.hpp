// What the CPU renderers of interleave, interval and accum share besides their
// MethodPlan: running work items on the settings' threads with per-thread
// counters, the loop over a pass's boxes, the per-sample test with the depth
// rule, and the frame of a render (plan, phases, progress, resolve, statistics).
#pragma once

#include "render/common/method_plan.hpp"
#include "render/common/progress.hpp"
#include "render/common/render_types.hpp"
#include "render/common/surface_shading.hpp"
#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

namespace blurcull::frontend::cpu_methods {

// Double precision like render_cpu: the coverage test is the same oracle, and
// the boxes that restrict it are conservative against it.
using K = blurcull::kernel<double>;
using Clock = std::chrono::steady_clock;

// One sample: its NDC position, lens position and time.
struct Sample {
    K::vec2 ndc;
    K::vec2 lens;
    double time;
};

struct Counters {
    std::uint64_t tested = 0, hit = 0, bounded = 0, bounded_empty = 0;
};

// Runs work(item, counters) for item = 0 .. items-1 on the settings' threads.
// Items must write disjoint memory; the counters are summed afterwards.
Counters run_items(const RenderSettings& settings, int items, const std::function<void(int, Counters&)>& work);

// One sample of a pass against triangle `triangle` in its pass box `bound`:
// the kernel's sample_test (screen bound, then the exact test; the passes
// bound lens and time by their boxes, so no sample bounds), counted in
// `local`, the alpha mask (SurfaceShader::sample_kept: a masked-out sample
// is not a hit), then the CPU depth rule (depth_nearer: with triangles in
// index order the first of equal depths wins, as in render_cpu) on the
// sample's depth and hit.
inline void test_pass_sample(const K::MovingTriangle& tri, const K::ScreenBound& bound, K::vec2 ndc, K::vec2 lens,
                             double time, double near, std::uint32_t triangle, const SurfaceShader& shader,
                             Counters& local, double& depth, std::uint32_t& hit) {
    double z = 0.0;
    const int verdict = K::sample_test(tri, bound, true, K::no_sample_bounds(), ndc, lens, time, near, z);
    if (verdict == BC_SAMPLE_CULLED) return;
    ++local.tested;
    if (verdict != BC_SAMPLE_COVERED) return;
    // The samples' positions are floats (method_sample), so these casts are exact.
    if (shader.masked(triangle) &&
        !shader.sample_kept(triangle, glm::vec2(ndc), glm::vec2(lens), static_cast<float>(time)))
        return;
    ++local.hit;
    if (K::depth_nearer(z, depth)) {
        depth = z;
        hit = triangle;
    }
}

// Calls visit(triangle, tri, box) for every visible triangle of the plan whose
// pass box for `pass` holds a lattice cell, in index order (the depth rule
// needs it); counts every box in local.bounded, the empty ones in
// local.bounded_empty.
template <class VisitBox>
void for_each_pass_box(const MethodPlan& plan, int pass, Counters& local, VisitBox&& visit) {
    for (std::size_t index = 0; index < plan.triangles.size(); ++index) {
        if (!plan.visible[index]) continue;
        const PassBox box = method_pass_box(plan, pass, index);
        ++local.bounded;
        if (box.rect.empty()) {
            ++local.bounded_empty;
            continue;
        }
        visit(static_cast<std::uint32_t>(index), plan.triangles[index], box);
    }
}

// The frame every renderer here shares: the clock and the plan (construction),
// the setup and raster phases with progress (run_raster), the resolve and the
// statistics (finish). What runs between construction and run_raster is timed
// as the method's setup.
class MethodRender {
public:
    // Starts the clock and makes the plan of `method` for the scene.
    MethodRender(const Scene& scene, const RenderSettings& settings, RenderMethod method,
                 const InterleaveOptions& options = {});

    // The plan made at construction.
    const MethodPlan& plan() const { return plan_; }

    // Ends the setup phase, runs work(item, counters) for item = 0 .. items-1
    // on the settings' threads (see run_items) with progress, times it as the
    // raster phase and returns the summed counters.
    Counters run_raster(int items, const std::function<void(int, Counters&)>& work);

    // Resolves the per-sample hits into the image and returns the result with
    // the counters, the plan's warnings and the times; hands the hits to
    // sample_ids when given.
    RenderResult finish(std::vector<std::uint32_t>& hits, const Counters& counters,
                        std::vector<std::uint32_t>* sample_ids);

private:
    const Scene& scene_;
    const RenderSettings& settings_;
    Clock::time_point start_, phase_;
    MethodPlan plan_;
    RenderResult result_;
};

}  // namespace blurcull::frontend::cpu_methods
