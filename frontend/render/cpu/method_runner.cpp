#include "render/cpu/method_runner.hpp"

#include "render/common/parallel_items.hpp"

#include <atomic>
#include <utility>

namespace blurcull::frontend::cpu_methods {
namespace {

void store_counters(RenderStats& stats, const Counters& counters) {
    stats.samples_tested = counters.tested;
    stats.samples_hit = counters.hit;
    stats.bounds_computed = counters.bounded;
    stats.bounds_empty = counters.bounded_empty;
}

MethodPlan plan_for(const Scene& scene, const RenderSettings& settings, RenderMethod method,
                    const InterleaveOptions& options) {
    RenderSettings method_settings = settings;
    method_settings.method = method;
    return make_method_plan(scene, method_settings, options);
}

}  // namespace

Counters run_items(const RenderSettings& settings, int items, const std::function<void(int, Counters&)>& work) {
    std::atomic<std::uint64_t> tested{0}, hit{0}, bounded{0}, bounded_empty{0};
    run_parallel_items(
        render_threads(settings), items, [] { return Counters{}; },
        [&](Counters& local, int item) { work(item, local); },
        [&](const Counters& local) {
            tested.fetch_add(local.tested);
            hit.fetch_add(local.hit);
            bounded.fetch_add(local.bounded);
            bounded_empty.fetch_add(local.bounded_empty);
        });
    return Counters{tested.load(), hit.load(), bounded.load(), bounded_empty.load()};
}

MethodRender::MethodRender(const Scene& scene, const RenderSettings& settings, RenderMethod method,
                           const InterleaveOptions& options)
    : scene_(scene),
      settings_(settings),
      start_(Clock::now()),
      phase_(start_),
      plan_(plan_for(scene, settings, method, options)) {
    result_.stats.triangles = scene.triangles.size();
}

Counters MethodRender::run_raster(int items, const std::function<void(int, Counters&)>& work) {
    result_.stats.ms_per_phase.emplace_back("setup", ms_since(phase_));
    phase_ = Clock::now();
    Progress progress(settings_.progress, start_, items);
    const Counters counters = run_items(settings_, items, [&](int item, Counters& local) {
        work(item, local);
        progress.advance();
    });
    progress.finish();
    result_.stats.ms_per_phase.emplace_back("raster", ms_since(phase_));
    return counters;
}

RenderResult MethodRender::finish(std::vector<std::uint32_t>& hits, const Counters& counters,
                                  std::vector<std::uint32_t>* sample_ids) {
    phase_ = Clock::now();
    result_.image = resolve_method_samples(scene_, plan_, hits, settings_.width, settings_.height);
    result_.stats.ms_per_phase.emplace_back("resolve", ms_since(phase_));
    store_counters(result_.stats, counters);
    result_.warnings = plan_.warnings;
    if (sample_ids != nullptr) *sample_ids = std::move(hits);
    result_.stats.ms_total = ms_since(start_);
    return std::move(result_);
}

}  // namespace blurcull::frontend::cpu_methods
