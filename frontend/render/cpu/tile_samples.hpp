// A work tile's stochastic samples for the CPU tile rasterizer: loaded from
// the settings' sampler once per tile, as lanes (render/cpu/sample_chain.hpp)
// in slot order, and the orders the culls visit them in: per footprint by
// time (time_lanes), by stratum of shutter and lens (strata_lanes), and seen
// through a motion-segment window (local times, in_window).
#pragma once

#include "render/common/pixel_samples.hpp"
#include "render/cpu/frame_context.hpp"
#include "render/cpu/sample_chain.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace blurcull::frontend::cpu_tiles {

template <class Real>
class TileSamples {
public:
    explicit TileSamples(const FrameContext<Real>& frame)
        : frame_(frame),
          sample_count_(static_cast<std::size_t>(tile_size) * tile_size * frame.spp),
          by_time_(sample_count_),
          by_time_t_(sample_count_),
          lanes_(sample_count_),
          time_lanes_(sample_count_),
          shutter_time_(sample_count_),
          in_window_(sample_count_),
          pixel_samples_(frame.spp),
          strata_lanes_(frame.setup.strata.count() > 1 ? sample_count_ : 0),
          strata_slot_(frame.setup.strata.count() > 1 ? sample_count_ : 0),
          stratum_(frame.setup.strata.count() > 1 ? sample_count_ : 0) {}

    // Loads work tile (tx, ty): its samples in the whole-shutter window, and
    // (time_sorted) each footprint's sorted by time.
    void load(int tx, int ty) {
        window_segment_ = 0;
        window_segments_ = 1;
        window_ = glm::vec2(0.0f, 1.0f);
        x0_ = tx * tile_size;
        y0_ = ty * tile_size;
        x1_ = std::min(x0_ + tile_size, frame_.settings.width) - 1;
        y1_ = std::min(y0_ + tile_size, frame_.settings.height) - 1;
        tw_ = x1_ - x0_ + 1;
        load_samples();
        strata_grouped_ = false;
        footprints_x_ = (tw_ + frame_.footprint - 1) / frame_.footprint;
        if (frame_.time_sorted) sort_footprints_by_time();
    }

    // The tile's pixels, inclusive, and its width.
    int x0() const { return x0_; }
    int y0() const { return y0_; }
    int x1() const { return x1_; }
    int y1() const { return y1_; }
    int width() const { return tw_; }
    std::size_t pixels() const { return static_cast<std::size_t>(tw_) * static_cast<std::size_t>(y1_ - y0_ + 1); }
    // Samples of a whole tile (what the buffers hold).
    std::size_t capacity() const { return sample_count_; }

    // Slot of sample j of pixel (px, py): pixels row-major, then index.
    std::size_t slot(int px, int py, std::uint32_t j) const {
        return (static_cast<std::size_t>(py - y0_) * tw_ + (px - x0_)) * frame_.spp + j;
    }

    // The samples in slot order; lens and time as the current window sees them.
    const SampleLanes& lanes() const { return lanes_; }
    // Each sample's own shutter time (lanes() hold the window's local time).
    float shutter_time(std::size_t k) const { return shutter_time_[k]; }
    // Its screen position and lens position as the shader takes them (floats).
    glm::vec2 ndc_of(std::size_t k) const { return glm::vec2(lanes_.fsx()[k], lanes_.fsy()[k]); }
    glm::vec2 lens_of(std::size_t k) const { return glm::vec2(lanes_.fu()[k], lanes_.fv()[k]); }

    // ---- motion-segment windows -------------------------------------------

    // Whether the samples are seen through another window than piece's.
    bool window_differs(const SegmentPiece& piece) const {
        return piece.segment != window_segment_ || piece.segments != window_segments_;
    }
    // More than one segment: the samples' times are a window's local times.
    bool segmented() const { return window_segments_ > 1; }
    glm::vec2 window() const { return window_; }
    // Whether the current window holds sample k (its shutter time).
    bool in_window(std::size_t k) const { return in_window_[k] != 0; }

