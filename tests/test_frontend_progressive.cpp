// Progressive rendering on the CPU backend (render/cpu/progressive.hpp):
// passes over consecutive sample indices of one spp pattern, added to running
// sums, give the one-shot render_cpu image bit for bit however the passes
// split the samples; a cancelled pass throws and ends the render; bad sums are
// refused in one line; the pass schedule doubles within its time budget.
#include "frontend_test_helpers.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/cpu/progressive.hpp"
#include "scene/builtin_scenes.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;

namespace {

// The progressive render of `settings.spp` samples in passes of `passes`
// samples each (their sum is the spp).
RenderResult render_in_passes(const Scene& scene, const RenderSettings& settings, const std::vector<int>& passes,
                              const CpuOptions& options = {}) {
    ProgressiveRender render(scene, settings, options);
    for (int count : passes) render.next_pass(count);
    REQUIRE(render.done());
    return render.result();
}

bool same_coverage(const Image& a, const Image& b) { return a.coverage == b.coverage; }

// The counter `name` of `stats`, or -1 when it has none of that name.
double counter(const RenderStats& stats, const std::string& name) {
    for (const auto& [counter_name, value] : stats.counters)
        if (counter_name == name) return value;
    return -1.0;
}

// One-shot against progressive in each split of `splits`, pixels, coverage and counts.
void check_splits(const Scene& scene, const RenderSettings& settings, const CpuOptions& options,
                  const std::vector<std::vector<int>>& splits) {
    const RenderResult one_shot = render_cpu(scene, settings, options);
    for (const std::vector<int>& passes : splits) {
        INFO(scene.name << ", cull " << to_string(settings.cull) << ", " << to_string(options.precision) << ", "
                        << passes.size() << " passes");
        const RenderResult progressive = render_in_passes(scene, settings, passes, options);
        CHECK(same_pixels(progressive.image, one_shot.image));
        CHECK(same_coverage(progressive.image, one_shot.image));
        // Occlusion culling skips what a pass's own earlier triangles hide,
        // so its counts depend on the split; without it they add up.
        if (!options.occlusion) {
            CHECK(progressive.stats.samples_hit == one_shot.stats.samples_hit);
            CHECK(progressive.stats.samples_tested == one_shot.stats.samples_tested);
        }
    }
}

}  // namespace

TEST_CASE("passes accumulated give the one-shot image bit for bit, on every built-in scene and split") {
    const int width = 48, height = 36;
    std::vector<std::vector<int>> splits_16 = {std::vector<int>(16, 1), {1, 1, 2, 4, 8}, {5, 11},
                                                {3, 3, 3, 3, 3, 1}};
    // A scaled-down run (CI's sanitizer pass): two splits, no forest.
    const bool scaled_down = blurcull::testing::property_scale() < 1.0;
    if (scaled_down) splits_16 = {{1, 1, 2, 4, 8}, {5, 11}};
    // Every split, both culls and precisions on the two small scenes; the
    // view's schedule on the two large ones (the forest's 168k triangles are
    // set up again in every pass).
    for (const std::string name : {"hand", "car", "dragonfly", "forest"}) {
        if (scaled_down && std::string(name) == "forest") continue;
        const Scene scene = small_scene(name, width, height);
        const bool small = name == "hand" || name == "car";
        for (CullMethod cull : {CullMethod::two_stage, CullMethod::bbox}) {
            for (KernelPrecision precision : {KernelPrecision::float64, KernelPrecision::float32}) {
                if (!small && (cull != CullMethod::two_stage || precision != KernelPrecision::float64)) continue;
                RenderSettings settings = quiet_settings(width, height, 16);
                settings.cull = cull;
                CpuOptions options;
                options.precision = precision;
                // Occlusion culling works on bbox's strata only.
                for (bool occlusion : {false, true}) {
                    if (occlusion && cull != CullMethod::bbox) continue;
                    options.occlusion = occlusion;
                    check_splits(scene, settings, options,
                                 small ? splits_16 : std::vector<std::vector<int>>{{1, 1, 2, 4, 8}});
                }
            }
        }
    }
}

