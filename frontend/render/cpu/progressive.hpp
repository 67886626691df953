// Progressive rendering on the CPU backend: one image of settings.spp
// samples per pixel built in passes, each pass drawing the next run of the
// same pattern's sample indices and adding them to running sums
// (CpuOptions::sums). After k passes the image is that of the first
// samples() indices; once they reach settings.spp it equals the one-shot
// render_cpu image bit for bit (tests/test_frontend_progressive.cpp).
// `blurcull view` on the CPU backend shows it (docs/view-cpu.md).
#pragma once

#include "render/cpu/cpu_backend.hpp"
#include "scene/scene.hpp"

namespace blurcull::frontend {

class ProgressiveRender {
public:
    // Nothing is rendered yet; settings.spp is the target. options.sums and
    // pass_samples are the class's own (ignored); options.cancel is used.
    // Throws std::invalid_argument for bad settings.
    ProgressiveRender(Scene scene, const RenderSettings& settings, const CpuOptions& options = {});

    int samples() const { return sums_.samples; }  // per pixel, so far
    int target() const { return settings_.spp; }
    bool done() const { return samples() >= target(); }

    // Renders the next min(count, what is left) samples per pixel (count >=
    // 1) and returns the image of every sample so far, with the statistics
    // summed over the passes (RenderStats::add: counts, counters such as
    // samples_occluded, ms_total and ms_per_phase). Throws std::logic_error when done(), RenderCancelled when
    // the cancel flag was set (the render cannot go on after that), and what
    // render_cpu throws.
    const RenderResult& next_pass(int count);

    // The image and statistics so far (empty before the first pass).
    const RenderResult& result() const { return result_; }

private:
    Scene scene_;
    RenderSettings settings_;
    CpuOptions options_;
    SampleSums sums_;
    RenderResult result_;
    bool broken_ = false;  // a pass was cancelled or failed: the sums are part-updated
};

// How many samples the next pass of a progressive render draws: as many as
// it has (so the count doubles), at most what `budget_ms` allows at
// `ms_per_sample` (the last pass's time per sample; <= 0: unknown), at least
// 1, at most what is left of `target`. Keeps a pass short enough to show
// progress often and the count growing so that per-pass setup stays a small
// share.
int next_pass_samples(int samples, int target, double ms_per_sample, double budget_ms);

}  // namespace blurcull::frontend