    // Motion segments: the tile's samples as seen by the pieces of one window,
    // each at its local time (kernel::segment_local_time, in float like the
    // samples, so the fast test sees the time covers() sees), and marked when
    // the window does not hold it. The footprints' time order (by_time_t_)
    // stays in shutter time: the runs map a piece's bounds back to it.
    void enter_window(const SegmentPiece& piece) {
        window_segment_ = piece.segment;
        window_segments_ = piece.segments;
        window_ = kernelf::segment_window(piece.segment, piece.segments);
        for (std::size_t k = 0; k < sample_count_; ++k) {
            const float local = kernelf::segment_local_time(window_, shutter_time_[k]);
            in_window_[k] = kernelf::segment_holds(window_, shutter_time_[k]) ? 1 : 0;
            lanes_.set_time(k, local);
        }
        if (frame_.time_sorted)
            for (std::size_t q = 0; q < by_time_.size(); ++q) time_lanes_.set_time(q, lanes_.ft()[by_time_[q]]);
    }

    // ---- per footprint by time (time_sorted) ---------------------------------

    // The samples per footprint of the tile's grid sorted by time, and the
    // slot of each.
    const SampleLanes& time_lanes() const { return time_lanes_; }
    std::size_t time_slot(std::size_t i) const { return static_cast<std::size_t>(by_time_[i]); }
    // Footprint cell (fx, fy)'s shutter times, sorted (its run of time_lanes()
    // from the pointer's offset to times()).
    const double* times() const { return by_time_t_.data(); }
    const double* footprint_times_begin(int fx, int fy) const {
        return by_time_t_.data() + footprint_start_[footprint_cell(fx, fy)];
    }
    const double* footprint_times_end(int fx, int fy) const {
        return by_time_t_.data() + footprint_start_[footprint_cell(fx, fy) + 1];
    }

    // ---- by stratum (bbox, hull) ---------------------------------------------

