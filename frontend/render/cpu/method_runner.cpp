#include "render/cpu/method_runner.hpp"

#include <algorithm>
#include <atomic>
#include <thread>
#include <utility>

namespace blurcull::frontend::cpu_methods {
namespace {

int thread_count(const RenderSettings& settings, int items) {
    const int threads =
        settings.threads > 0 ? settings.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    return std::max(1, std::min(threads, items));
}

void store_counters(RenderStats& stats, const Counters& counters) {
    stats.samples_tested = counters.tested;
    stats.samples_hit = counters.hit;
    stats.bounds_computed = counters.bounded;
    stats.bounds_empty = counters.bounded_empty;
}

}  // namespace


Counters run_items(const RenderSettings& settings, int items, const std::function<void(int, Counters&)>& work) {
    std::atomic<int> next{0};
    std::atomic<std::uint64_t> tested{0}, hit{0}, bounded{0}, bounded_empty{0};
    auto worker = [&]() {
        Counters local;
        for (int item = next.fetch_add(1); item < items; item = next.fetch_add(1)) work(item, local);
        tested.fetch_add(local.tested);
        hit.fetch_add(local.hit);
        bounded.fetch_add(local.bounded);
        bounded_empty.fetch_add(local.bounded_empty);
    };
    std::vector<std::thread> helpers;
    try {
        for (int i = 1; i < thread_count(settings, items); ++i) helpers.emplace_back(worker);
    } catch (...) {
        next.store(items);
        for (std::thread& helper : helpers) helper.join();
        throw;
    }
    worker();
    for (std::thread& helper : helpers) helper.join();
    return Counters{tested.load(), hit.load(), bounded.load(), bounded_empty.load()};
}

void finish_render(RenderResult& result, const Scene& scene, const MethodPlan& plan, std::vector<std::uint32_t>& hits,
                   const Counters& counters, int width, int height, Clock::time_point start,
                   std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point phase = Clock::now();
    result.image = resolve_method_samples(scene, plan, hits, width, height);
    result.stats.ms_per_phase.emplace_back("resolve", ms_since(phase));
    store_counters(result.stats, counters);
    result.warnings = plan.warnings;
    if (sample_ids != nullptr) *sample_ids = std::move(hits);
    result.stats.ms_total = ms_since(start);
}

}  // namespace blurcull::frontend::cpu_methods
