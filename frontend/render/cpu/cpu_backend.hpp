// The CPU reference rasterizer: exact stochastic rasterization with a
// per-sample z-buffer, culling by the kernel (docs/cpu-renderer.md).
#pragma once

#include "render/common/kernel_precision.hpp"
#include "render/common/render_types.hpp"
#include "scene/scene.hpp"

#include <glm/vec3.hpp>

#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace blurcull::frontend {

// Progressive rendering (render/cpu/progressive.hpp): the running per-pixel
// sums of the samples drawn so far, the pattern's samples 0 .. samples-1 of
// settings.spp. A pass adds its samples to them in index order, which is the
// order of a one-shot render's sums, so the pass that reaches settings.spp
// gives render_cpu's one-shot image bit for bit.
struct SampleSums {
    int samples = 0;                  // per pixel, summed so far
    std::vector<glm::vec3> colour;    // width * height, row-major: colour sums
    std::vector<std::uint32_t> covered;  // width * height: samples that hit a triangle

    // Empty sums for a width x height image.
    void reset(int width, int height) {
        samples = 0;
        colour.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), glm::vec3(0.0f));
        covered.assign(colour.size(), 0);
    }
};

// Thrown by render_cpu when CpuOptions::cancel became true during the render.
struct RenderCancelled : std::runtime_error {
    RenderCancelled() : std::runtime_error("cpu: render cancelled") {}
};

struct CpuOptions {
    // Side, in pixels, of the screen footprint the per-footprint sample bounds
    // (dualspace, twostage) are computed for: 1 = per pixel; larger amortises
    // their setup over more samples at the price of looser bounds.
    int footprint = 4;
    // Side, in pixels, of the blocks bounded first: a block whose bounds hold
    // nothing is skipped without bounding its footprints. <= footprint: off.
    // A block is what the kernel calls a tile (sample_bounds_in_tile); the
    // CPU's "work tile" is the binning unit (render/cpu/frame_context.hpp).
    int block = 16;
    // kernel<double> (default) or kernel<float>. In float every culling
    // method is still conservative against the double oracle (property
    // tests), and the decisions are those the GL backend makes.
    KernelPrecision precision = KernelPrecision::float64;
    // Progressive rendering: when set, the render draws only the pattern's
    // samples sums->samples .. sums->samples + pass_samples - 1 (of
    // settings.spp), adds them to *sums (sums->samples grows by
    // pass_samples) and returns the image of every sample summed so far.
    SampleSums* sums = nullptr;
    int pass_samples = 0;  // >= 1 with sums; ignored without
    // When set, checked before each work tile: once true, render_cpu throws
    // RenderCancelled (and *sums is left part-updated: reset it).
    const std::atomic<bool>* cancel = nullptr;
    // edges: a block gets the edge planes (their setup, about 5,000 to 9,000
    // instructions more than clip2's) only where its two-stage bounds leave
    // at least this many samples to visit; the other blocks are culled as
    // with clip2. 0: planes on every block. The default is the break-even of
    // docs/benchmarks.md ("edges' CPU time"): about 18 instructions saved per
    // visited sample against the planes' setup.
    int edge_min_samples = 512;
    // Strata of shutter and lens for the methods without per-footprint
    // bounds (bbox, hull): each work tile keeps its samples grouped by
    // stratum (time_strata equal slices of the shutter by lens_strata equal
    // parts of u and of v), and a moving or defocused triangle's samples of a
    // stratum are tested only in the pixels of that stratum's screen box
    // (kernel stratum_screen_box). Powers of two (the strata's ends are
    // then exact); 1 and 1: off.
    int time_strata = 4;
    int lens_strata = 1;
    // Occlusion culling on the strata (bbox, hull): a stratum's samples of a
    // pixel are skipped when every one of them already holds a depth below
    // the kernel's depth_floor of the triangle, so the strict depth test
    // would fail on each (the triangles go nearest first within each tile).
    // The image is the same; stats.samples_hit then counts the covered
    // samples among those tested, not every covered sample.
    bool occlusion = true;
};

// Renders with settings.spp samples per pixel, sample j of pixel (px, py)
// taken from patternsf::sampler_sample (settings.sampler's pattern) — the samples every
// backend uses. Culling only skips samples the exact test would reject, so the
// image is the same for every settings.cull (tests/test_frontend_cpu.cpp).
// stats.samples_tested counts the exact tests run (samples that passed the
// cull), stats.samples_hit those that found coverage (with
// options.occlusion, not those skipped as occluded). Deterministic whatever
// the thread count. With options.sums, one pass of a progressive render
// (SampleSums above); sample_ids then hold the pass's samples only. Throws
// std::invalid_argument for bad settings and
// SceneError for a bad scene. Triangles it skips are in result.warnings.
RenderResult render_cpu(const Scene& scene, const RenderSettings& settings, const CpuOptions& options = {},
                        std::vector<std::uint32_t>* sample_ids = nullptr);

}  // namespace blurcull::frontend
