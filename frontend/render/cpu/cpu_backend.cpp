#include "render/cpu/cpu_backend.hpp"

#include "render/common/camera_model.hpp"
#include "render/common/method_plan.hpp"
#include "render/common/progress.hpp"
#include "render/common/surface_shading.hpp"
#include "render/cpu/frame_context.hpp"
#include "render/cpu/frame_setup.hpp"
#include "render/common/parallel_items.hpp"
#include "render/cpu/tile_rasterizer.hpp"
#include "scene/scene_checks.hpp"

#include <blurcull/kernel.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace blurcull::frontend {
namespace {

using namespace cpu_tiles;

// The CPU path runs the kernel in double by default: its bounds are then
// conservative against the very oracle that decides coverage (the property
// tests prove it for double against double), so every culling method gives
// the same image. CpuOptions::precision float runs kernel<float>, the GL
// backend's arithmetic, to compare decisions with it.
using Clock = std::chrono::steady_clock;

// Rasterization: tiles are handed out dynamically; within a tile the
// triangles run nearest first, and the depth rule (nearest, then lowest
// index) makes the result independent of that order and of the schedule.
// The workers' summed time in the raster and the resolve steps of their tiles.
struct RasterSplit {
    double raster_seconds, resolve_seconds;
};

template <class Real>
RasterSplit rasterize_tiles(const FrameContext<Real>& frame, int threads, Clock::time_point start,
                            RenderResult& result) {
    std::atomic<std::uint64_t> total_tested{0}, total_hit{0}, total_bounded{0}, total_bounded_empty{0},
        total_visited{0}, total_occluded{0};
    std::mutex seconds_lock;
    double raster_seconds = 0.0, resolve_seconds = 0.0;
    const int tile_count = frame.setup.tiles_x * frame.setup.tiles_y;
    Progress progress(frame.settings.progress, start, tile_count);
    run_parallel_items(
        threads, tile_count, [&] { return TileRasterizer<Real>(frame); },
        [&](TileRasterizer<Real>& rasterizer, int tile) {
            if (frame.cancel != nullptr && frame.cancel->load(std::memory_order_relaxed)) return;
            rasterizer.render_tile(tile, result.image);
            progress.advance();
        },
        [&](const TileRasterizer<Real>& rasterizer) {
            total_tested.fetch_add(rasterizer.tested());
            total_hit.fetch_add(rasterizer.hits());
            total_bounded.fetch_add(rasterizer.bounded());
            total_bounded_empty.fetch_add(rasterizer.bounded_empty());
            total_visited.fetch_add(rasterizer.visited());
            total_occluded.fetch_add(rasterizer.occluded);
            const std::lock_guard<std::mutex> lock(seconds_lock);
            raster_seconds += rasterizer.raster_seconds;
            resolve_seconds += rasterizer.resolve_seconds;
        });
    progress.finish();
    if (frame.cancel != nullptr && frame.cancel->load()) throw RenderCancelled();
    RenderStats& stats = result.stats;
    stats.samples_tested = total_tested.load();
    stats.samples_hit = total_hit.load();
    stats.bounds_computed = total_bounded.load();
    stats.bounds_empty = total_bounded_empty.load();
    stats.samples_visited = total_visited.load();
    if (frame.occlusion) stats.counters.emplace_back("samples_occluded", double(total_occluded.load()));
    return RasterSplit{raster_seconds, resolve_seconds};
}

template <class Real>
RenderResult render_cpu_in(const Scene& scene, const RenderSettings& settings, const CpuOptions& options,
                           std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point start = Clock::now();
    const CameraModel model(scene.camera, settings.width, settings.height);
    const CullMethodInfo& cull = cull_method_info(settings.cull);
    const int footprint = options.footprint;
    // Blocks: the coarser level of the footprint hierarchy, a multiple of the footprint.
    const int block = options.block > footprint ? options.block - options.block % footprint : footprint;
    // Only the per-footprint methods bound lens and time; a static, in-focus
    // triangle has neither to bound, whatever the method.
    const bool cull_bounds = cull.bounds_samples;
    const int threads = render_threads(settings);

    RenderResult result;
    result.stats.triangles = scene.triangles.size();

    // Setup: clip-space triangles, their screen rectangles, binned into tiles.
    Clock::time_point phase = Clock::now();
    const SurfaceShader shader(scene, model, threads);
    FrameSetup<Real> setup;
    // Strata only where no per-footprint bound culls lens and time (bbox, hull).
    const SampleStrata strata = cull_bounds ? SampleStrata{} : SampleStrata{options.time_strata, options.lens_strata};
    set_up_triangles(scene, model, cull.kernel_method, threads, strata, setup);
    if (setup.invalid > 0) {
        result.warnings.push_back("cpu: skipped " + std::to_string(setup.invalid) +
                                  " triangles whose clip coordinates overflow");
    }
    result.stats.ms_per_phase.emplace_back("setup", ms_since(phase));
    phase = Clock::now();
    bin_triangles(settings.width, settings.height, setup);
    result.stats.ms_per_phase.emplace_back("binning", ms_since(phase));

    phase = Clock::now();
    result.image = Image(settings.width, settings.height);
    result.image.coverage.resize(result.image.pixels.size());
    const FrameContext<Real> frame{scene,
                                   settings,
                                   model,
                                   setup,
                                   shader,
                                   cull.kernel_method,
                                   blurcull::kernel<Real>::cull_traits(cull.kernel_method),
                                   static_cast<Real>(model.znear),
                                   static_cast<std::uint32_t>(options.sums != nullptr ? options.pass_samples
                                                                                      : settings.spp),
                                   footprint,
                                   block,
                                   cull_bounds,
                                   // Footprints that tile the work tiles get their samples sorted by time.
                                   cull_bounds && footprint <= tile_size && tile_size % footprint == 0,
                                   sample_ids,
                                   options.sums,
                                   options.sums != nullptr ? static_cast<std::uint32_t>(options.sums->samples) : 0u,
                                   options.cancel,
                                   double(options.edge_min_samples),
                                   options.occlusion};
    if (sample_ids != nullptr)
        sample_ids->assign(static_cast<std::size_t>(settings.width) * settings.height * frame.spp, no_sample_hit);
    const RasterSplit split = rasterize_tiles(frame, threads, start, result);
    if (options.sums != nullptr) options.sums->samples += options.pass_samples;
    // The tiles' phase in wall time, split into raster and resolve by the
    // workers' shares of their time (the two interleave tile by tile).
    const double tiles_ms = ms_since(phase), worker_seconds = split.raster_seconds + split.resolve_seconds;
    const double resolve_share = worker_seconds > 0.0 ? split.resolve_seconds / worker_seconds : 0.0;
    result.stats.ms_per_phase.emplace_back("raster", tiles_ms * (1.0 - resolve_share));
    result.stats.ms_per_phase.emplace_back("resolve", tiles_ms * resolve_share);
    result.stats.ms_total = ms_since(start);
    return result;
}

// A progressive pass must continue sums of this image size and fit in settings.spp.
void validate_pass(const RenderSettings& settings, const SampleSums& sums, int pass_samples) {
    const std::size_t pixels = static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height);
    if (sums.colour.size() != pixels || sums.covered.size() != pixels)
        throw std::invalid_argument("cpu: the progressive sums are not of a " + std::to_string(settings.width) + "x" +
                                    std::to_string(settings.height) + " image");
    if (pass_samples < 1 || sums.samples < 0 || sums.samples > settings.spp - pass_samples)
        throw std::invalid_argument("cpu: a progressive pass of " + std::to_string(pass_samples) +
                                    " samples after " + std::to_string(sums.samples) + " does not fit in " +
                                    std::to_string(settings.spp) + " spp");
}

}  // namespace

