// The CPU tile rasterizer's per-sample chain over runs of a tile's samples:
// a footprint's samples (in rows, or the run of its time-sorted copy inside
// the bounds' shutter interval, less the shutter pieces whose planes cull
// it whole), 32 lanes at a time through the culls (render/cpu/sample_chain),
// the motion-segment window, the fast coverage test, and the exact test
// (TileHits).
#pragma once

#include "render/cpu/fast_coverage.hpp"
#include "render/cpu/footprint_bounds.hpp"
#include "render/cpu/frame_context.hpp"
#include "render/cpu/sample_chain.hpp"
#include "render/cpu/tile_hits.hpp"
#include "render/cpu/tile_samples.hpp"

#include <blurcull/kernel.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace blurcull::frontend::cpu_tiles {

template <class Real>
class SampleRuns {
public:
    using K = blurcull::kernel<Real>;
    using Triangle = TileTriangle<K>;

    SampleRuns(const FrameContext<Real>& frame, const TileSamples<Real>& samples, const FootprintBounds<Real>& bounds,
               TileHits<Real>& hits)
        : frame_(frame), samples_(samples), bounds_(bounds), hits_(hits) {}

    // Tests a footprint's samples that may pass `sb`.
    void test_footprint(Triangle& current, int px0, int py0, int px1, int py1, const typename K::SampleBounds& sb) {
        // The screen bound per footprint first: skip it whole, or spare its
        // samples the per-sample screen test.
        const typename K::vec4 box = bounds_.footprint(px0, py0, px1, py1);
        const int state =
            K::screen_footprint(*current.bound, typename K::vec2(box.x, box.y), typename K::vec2(box.z, box.w));
        if (state == BC_FOOTPRINT_OUTSIDE) return;
        if (bounds_.planes_cull_footprint(sb, px0, py0, px1, py1)) return;
        current.check_screen = state != BC_FOOTPRINT_INSIDE;
        if (frame_.time_sorted && current.needs_bounds && test_time_run(current, px0, py0, px1, py1, sb)) return;
        for (int py = py0; py <= py1; ++py) {
            const std::size_t first = samples_.slot(px0, py, 0);
            test_run(current, sb, samples_.lanes(), first, static_cast<std::size_t>(px1 - px0 + 1) * frame_.spp,
                     [](std::size_t k) { return k; });
        }
    }

    // Samples first .. first + count - 1 of `lanes` (slot_of(i) the slot of
    // its sample i), 32 at a time: the culls (samples_passing, the kernel's
    // chain), the fast test on those that passed, covers on what it kept.
    template <class SlotOf>
    void test_run(const Triangle& current, const typename K::SampleBounds& sb, const SampleLanes& lanes,
                  std::size_t first, std::size_t count, SlotOf slot_of) {
        visited += count;
        for (std::size_t done = 0; done < count; done += 32) {
            const std::size_t at = first + done;
            const int n = static_cast<int>(std::min<std::size_t>(32, count - done));
            std::uint32_t passed =
                current.needs_bounds ? samples_passing<Real>(*current.bound, current.check_screen, sb, lanes, at, n)
                                     : samples_passing_screen<Real>(*current.bound, current.check_screen, lanes, at, n);
            if (samples_.segmented()) {
                // Another motion segment's time: culled.
                for (std::uint32_t bits = passed; bits != 0; bits &= bits - 1) {
                    const std::uint32_t i = static_cast<std::uint32_t>(__builtin_ctz(bits));
                    if (!samples_.in_window(slot_of(at + i))) passed &= ~(1u << i);
                }
            }
            if (passed == 0) continue;
            tested += bit_count(passed);
            const std::uint32_t kept = may_cover32(*current.fast, lanes.fsx() + at, lanes.fsy() + at, lanes.fu() + at,
                                                   lanes.fv() + at, lanes.ft() + at, passed);
            for (std::uint32_t maybe = passed & kept; maybe != 0; maybe &= maybe - 1)
                hits_.test_exactly(current, slot_of(at + static_cast<std::size_t>(__builtin_ctz(maybe))));
        }
    }