TEST_CASE("passes accumulated give the one-shot image for an spp that is not a square, and another seed") {
    RenderSettings settings = quiet_settings(48, 36, 7);
    settings.seed = 12345;
    check_splits(small_scene("car", 48, 36), settings, {}, {{1, 2, 4}});
}

TEST_CASE("the image after some passes is the mean of the pattern's first samples, however they were split") {
    const Scene scene = small_scene("hand", 40, 30);
    const RenderSettings settings = quiet_settings(40, 30, 16);
    ProgressiveRender split(scene, settings), whole(scene, settings);
    split.next_pass(1);
    split.next_pass(1);
    split.next_pass(2);
    whole.next_pass(4);
    CHECK(split.samples() == 4);
    CHECK(!split.done());
    CHECK(same_pixels(split.result().image, whole.result().image));
    // The first 4 of 16 are not the 4-spp pattern (strata of 16): a
    // different image, not a copy of one.
    const RenderResult four = render_cpu(scene, quiet_settings(40, 30, 4));
    CHECK(!same_pixels(split.result().image, four.image));
    // A pass asking for more than is left draws what is left.
    split.next_pass(100);
    CHECK(split.done());
    CHECK(same_pixels(split.result().image, render_cpu(scene, settings).image));
    CHECK_THROWS_AS(split.next_pass(1), std::logic_error);
}

TEST_CASE("a cancelled pass throws RenderCancelled and the render cannot go on") {
    const Scene scene = small_scene("hand", 40, 30);
    std::atomic<bool> cancel{false};
    CpuOptions options;
    options.cancel = &cancel;
    ProgressiveRender render(scene, quiet_settings(40, 30, 8), options);
    render.next_pass(1);
    cancel = true;
    CHECK_THROWS_AS(render.next_pass(1), RenderCancelled);
    cancel = false;
    CHECK_THROWS_AS(render.next_pass(1), std::logic_error);
    // A one-shot render too.
    cancel = true;
    CHECK_THROWS_AS(render_cpu(scene, quiet_settings(40, 30, 2), options), RenderCancelled);
}

TEST_CASE("render_cpu refuses progressive sums that do not fit, in one line") {
    const Scene scene = small_scene("hand", 16, 12);
    const RenderSettings settings = quiet_settings(16, 12, 4);
    SampleSums sums;
    CpuOptions options;
    options.sums = &sums;
    options.pass_samples = 1;
    sums.reset(8, 8);
    CHECK_THROWS_WITH_AS(render_cpu(scene, settings, options), "cpu: the progressive sums are not of a 16x12 image",
                         std::invalid_argument);
    sums.reset(16, 12);
    sums.samples = 3;
    options.pass_samples = 2;
    CHECK_THROWS_WITH_AS(render_cpu(scene, settings, options),
                         "cpu: a progressive pass of 2 samples after 3 does not fit in 4 spp", std::invalid_argument);
    options.pass_samples = 0;
    CHECK_THROWS_AS(render_cpu(scene, settings, options), std::invalid_argument);
    options.pass_samples = 1;
    render_cpu(scene, settings, options);
    CHECK(sums.samples == 4);
}

TEST_CASE("the pass schedule doubles the samples within the time budget") {
    // No time known: 1, 1, 2, 4, 8 for 16.
    std::vector<int> passes;
    for (int samples = 0; samples < 16;) {
        passes.push_back(next_pass_samples(samples, 16, 0.0, 500.0));
        samples += passes.back();
    }
    CHECK(passes == std::vector<int>{1, 1, 2, 4, 8});
    // The last pass is what is left.
    CHECK(next_pass_samples(12, 16, 0.0, 500.0) == 4);
    CHECK(next_pass_samples(16, 16, 0.0, 500.0) == 0);
    // 100 ms a sample and 500 ms of budget: at most 5.
    CHECK(next_pass_samples(8, 32, 100.0, 500.0) == 5);
    // Slower than the budget: still one sample.
    CHECK(next_pass_samples(8, 32, 900.0, 500.0) == 1);
}

