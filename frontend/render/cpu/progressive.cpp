#include "render/cpu/progressive.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace blurcull::frontend {

ProgressiveRender::ProgressiveRender(Scene scene, const RenderSettings& settings, const CpuOptions& options)
    : scene_(std::move(scene)), settings_(settings), options_(options) {
    validate_settings(settings_);
    settings_.progress = false;  // a pass is short; the caller shows its own progress
    sums_.reset(settings_.width, settings_.height);
}

const RenderResult& ProgressiveRender::next_pass(int count) {
    if (broken_) throw std::logic_error("progressive render: a pass was cancelled or failed; start a new one");
    if (done()) throw std::logic_error("progressive render: all " + std::to_string(target()) + " spp are drawn");
    if (count < 1) throw std::invalid_argument("progressive render: a pass needs at least 1 sample");
    CpuOptions pass = options_;
    pass.sums = &sums_;
    pass.pass_samples = std::min(count, target() - samples());
    broken_ = true;  // until the pass returns
    RenderResult rendered = render_cpu(scene_, settings_, pass);
    broken_ = false;
    scene_.validated = true;  // render_cpu checked it; the next passes need not
    result_.stats.add(rendered.stats);
    result_.image = std::move(rendered.image);
    if (result_.warnings.empty()) result_.warnings = std::move(rendered.warnings);  // the same every pass
    return result_;
}

int next_pass_samples(int samples, int target, double ms_per_sample, double budget_ms) {
    const int left = target - samples;
    if (left <= 0) return 0;
    int count = std::max(1, samples);
    if (ms_per_sample > 0.0 && budget_ms > 0.0) {
        const double affordable = std::floor(budget_ms / ms_per_sample);
        if (affordable < static_cast<double>(count)) count = std::max(1, static_cast<int>(affordable));
    }
    return std::min(count, left);
}

}  // namespace blurcull::frontend