    // Samples that went through the culls (visited) and the exact tests run (tested).
    std::uint64_t visited = 0, tested = 0;

private:
    // The footprint's samples inside the bounds' shutter interval, one
    // contiguous run of its time-sorted copy, when that visits fewer samples
    // than the footprint's rows (false: not worth it, nothing done). The run
    // spans the whole footprint cell of the tile's grid; where the triangle's
    // rectangle clips the cell, the screen test is kept on: the cell's
    // pixels outside the rectangle hold no sample inside the screen bound.
    bool test_time_run(Triangle& current, int px0, int py0, int px1, int py1, const typename K::SampleBounds& sb) {
        typename K::vec2 range = K::sample_time_range(sb);
        // A motion segment's bounds are in its local time: back to shutter
        // time, inside its window (in float, the samples' precision).
        if (samples_.segmented())
            range = typename K::vec2(kernelf::segment_shutter_range(samples_.window(), glm::vec2(range)));
        const int fp = frame_.footprint, x0 = samples_.x0(), y0 = samples_.y0();
        const int fx = (px0 - x0) / fp, fy = (py0 - y0) / fp;
        const int cx0 = x0 + fx * fp, cy0 = y0 + fy * fp;
        const int cx1 = std::min(samples_.x1(), cx0 + fp - 1), cy1 = std::min(samples_.y1(), cy0 + fp - 1);
        const double cell_pixels = double((cx1 - cx0 + 1) * (cy1 - cy0 + 1));
        const double pixels = double((px1 - px0 + 1) * (py1 - py0 + 1));
        const double share = std::max(0.0, double(range.y) - double(range.x));
        if (!(share * cell_pixels < pixels)) return false;
        const double* times = samples_.times();
        const double* begin = samples_.footprint_times_begin(fx, fy);
        const double* end = samples_.footprint_times_end(fx, fy);
        const double* lo = std::lower_bound(begin, end, double(range.x));
        const double* hi = std::upper_bound(lo, end, double(range.y));
        current.check_screen = current.check_screen || cx0 != px0 || cy0 != py0 || cx1 != px1 || cy1 != py1;
        const auto slot_of = [this](std::size_t i) { return samples_.time_slot(i); };
        const SampleLanes& lanes = samples_.time_lanes();
        // Planes: the runs of the shutter pieces whose planes cull the whole
        // footprint are skipped (not visited).
        const int pieces = K::plane_pieces(sb);
        if (pieces > 0 && !samples_.segmented()) {
            const typename K::vec4 pad_box = bounds_.padded_footprint(px0, py0, px1, py1);
            const typename K::vec2 s_lo(pad_box.x, pad_box.y), s_hi(pad_box.z, pad_box.w);
            for (int q = 0; q < pieces; ++q) {
                if (!K::plane_piece_culls_box(sb, q, s_lo, s_hi)) continue;
                // The piece's samples: after the previous piece's end (which
                // holds its own end), up to its own end.
                const typename K::vec2 piece_time = K::plane_piece_time(sb, q);
                const double* from = q == 0 ? std::lower_bound(lo, hi, double(piece_time.x))
                                            : std::upper_bound(lo, hi, double(piece_time.x));
                const double* to = std::max(from, std::upper_bound(lo, hi, double(piece_time.y)));
                test_run(current, sb, lanes, static_cast<std::size_t>(lo - times), static_cast<std::size_t>(from - lo),
                         slot_of);
                lo = to;
            }
        }
        test_run(current, sb, lanes, static_cast<std::size_t>(lo - times), static_cast<std::size_t>(hi - lo), slot_of);
        return true;
    }

    const FrameContext<Real>& frame_;
    const TileSamples<Real>& samples_;
    const FootprintBounds<Real>& bounds_;
    TileHits<Real>& hits_;
};

}  // namespace blurcull::frontend::cpu_tiles
