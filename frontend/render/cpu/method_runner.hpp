// What the CPU renderers of interleave, interval and accum share besides their
// MethodPlan: running work items on the settings' threads with per-thread
// counters, the strict depth test, and the common end of a render.
#pragma once

#include "render/common/render_types.hpp"
#include "render/cpu/method_plan.hpp"
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

// Milliseconds from `start` to now.
double ms_since(Clock::time_point start);

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

// Depth test of one covered sample: strict, so with triangles in index order
// the first of equal depths wins, as in render_cpu.
inline void depth_test(double z, std::uint32_t triangle, double& depth, std::uint32_t& hit) {
    if (z < depth) {
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
