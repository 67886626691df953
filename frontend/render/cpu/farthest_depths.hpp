// The occlusion test's hierarchical depths for one work tile of the CPU
// backend (docs/cpu-renderer.md, "Occlusion culling"): per stratum of the
// shutter and lens, the farthest depth its samples hold in each pixel, in
// each row of the tile and in the whole tile (infinite while one sample is
// uncovered). A triangle whose proven depth floor is beyond a row's (or the
// tile's) farthest depth cannot win any of its samples there, so the row (or
// the tile) is skipped in one comparison instead of one per pixel.
//
// Each level is recomputed lazily: a hit that changes a sample's depth marks
// its pixel, row and tile due, and a due value is recomputed when next asked
// for. Depths only decrease, so a value not yet recomputed is never below
// the true one: the test stays conservative in between.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace blurcull::frontend {

template <class Real>
class FarthestDepths {
public:
    // A tile of width x height pixels and `strata` strata, whose samples of
    // stratum s in pixel p (index s * width * height + y * width + x) are
    // slot[start[p]] .. slot[start[p + 1] - 1] of `depth`. Everything is due.
    void reset(int strata, int width, int height, const std::uint32_t* start, const std::uint32_t* slot,
               const Real* depth) {
        width_ = static_cast<std::size_t>(width);
        height_ = static_cast<std::size_t>(height);
        start_ = start;
        slot_ = slot;
        depth_ = depth;
        const std::size_t count = static_cast<std::size_t>(strata);
        pixel_.assign(count * width_ * height_, Real(0));
        pixel_due_.assign(pixel_.size(), 1);
        row_.assign(count * height_, Real(0));
        row_due_.assign(row_.size(), 1);
        tile_.assign(count, Real(0));
        tile_due_.assign(count, 1);
    }

    // A sample of stratum s in pixel (x, y) of the tile changed its depth.
    void changed(int s, std::size_t x, std::size_t y) {
        const std::size_t row = static_cast<std::size_t>(s) * height_ + y;
        pixel_due_[row * width_ + x] = 1;
        row_due_[row] = 1;
        tile_due_[static_cast<std::size_t>(s)] = 1;
    }

    // The farthest depth of stratum s's samples in pixel (x, y).
    Real pixel(int s, std::size_t x, std::size_t y) {
        return of_pixel((static_cast<std::size_t>(s) * height_ + y) * width_ + x);
    }

    // ... in row y of the tile, and in the whole tile.
    Real row(int s, std::size_t y) {
        const std::size_t r = static_cast<std::size_t>(s) * height_ + y;
        if (row_due_[r]) {
            Real far = Real(0);
            // One uncovered sample makes it infinite: no need to look further.
            for (std::size_t x = 0; x < width_ && !(far == infinity()); ++x)
                far = std::max(far, of_pixel(r * width_ + x));
            row_[r] = far;
            row_due_[r] = 0;
        }
        return row_[r];
    }
    Real tile(int s) {
        const std::size_t t = static_cast<std::size_t>(s);
        if (tile_due_[t]) {
            Real far = Real(0);
            for (std::size_t y = 0; y < height_ && !(far == infinity()); ++y) far = std::max(far, row(s, y));
            tile_[t] = far;
            tile_due_[t] = 0;
        }
        return tile_[t];
    }

private:
    static constexpr Real infinity() { return std::numeric_limits<Real>::infinity(); }

    Real of_pixel(std::size_t p) {
        if (pixel_due_[p]) {
            Real far = Real(0);
            for (std::uint32_t q = start_[p]; q < start_[p + 1]; ++q) far = std::max(far, depth_[slot_[q]]);
            pixel_[p] = far;
            pixel_due_[p] = 0;
        }
        return pixel_[p];
    }

    std::size_t width_ = 0, height_ = 0;
    const std::uint32_t* start_ = nullptr;
    const std::uint32_t* slot_ = nullptr;
    const Real* depth_ = nullptr;
    std::vector<Real> pixel_, row_, tile_;
    std::vector<char> pixel_due_, row_due_, tile_due_;
};

}  // namespace blurcull::frontend