TEST_CASE("a progressive render's statistics are its passes' summed, the occlusion counter included") {
    // The car on bbox: occlusion culling (on by default) skips samples its
    // own nearer triangles already hide.
    const int width = 48, height = 36, spp = 16;
    const Scene scene = small_scene("car", width, height);
    RenderSettings settings = quiet_settings(width, height, spp);
    settings.cull = CullMethod::bbox;
    const CpuOptions options;
    REQUIRE(options.occlusion);
    // Each pass drawn again on its own (render_cpu on sums of its own, as the
    // progressive render draws it): the render's totals are their sums.
    ProgressiveRender progressive(scene, settings, options);
    SampleSums sums;
    sums.reset(width, height);
    double occluded = 0.0;
    std::uint64_t tested = 0, hit = 0, visited = 0, bounded = 0;
    for (int count : {1, 1, 2, 4, 8}) {
        CpuOptions pass = options;
        pass.sums = &sums;
        pass.pass_samples = count;
        const RenderResult alone = render_cpu(scene, settings, pass);
        REQUIRE(counter(alone.stats, "samples_occluded") >= 0.0);
        occluded += counter(alone.stats, "samples_occluded");
        tested += alone.stats.samples_tested;
        hit += alone.stats.samples_hit;
        visited += alone.stats.samples_visited;
        bounded += alone.stats.bounds_computed;
        const RenderStats& total = progressive.next_pass(count).stats;
        INFO("after " << progressive.samples() << " spp");
        CHECK(counter(total, "samples_occluded") == occluded);
        CHECK(total.samples_tested == tested);
        CHECK(total.samples_hit == hit);
        CHECK(total.samples_visited == visited);
        CHECK(total.bounds_computed == bounded);
        CHECK(total.counters.size() == alone.stats.counters.size());
    }
    // Not vacuous: the later passes' skipped samples are counted too.
    CHECK(occluded > counter(ProgressiveRender(scene, settings, options).next_pass(1).stats, "samples_occluded"));
    // One pass of every sample does the one-shot render's work, counters included.
    ProgressiveRender whole(scene, settings, options);
    const RenderStats& one_pass = whole.next_pass(spp).stats;
    const RenderResult one_shot = render_cpu(scene, settings, options);
    CHECK(counter(one_shot.stats, "samples_occluded") > 0.0);
    CHECK(one_pass.counters == one_shot.stats.counters);
    CHECK(one_pass.samples_tested == one_shot.stats.samples_tested);
    CHECK(one_pass.samples_hit == one_shot.stats.samples_hit);
}

TEST_CASE("RenderStats::add sums every count, and the phases and counters by name") {
    RenderStats a;
    a.samples_tested = 10;
    a.samples_hit = 4;
    a.samples_visited = 20;
    a.bounds_computed = 3;
    a.bounds_empty = 1;
    a.secondary_rays = 7;
    a.ms_total = 1.5;
    a.ms_per_phase = {{"setup", 1.0}, {"raster", 0.5}};
    a.counters = {{"samples_occluded", 5.0}};
    a.triangles = 100;
    RenderStats b;
    b.samples_tested = 1;
    b.samples_hit = 2;
    b.samples_visited = 3;
    b.bounds_computed = 4;
    b.bounds_empty = 5;
    b.secondary_rays = 6;
    b.ms_total = 0.25;
    b.ms_per_phase = {{"raster", 2.0}, {"resolve", 0.125}};
    b.counters = {{"clusters", 2.0}, {"samples_occluded", 1.0}};
    b.triangles = 50;
    a.add(b);
    CHECK(a.samples_tested == 11);
    CHECK(a.samples_hit == 6);
    CHECK(a.samples_visited == 23);
    CHECK(a.bounds_computed == 7);
    CHECK(a.bounds_empty == 6);
    CHECK(a.secondary_rays == 13);
    CHECK(a.ms_total == 1.75);
    using Named = std::vector<std::pair<std::string, double>>;
    CHECK(a.ms_per_phase == Named{{"setup", 1.0}, {"raster", 2.5}, {"resolve", 0.125}});
    CHECK(a.counters == Named{{"samples_occluded", 6.0}, {"clusters", 2.0}});
    CHECK(a.triangles == 100);  // the scene's size, not summed
    // Into empty statistics: a copy.
    RenderStats empty;
    empty.add(b);
    CHECK(empty.counters == b.counters);
    CHECK(empty.ms_per_phase == b.ms_per_phase);
    CHECK(empty.triangles == 50);
}
