// One worker's rasterization of work tiles (docs/cpu-renderer.md): a tile is
// loaded (TileSamples: its samples, sorted by time per footprint when that
// pays), its binned triangles rasterized nearest first, block by block and
// footprint by footprint (FootprintBounds: the cull's lens and time bounds)
// or stratum by stratum with the occlusion test, their samples tested in
// runs (SampleRuns) with the depth rule (TileHits), and resolved into the
// image (TileHits::resolve). This class only walks the levels; each part
// does one job.
#pragma once

#include "render/common/image.hpp"
#include "render/cpu/footprint_bounds.hpp"
#include "render/cpu/frame_context.hpp"
#include "render/cpu/sample_runs.hpp"
#include "render/cpu/tile_hits.hpp"
#include "render/cpu/tile_samples.hpp"

#include <blurcull/kernel.hpp>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>

namespace blurcull::frontend::cpu_tiles {

template <class Real>
class TileRasterizer {
public:
    using K = blurcull::kernel<Real>;
    using Triangle = TileTriangle<K>;
    using Clock = std::chrono::steady_clock;

    explicit TileRasterizer(const FrameContext<Real>& frame)
        : frame_(frame), samples_(frame), hits_(frame, samples_), bounds_(frame), runs_(frame, samples_, bounds_, hits_) {}
    // The parts hold references to each other.
    TileRasterizer(const TileRasterizer&) = delete;
    TileRasterizer& operator=(const TileRasterizer&) = delete;

    // Rasterizes work tile `tile` (row-major over the tiles) into its pixels of `image`.
    void render_tile(int tile, Image& image) {
        const Clock::time_point started = Clock::now();
        samples_.load(tile % frame_.setup.tiles_x, tile / frame_.setup.tiles_x);
        hits_.clear();
        for (std::uint32_t index : frame_.setup.bins[static_cast<std::size_t>(tile)]) {
            const SegmentPiece& piece = frame_.setup.pieces[index];
            if (samples_.window_differs(piece)) samples_.enter_window(piece);
            rasterize_triangle(index);
        }
        const Clock::time_point rasterized = Clock::now();
        hits_.resolve(image);
        const Clock::time_point resolved = Clock::now();
        raster_seconds += std::chrono::duration<double>(rasterized - started).count();
        resolve_seconds += std::chrono::duration<double>(resolved - rasterized).count();
    }

    // This worker's counts: exact tests, hits, sample bounds set up, and empty ones, samples visited.
    std::uint64_t tested() const { return runs_.tested; }
    std::uint64_t hits() const { return hits_.hits; }
    std::uint64_t bounded() const { return bounds_.bounded; }
    std::uint64_t bounded_empty() const { return bounds_.bounded_empty; }
    std::uint64_t visited() const { return runs_.visited; }
    std::uint64_t occluded = 0;  // samples skipped by the occlusion test (CpuOptions::occlusion)
    // This worker's time in its tiles' raster (samples, triangles) and resolve steps.
    double raster_seconds = 0.0, resolve_seconds = 0.0;

private:
    // Blocks of the image grid clipped to the triangle's rectangle; the
    // bounds hold for any footprint. A block whose bounds hold nothing is
    // skipped whole; the others are bounded again per footprint when
    // footprints are smaller than blocks (with planes: the footprint's
    // bounds with the block's planes, set up once per block).
    void rasterize_triangle(std::uint32_t index) {
        const PixelRect& r = frame_.setup.rects[index];
        frame_.setup.screen_bound(index, bound_);
        Triangle current{index, &frame_.setup.triangles[index], &frame_.setup.fast_tests[index], &bound_,
                         frame_.cull_bounds && frame_.setup.classes[index] != 0, true, false};
        const int rx0 = std::max(r.x0, samples_.x0()), rx1 = std::min(r.x1, samples_.x1());
        const int ry0 = std::max(r.y0, samples_.y0()), ry1 = std::min(r.y1, samples_.y1());
        bounds_.begin_triangle(current, rx0, ry0, rx1, ry1);
        // bbox, hull: a moving or defocused triangle stratum by stratum (the
        // setup gives strata only to one-segment pieces, whose samples keep
        // their shutter times).
        if (const StratumBox<K>* boxes = frame_.setup.stratum_boxes[index]) {
            rasterize_by_strata(current, boxes);
            hits_.flush_exact(current);
            return;
        }
        const int block = frame_.block, footprint = frame_.footprint;
        for (int by = ry0 - (ry0 % block); by <= ry1; by += block) {
            for (int bx = rx0 - (rx0 % block); bx <= rx1; bx += block) {
                const int bx0 = std::max(bx, rx0), bx1 = std::min(bx + block - 1, rx1);
                const int by0 = std::max(by, ry0), by1 = std::min(by + block - 1, ry1);
                if (!current.needs_bounds) {
                    runs_.test_footprint(current, bx0, by0, bx1, by1, K::no_sample_bounds());
                    continue;
                }
                const auto plan = bounds_.block(current, bx0, by0, bx1, by1);
                if (plan == FootprintBounds<Real>::Block::skip) continue;
                if (plan == FootprintBounds<Real>::Block::whole) {
                    runs_.test_footprint(current, bx0, by0, bx1, by1, bounds_.block_bounds());
                    continue;
                }
                for (int fy = by0 - (by0 % footprint); fy <= by1; fy += footprint) {
                    for (int fx = bx0 - (bx0 % footprint); fx <= bx1; fx += footprint) {
                        const int px0 = std::max(fx, bx0), px1 = std::min(fx + footprint - 1, bx1);
                        const int py0 = std::max(fy, by0), py1 = std::min(fy + footprint - 1, by1);
                        const typename K::SampleBounds sb = bounds_.footprint_in_block(current, px0, py0, px1, py1);
                        if (!sb.empty) runs_.test_footprint(current, px0, py0, px1, py1, sb);
                    }
                }
            }
        }
        hits_.flush_exact(current);
    }