RenderResult render_cpu(const Scene& scene, const RenderSettings& settings, const CpuOptions& options,
                        std::vector<std::uint32_t>* sample_ids) {
    validate_settings(settings);
    require_valid_scene(scene);
    if (options.footprint < 1) throw std::invalid_argument("cpu: footprint must be >= 1 pixel");
    if (options.block < 0) throw std::invalid_argument("cpu: block must be >= 0 pixels");
    auto power_of_two = [](int n, int most) { return n >= 1 && n <= most && (n & (n - 1)) == 0; };
    if (!power_of_two(options.time_strata, 16) || !power_of_two(options.lens_strata, 4))
        throw std::invalid_argument("cpu: time strata must be 1, 2, 4, 8 or 16 and lens strata 1, 2 or 4 (got " +
                                    std::to_string(options.time_strata) + " and " +
                                    std::to_string(options.lens_strata) + ")");
    if (options.sums != nullptr) validate_pass(settings, *options.sums, options.pass_samples);
    switch (options.precision) {
    case KernelPrecision::float32:
        return render_cpu_in<float>(scene, settings, options, sample_ids);
    case KernelPrecision::float64:
        return render_cpu_in<double>(scene, settings, options, sample_ids);
    }
    throw std::invalid_argument("cpu: unknown kernel precision");
}

}  // namespace blurcull::frontend