    // Whether group_by_stratum ran for this tile.
    bool strata_grouped() const { return strata_grouped_; }
    // The tile's samples by stratum, then pixel (row-major), then index:
    // copied into strata_lanes_ (slots in strata_slot_), stratum s's samples
    // of pixel p from strata_start_[s * pixels + p] (a counting sort).
    void group_by_stratum() {
        const SampleStrata& strata = frame_.setup.strata;
        const std::size_t pixels = this->pixels();
        const std::size_t count = pixels * frame_.spp;
        strata_start_.assign(static_cast<std::size_t>(strata.count()) * pixels + 1, 0);
        for (std::size_t k = 0; k < count; ++k) {
            stratum_[k] = static_cast<std::uint8_t>(strata.of(lanes_.fu()[k], lanes_.fv()[k], lanes_.ft()[k]));
            ++strata_start_[static_cast<std::size_t>(stratum_[k]) * pixels + k / frame_.spp + 1];
        }
        for (std::size_t i = 1; i < strata_start_.size(); ++i) strata_start_[i] += strata_start_[i - 1];
        std::vector<std::uint32_t>& next = strata_next_;
        next.assign(strata_start_.begin(), strata_start_.end() - 1);
        for (std::size_t k = 0; k < count; ++k) {
            const std::uint32_t q = next[static_cast<std::size_t>(stratum_[k]) * pixels + k / frame_.spp]++;
            strata_lanes_.copy(q, lanes_, k);
            strata_slot_[q] = static_cast<std::uint32_t>(k);
        }
        strata_grouped_ = true;
    }
    const SampleLanes& strata_lanes() const { return strata_lanes_; }
    std::size_t strata_slot(std::size_t q) const { return static_cast<std::size_t>(strata_slot_[q]); }
    const std::uint32_t* strata_slots() const { return strata_slot_.data(); }
    const std::uint32_t* strata_starts() const { return strata_start_.data(); }
    std::uint8_t stratum(std::size_t k) const { return stratum_[k]; }
    // Stratum s's samples of pixels [from, to) of tile row py: one contiguous
    // run of strata_lanes() (first, count).
    std::pair<std::uint32_t, std::uint32_t> stratum_run(int s, int py, int from, int to) const {
        const std::size_t row = static_cast<std::size_t>(s) * pixels() +
                                static_cast<std::size_t>(py - y0_) * static_cast<std::size_t>(tw_) -
                                static_cast<std::size_t>(x0_);
        const std::uint32_t first = strata_start_[row + static_cast<std::size_t>(from)];
        return {first, strata_start_[row + static_cast<std::size_t>(to)] - first};
    }

private:
    // The tile's samples (the settings' sampler's).
    void load_samples() {
        for (int py = y0_; py <= y1_; ++py) {
            for (int px = x0_; px <= x1_; ++px) {
                const patternsf::SamplerSetup pattern = patternsf::sampler_setup(
                    frame_.settings.sampler, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py),
                    static_cast<std::uint32_t>(frame_.settings.spp), frame_.settings.seed);
                pixel_samples(pattern, frame_.first_sample, frame_.spp, pixel_samples_.data(),
                              lens_samples_for(frame_.model.lens_radius));
                for (std::uint32_t j = 0; j < frame_.spp; ++j) {
                    const kernelf::PixelSample& s = pixel_samples_[j];
                    const std::size_t k = slot(px, py, j);
                    const glm::vec2 ndc = frame_.model.sample_ndc(px, py, s.offset);
                    lanes_.set(k, ndc.x, ndc.y, s.lens.x, s.lens.y, s.time);
                    shutter_time_[k] = s.time;
                    in_window_[k] = 1;
                }
            }
        }
    }

    // Per footprint of the tile's grid, its samples sorted by time (copied
    // into time_lanes_, slots in by_time_), so that a footprint's bounds
    // visit only the contiguous run of their shutter interval.
    void sort_footprints_by_time() {
        const int footprint = frame_.footprint;
        const int th = y1_ - y0_ + 1;
        const int footprints_y = (th + footprint - 1) / footprint;
        footprint_start_.assign(static_cast<std::size_t>(footprints_x_) * footprints_y + 1, 0);
        std::size_t next = 0;
        for (int fy = 0; fy < footprints_y; ++fy) {
            for (int fx = 0; fx < footprints_x_; ++fx) {
                const std::size_t first = next;
                footprint_start_[static_cast<std::size_t>(fy) * footprints_x_ + fx] = first;
                for (int py = y0_ + fy * footprint; py <= std::min(y1_, y0_ + fy * footprint + footprint - 1); ++py)
                    for (int px = x0_ + fx * footprint; px <= std::min(x1_, x0_ + fx * footprint + footprint - 1); ++px)
                        for (std::uint32_t j = 0; j < frame_.spp; ++j)
                            by_time_[next++] = static_cast<std::uint32_t>(slot(px, py, j));
                std::sort(by_time_.begin() + static_cast<std::ptrdiff_t>(first),
                          by_time_.begin() + static_cast<std::ptrdiff_t>(next),
                          [&](std::uint32_t a, std::uint32_t b) { return lanes_.ft()[a] < lanes_.ft()[b]; });
                for (std::size_t q = first; q < next; ++q) {
                    time_lanes_.copy(q, lanes_, by_time_[q]);
                    by_time_t_[q] = shutter_time_[by_time_[q]];
                }
            }
        }
        footprint_start_.back() = next;
    }

    std::size_t footprint_cell(int fx, int fy) const {
        return static_cast<std::size_t>(fy) * footprints_x_ + static_cast<std::size_t>(fx);
    }

    const FrameContext<Real>& frame_;
    std::size_t sample_count_;            // samples of a whole tile
    std::vector<std::uint32_t> by_time_;  // slot of each time_lanes_ sample
    std::vector<double> by_time_t_;       // its shutter time (the sort key)
    std::vector<std::size_t> footprint_start_;
    SampleLanes lanes_;                // the tile's samples, in slot order
    SampleLanes time_lanes_;           // the same, per footprint sorted by time (time_sorted)
    std::vector<float> shutter_time_;  // each sample's own time (lanes_ hold the window's local time)
    std::vector<char> in_window_;      // whether the current motion-segment window holds the sample
    std::vector<kernelf::PixelSample> pixel_samples_;  // load_samples' scratch: one pixel's samples
    SampleLanes strata_lanes_;                 // lanes_ grouped by stratum (group_by_stratum)
    std::vector<std::uint32_t> strata_slot_;   // slot of each strata_lanes_ sample
    std::vector<std::uint8_t> stratum_;        // stratum of each slot
    std::vector<std::uint32_t> strata_start_;  // first strata_lanes_ sample of each (stratum, pixel)
    std::vector<std::uint32_t> strata_next_;   // group_by_stratum's scratch
    bool strata_grouped_ = false;              // strata_lanes_ hold this tile's samples
    int window_segment_ = 0, window_segments_ = 1;  // the window lanes_ are loaded for
    glm::vec2 window_{0.0f, 1.0f};
    int x0_ = 0, y0_ = 0, x1_ = -1, y1_ = -1, tw_ = 0, footprints_x_ = 0;
};

}  // namespace blurcull::frontend::cpu_tiles
