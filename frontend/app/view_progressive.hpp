// `blurcull view` on the CPU backend: a worker thread renders the posed
// scene progressively (render/cpu/progressive.hpp) while the window stays
// responsive. A job's first image is a 1-spp preview (at a reduced
// resolution when a full-resolution pass would miss the frame-rate budget);
// then passes over the next sample indices of the target spp's pattern are
// accumulated into the same image until the target is reached, which is the
// one-shot `render --backend cpu` image bit for bit. A new job (the camera or
// a setting changed) cancels the accumulation at the next tile and starts
// again. docs/view-cpu.md.
#pragma once

#include "render/common/image.hpp"
#include "render/common/render_types.hpp"
#include "render/cpu/progressive.hpp"
#include "scene/scene.hpp"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace blurcull::frontend {

// One image the worker finished: a job's preview or its accumulation so far.
struct ViewFrame {
    std::uint64_t job = 0;     // the submit() it belongs to
    int pass = 0;              // 1: the job's first image
    Image image;               // the settings' size (a scaled preview is enlarged to it)
    RenderStats stats;         // the accumulation's, summed over its passes (a scaled preview: its own)
    std::vector<std::string> warnings;
    int samples = 0;           // spp in the image
    int target = 0;            // the settings' spp
    int preview_scale = 1;     // > 1: a preview at 1/preview_scale of the size, outside the accumulation
    CullMethod cull = CullMethod::bbox;  // what drew it: the settings', or a preview's preview_cull
    double pass_ms = 0.0;      // wall time of the pass
    double pass_cpu_ms = 0.0;  // CPU time of the process during the pass, every thread

    // The accumulation reached the target spp: the final image of the job.
    bool converged() const { return preview_scale == 1 && samples >= target; }
};

// The frame-rate budget of a preview: 10 frames per second.
inline constexpr double preview_budget_ms = 100.0;
// The largest preview reduction (1/4 of the width and height).
inline constexpr int max_preview_scale = 4;
// A scaled preview's cull method: every method gives the same image, and at
// 1 spp on a small image the per-triangle setup dominates, which bbox keeps
// cheapest (docs/view-cpu.md has the times).
inline constexpr CullMethod preview_cull = CullMethod::bbox;

// The preview scale for the next job, from the last preview's: one step
// coarser when it took longer than the budget, one step finer when the finer
// one would still fit in 80% of it (time growing with the pixel count).
int next_preview_scale(int scale, double preview_ms, double budget_ms = preview_budget_ms);

// `image` enlarged to width x height, each pixel repeated (nearest), with
// its coverage.
Image enlarge_nearest(const Image& image, int width, int height);

class ProgressiveView {
public:
    // `wake` is called on the worker thread after each finished frame (the
    // window's glfwPostEmptyEvent, which GLFW allows from any thread).
    // `pass_budget_ms`: a pass after the first draws as many samples as fit
    // in it (next_pass_samples).
    explicit ProgressiveView(std::function<void()> wake, double pass_budget_ms = 500.0);
    ProgressiveView(const ProgressiveView&) = delete;
    ProgressiveView& operator=(const ProgressiveView&) = delete;
    // Cancels the running pass and joins the worker.
    ~ProgressiveView();

    // Starts a new job for this scene and settings (settings.spp the target)
    // and returns its number. The running job stops: at the next tile when it
    // is accumulating; a job's first image is always finished, so that a
    // stream of changes (a drag) still shows one frame per preview.
    std::uint64_t submit(Scene scene, const RenderSettings& settings);

    // The newest frame not yet taken (older ones were dropped), if any.
    // Rethrows, on the caller's thread, what the worker's render threw.
    std::optional<ViewFrame> take();

    // The scale the next job's preview will have (1: its first pass is the
    // accumulation's, at full size).
    int preview_scale() const { return preview_scale_.load(); }

private:
    struct Job {
        std::uint64_t id = 0;
        Scene scene;
        RenderSettings settings;
    };

    void run();
    void render_job(Job& job);
    void render_preview(Job& job, int scale);
    void publish(ViewFrame frame);
    bool cancelled() { return cancel_.load(); }
    void first_image_done();

    std::function<void()> wake_;
    double pass_budget_ms_;
    std::mutex mutex_;
    std::condition_variable wanted_;
    std::optional<Job> pending_;
    std::optional<ViewFrame> latest_;
    std::exception_ptr error_;
    std::uint64_t submitted_ = 0;
    bool stop_ = false;
    bool cancellable_ = false;  // the running job is past its first image
    std::atomic<bool> cancel_{false};
    std::atomic<int> preview_scale_{1};
    std::thread worker_;  // last: starts once everything above is made
};

}  // namespace blurcull::frontend
