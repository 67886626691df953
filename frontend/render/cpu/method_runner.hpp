// What the CPU renderers of interleave, interval and accum share besides their
// MethodPlan: running work items on the settings' threads with per-thread
// counters, the per-sample test with the depth rule, and the common end of a render.
#pragma once

#include "render/common/method_plan.hpp"
#include "render/common/progress.hpp"
#include "render/common/render_types.hpp"
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
// `local`, then the CPU depth rule (depth_nearer: with triangles in index
// order the first of equal depths wins, as in render_cpu) on the sample's
// depth and hit.
inline void test_pass_sample(const K::MovingTriangle& tri, const K::ScreenBound& bound, K::vec2 ndc, K::vec2 lens,
                             double time, double near, std::uint32_t triangle, Counters& local, double& depth,
                             std::uint32_t& hit) {
    double z = 0.0;
    const int verdict = K::sample_test(tri, bound, true, K::no_sample_bounds(), ndc, lens, time, near, z);
    if (verdict == BC_SAMPLE_CULLED) return;
    ++local.tested;
    if (verdict != BC_SAMPLE_COVERED) return;
    ++local.hit;
    if (K::depth_nearer(z, depth)) {
        depth = z;
        hit = triangle;
    }
}

// The common end of every renderer here: resolve the per-sample hits into the
// image, record the resolve's time, the counters, the plan's warnings and the
// total time; hand the hits to sample_ids when given.
void finish_render(RenderResult& result, const Scene& scene, const MethodPlan& plan, std::vector<std::uint32_t>& hits,
                   const Counters& counters, int width, int height, Clock::time_point start,
                   std::vector<std::uint32_t>* sample_ids);

}  // namespace blurcull::frontend::cpu_methods