    // A moving or defocused triangle under bbox or hull, stratum by stratum:
    // each stratum's samples only in the pixels of its screen box (the
    // setup's stratum_boxes), through test_run with the stratum's box as the
    // screen bound, skipping the pixels (rows, the tile) whose samples of
    // the stratum all hold a depth below the triangle's depth floor. Its
    // per-sample test runs only with a hull (hull): for bbox the box chose
    // the pixels, and the few samples per pixel it would cull cost more to
    // test than the fast test spends on them.
    void rasterize_by_strata(const Triangle& current, const StratumBox<K>* strata) {
        if (!samples_.strata_grouped()) {  // once per tile, when a triangle first needs it
            samples_.group_by_stratum();
            hits_.track_strata();
        }
        // No lens or time bounds here (bbox, hull): test_run's chain is the screen test alone.
        static const typename K::SampleBounds no_bounds = K::no_sample_bounds();
        const auto slot_of = [this](std::size_t q) { return samples_.strata_slot(q); };
        const SampleLanes& lanes = samples_.strata_lanes();
        FarthestDepths<Real>& farthest = hits_.farthest();
        const int tx0 = samples_.x0(), ty0 = samples_.y0();
        Triangle stratum = current;
        stratum.check_screen = bound_.hull_count > 0;
        stratum_bound_.empty = false;
        stratum_bound_.hull_count = bound_.hull_count;
        for (int e = 0; e < bound_.hull_count; ++e) stratum_bound_.hull_edge[e] = bound_.hull_edge[e];
        stratum.bound = &stratum_bound_;
        for (int s = 0; s < frame_.setup.strata.count(); ++s) {
            const PixelRect& r = strata[s].rect;
            const int x0 = std::max(r.x0, tx0), x1 = std::min(r.x1, samples_.x1());
            const int y0 = std::max(r.y0, ty0), y1 = std::min(r.y1, samples_.y1());
            if (x0 > x1 || y0 > y1) continue;
            stratum_bound_.lo = typename K::vec2(strata[s].box.x, strata[s].box.y);
            stratum_bound_.hi = typename K::vec2(strata[s].box.z, strata[s].box.w);
            // Occlusion off: a floor no stored depth is below.
            const Real floor = frame_.occlusion ? strata[s].depth_floor : Real(0);
            const bool occludable = floor > Real(0);
            // Every sample of the stratum's rectangle is nearer than the
            // triangle can be: nothing to test.
            if (occludable && farthest.tile(s) < floor) {
                for (int py = y0; py <= y1; ++py) occluded += samples_.stratum_run(s, py, x0, x1 + 1).second;
                continue;
            }
            for (int py = y0; py <= y1; ++py) {
                if (!occludable) {
                    const auto [first, count] = samples_.stratum_run(s, py, x0, x1 + 1);
                    runs_.test_run(stratum, no_bounds, lanes, first, count, slot_of);
                    continue;
                }
                const std::size_t ly = static_cast<std::size_t>(py - ty0);
                if (farthest.row(s, ly) < floor) {
                    occluded += samples_.stratum_run(s, py, x0, x1 + 1).second;
                    continue;
                }
                // Runs of pixels whose samples of this stratum are not all
                // nearer than the triangle can be.
                const auto hidden = [&](int px) {
                    return farthest.pixel(s, static_cast<std::size_t>(px - tx0), ly) < floor;
                };
                int px = x0;
                while (px <= x1) {
                    const int hidden_from = px;
                    while (px <= x1 && hidden(px)) ++px;
                    occluded += samples_.stratum_run(s, py, hidden_from, px).second;
                    if (px > x1) break;
                    const int run_start = px;
                    while (px <= x1 && !hidden(px)) ++px;
                    const auto [first, count] = samples_.stratum_run(s, py, run_start, px);
                    runs_.test_run(stratum, no_bounds, lanes, first, count, slot_of);
                }
            }
        }
    }

    const FrameContext<Real>& frame_;
    TileSamples<Real> samples_;
    TileHits<Real> hits_;
    FootprintBounds<Real> bounds_;
    SampleRuns<Real> runs_;
    typename K::ScreenBound bound_{}, stratum_bound_{};  // the current triangle's, and its stratum's
};

}  // namespace blurcull::frontend::cpu_tiles
