#include "app/view_progressive.hpp"

#include "render/cpu/cpu_backend.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <utility>

namespace blurcull::frontend {
namespace {

using Clock = std::chrono::steady_clock;

// CPU time of the whole process so far, every thread, in milliseconds.
double process_cpu_ms() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

// Wall and CPU time since it was made.
struct PassTimer {
    Clock::time_point wall = Clock::now();
    double cpu = process_cpu_ms();
    double wall_ms() const { return std::chrono::duration<double, std::milli>(Clock::now() - wall).count(); }
    double cpu_ms() const { return process_cpu_ms() - cpu; }
};

}  // namespace

int next_preview_scale(int scale, double preview_ms, double budget_ms) {
    if (preview_ms > budget_ms) return std::min(scale + 1, max_preview_scale);
    if (scale > 1) {
        const double ratio = static_cast<double>(scale) / static_cast<double>(scale - 1);
        if (preview_ms * ratio * ratio < 0.8 * budget_ms) return scale - 1;
    }
    return std::max(scale, 1);
}

Image enlarge_nearest(const Image& image, int width, int height) {
    Image large(width, height);
    const bool coverage = !image.coverage.empty();
    if (coverage) large.coverage.resize(large.pixels.size());
    for (int y = 0; y < height; ++y) {
        const int sy = std::min(y * image.height / height, image.height - 1);
        for (int x = 0; x < width; ++x) {
            const int sx = std::min(x * image.width / width, image.width - 1);
            large.at(x, y) = image.at(sx, sy);
            if (coverage) large.coverage[large.index(x, y)] = image.coverage[image.index(sx, sy)];
        }
    }
    return large;
}

ProgressiveView::ProgressiveView(std::function<void()> wake, double pass_budget_ms)
    : wake_(std::move(wake)), pass_budget_ms_(pass_budget_ms), worker_([this] { run(); }) {}

ProgressiveView::~ProgressiveView() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        cancel_ = true;
    }
    wanted_.notify_one();
    worker_.join();
}

std::uint64_t ProgressiveView::submit(Scene scene, const RenderSettings& settings) {
    std::uint64_t id = 0;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        id = ++submitted_;
        pending_ = Job{id, std::move(scene), settings};
        if (cancellable_) cancel_ = true;
    }
    wanted_.notify_one();
    return id;
}

std::optional<ViewFrame> ProgressiveView::take() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    return std::exchange(latest_, std::nullopt);
}

void ProgressiveView::run() {
    for (;;) {
        Job job;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wanted_.wait(lock, [this] { return stop_ || pending_.has_value(); });
            if (stop_) return;
            job = std::move(*pending_);
            pending_.reset();
            cancel_ = false;
            cancellable_ = false;
        }
        try {
            render_job(job);
        } catch (const RenderCancelled&) {
            // A newer job (or the end) is waiting.
        } catch (...) {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                error_ = std::current_exception();
            }
            wake_();
        }
    }
}

// The preview first when a full-size pass is too slow for the budget; then
// the accumulation, one pass at a time, each one shown.
void ProgressiveView::render_job(Job& job) {
    int pass = 0;
    const int scale = preview_scale_.load();
    if (scale > 1) {
        render_preview(job, scale);
        pass = 1;
        first_image_done();
    }
    CpuOptions options;
    options.cancel = &cancel_;
    ProgressiveRender render(std::move(job.scene), job.settings, options);
    double ms_per_sample = 0.0;
    while (!render.done() && !cancelled()) {
        const int count = next_pass_samples(render.samples(), render.target(), ms_per_sample, pass_budget_ms_);
        const PassTimer timer;
        const RenderResult& result = render.next_pass(count);
        ViewFrame frame;
        frame.job = job.id;
        frame.pass = ++pass;
        frame.image = result.image;
        frame.stats = result.stats;
        frame.warnings = result.warnings;
        frame.samples = render.samples();
        frame.target = render.target();
        frame.cull = job.settings.cull;
        frame.pass_ms = timer.wall_ms();
        frame.pass_cpu_ms = timer.cpu_ms();
        ms_per_sample = frame.pass_ms / count;
        if (pass == 1) preview_scale_ = next_preview_scale(1, frame.pass_ms);
        publish(std::move(frame));
        if (pass == 1) first_image_done();
    }
}

// A 1-spp render at 1/scale of the size, enlarged: outside the accumulation.
void ProgressiveView::render_preview(Job& job, int scale) {
    RenderSettings small = job.settings;
    small.width = std::max(1, static_cast<int>(std::lround(job.settings.width / static_cast<double>(scale))));
    small.height = std::max(1, static_cast<int>(std::lround(job.settings.height / static_cast<double>(scale))));
    small.spp = 1;
    small.cull = preview_cull;
    small.progress = false;
    CpuOptions options;
    options.cancel = &cancel_;
    const PassTimer timer;
    RenderResult result = render_cpu(job.scene, small, options);
    job.scene.validated = true;  // render_cpu checked it
    ViewFrame frame;
    frame.job = job.id;
    frame.pass = 1;
    frame.image = enlarge_nearest(result.image, job.settings.width, job.settings.height);
    frame.stats = result.stats;
    frame.warnings = std::move(result.warnings);
    frame.samples = 1;
    frame.target = job.settings.spp;
    frame.preview_scale = scale;
    frame.cull = small.cull;
    frame.pass_ms = timer.wall_ms();
    frame.pass_cpu_ms = timer.cpu_ms();
    preview_scale_ = next_preview_scale(scale, frame.pass_ms);
    publish(std::move(frame));
}

void ProgressiveView::publish(ViewFrame frame) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        latest_ = std::move(frame);
    }
    wake_();
}

// From here a newer job cancels this one's passes.
void ProgressiveView::first_image_done() {
    std::lock_guard<std::mutex> lock(mutex_);
    cancellable_ = true;
    if (pending_) cancel_ = true;
}

}  // namespace blurcull::frontend
