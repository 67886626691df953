// FarthestDepths (render/cpu/farthest_depths.hpp), the occlusion test's
// pixel, row and tile levels: with every depth change reported, each level
// asked for returns exactly the farthest depth its samples hold, however
// the changes and the questions interleave (lazy recomputation loses nothing).
#include "kernel_generators.hpp"
#include "render/cpu/farthest_depths.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

using blurcull::frontend::FarthestDepths;
using blurcull::testing::property_scale;
using blurcull::testing::Rng;

namespace {

// A uniform index below n.
std::size_t pick(Rng& rng, std::size_t n) { return static_cast<std::size_t>(rng.below(static_cast<int>(n))); }

// A tile's samples grouped as the CPU backend groups them: per (stratum,
// pixel) a contiguous run of slots, the slots in a shuffled order.
struct Tile {
    int strata, width, height;
    std::vector<std::uint32_t> start, slot;
    std::vector<double> depth;
    std::vector<std::size_t> stratum_of, pixel_of;  // per slot

    double truth_pixel(int s, int x, int y) const {
        const std::size_t p = (static_cast<std::size_t>(s) * height + y) * width + x;
        double far = 0.0;
        for (std::uint32_t q = start[p]; q < start[p + 1]; ++q) far = std::max(far, depth[slot[q]]);
        return far;
    }
    double truth_row(int s, int y) const {
        double far = 0.0;
        for (int x = 0; x < width; ++x) far = std::max(far, truth_pixel(s, x, y));
        return far;
    }
    double truth_tile(int s) const {
        double far = 0.0;
        for (int y = 0; y < height; ++y) far = std::max(far, truth_row(s, y));
        return far;
    }
};

Tile random_tile(Rng& rng) {
    Tile tile;
    tile.strata = 1 << rng.below(3);
    tile.width = 1 + rng.below(16);
    tile.height = 1 + rng.below(16);
    const std::size_t groups = static_cast<std::size_t>(tile.strata) * tile.width * tile.height;
    tile.start.push_back(0);
    for (std::size_t g = 0; g < groups; ++g) {
        // A stratum may hold no sample of a pixel.
        const std::uint32_t count = static_cast<std::uint32_t>(rng.below(4));
        for (std::uint32_t i = 0; i < count; ++i) {
            tile.stratum_of.push_back(g / (static_cast<std::size_t>(tile.width) * tile.height));
            tile.pixel_of.push_back(g % (static_cast<std::size_t>(tile.width) * tile.height));
        }
        tile.start.push_back(tile.start.back() + count);
    }
    const std::size_t samples = tile.start.back();
    // slot[q]: a permutation, so that group order and slot order differ.
    std::vector<std::uint32_t> order(samples);
    for (std::uint32_t i = 0; i < samples; ++i) order[i] = i;
    for (std::size_t i = samples; i > 1; --i) std::swap(order[i - 1], order[pick(rng, i)]);
    tile.slot.assign(samples, 0);
    std::vector<std::size_t> stratum_of(samples), pixel_of(samples);
    for (std::size_t q = 0; q < samples; ++q) {
        tile.slot[q] = order[q];
        stratum_of[order[q]] = tile.stratum_of[q];
        pixel_of[order[q]] = tile.pixel_of[q];
    }
    tile.stratum_of = stratum_of;
    tile.pixel_of = pixel_of;
    tile.depth.assign(samples, std::numeric_limits<double>::infinity());
    return tile;
}

}  // namespace

TEST_CASE("every level of FarthestDepths is the farthest depth its samples hold, after any changes") {
    Rng rng(0xfa57de97u);
    const int tiles = std::max(20, static_cast<int>(400 * property_scale()));
    std::uint64_t questions = 0, finite = 0;
    for (int t = 0; t < tiles; ++t) {
        Tile tile = random_tile(rng);
        FarthestDepths<double> farthest;
        // Some samples hold depths before the grouping, as when triangles
        // drew before a tile first needed its strata.
        for (double& d : tile.depth)
            if (rng.below(2) == 0) d = 1.0 + rng.uniform() * 9.0;
        farthest.reset(tile.strata, tile.width, tile.height, tile.start.data(), tile.slot.data(), tile.depth.data());
        for (int step = 0; step < 200 && !tile.depth.empty(); ++step) {
            if (rng.below(3) != 0) {
                // A hit: some sample's depth decreases, and is reported.
                const std::size_t k = pick(rng, tile.depth.size());
                const double nearer = std::min(tile.depth[k], 10.0) * rng.uniform();
                if (nearer < tile.depth[k]) {
                    tile.depth[k] = nearer;
                    farthest.changed(static_cast<int>(tile.stratum_of[k]), tile.pixel_of[k] % tile.width,
                                     tile.pixel_of[k] / tile.width);
                }
                continue;
            }
            const int s = rng.below(tile.strata);
            const int x = rng.below(tile.width);
            const int y = rng.below(tile.height);
            double asked = 0.0, truth = 0.0;
            switch (rng.below(3)) {
            case 0:
                asked = farthest.pixel(s, static_cast<std::size_t>(x), static_cast<std::size_t>(y));
                truth = tile.truth_pixel(s, x, y);
                break;
            case 1:
                asked = farthest.row(s, static_cast<std::size_t>(y));
                truth = tile.truth_row(s, y);
                break;
            default:
                asked = farthest.tile(s);
                truth = tile.truth_tile(s);
            }
            INFO("tile ", t, " step ", step, " stratum ", s, " pixel ", x, ",", y);
            REQUIRE(asked == truth);
            ++questions;
            finite += truth < std::numeric_limits<double>::infinity() && truth > 0.0;
        }
    }
    // Not vacuous: many questions had a finite answer (covered samples only).
    CHECK(questions > static_cast<std::uint64_t>(tiles) * 30);
    CHECK(finite > questions / 10);
}
