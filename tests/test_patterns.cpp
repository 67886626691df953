// Sample patterns (random, jittered, Owen-scrambled Sobol) and the interleaved
// tile set: ranges, determinism, stratification and net properties, the
// tiling contract (every tile holds every tuple once, neighbouring tiles agree
// on their shared corners and edges) and the optimisation's cost.
#include <blurcull/blurcull.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <vector>

using namespace blurcull;
using P = patternsf;

namespace {

bool same_sample(const P::PixelSample& a, const P::PixelSample& b) {
    return a.offset == b.offset && a.lens == b.lens && a.time == b.time;
}

const int all_patterns[] = {BC_PATTERN_HASHED, BC_PATTERN_RANDOM, BC_PATTERN_JITTERED, BC_PATTERN_SOBOL,
                            BC_PATTERN_PADDED_SOBOL};

// Cells of the (2^a x 2^b) grid holding each point; a net has every cell once.
bool is_net(const std::vector<std::pair<double, double>>& points, int a, int b) {
    const std::size_t cells = std::size_t(1) << (a + b);
    if (points.size() != cells) return false;
    std::vector<int> count(cells, 0);
    for (const auto& p : points) {
        const auto ix = static_cast<std::size_t>(std::floor(p.first * double(1 << a)));
        const auto iy = static_cast<std::size_t>(std::floor(p.second * double(1 << b)));
        if (ix >= (std::size_t(1) << a) || iy >= (std::size_t(1) << b)) return false;
        if (++count[(iy << a) | ix] != 1) return false;
    }
    return true;
}

// Every elementary interval of volume 2^-m holds exactly one of the 2^m points.
bool is_zero_net(const std::vector<std::pair<double, double>>& points, int m) {
    for (int a = 0; a <= m; ++a) {
        if (!is_net(points, a, m - a)) return false;
    }
    return true;
}

double sobol_fraction(std::uint32_t index, int dim) { return double(P::bc_sobol(index, dim)) * 0x1p-32; }

// Tuple of lattice cell (gx, gy) through any slot table with the tile set's layout.
struct LatticeView {
    const InterleavedTiles& tiles;
    const std::vector<std::uint16_t>& slots;
    int at(int gx, int gy) const {
        const int w = tiles.width;
        const std::uint32_t prototype = tiles.prototype_of_tile(std::uint32_t(gx / w), std::uint32_t(gy / w));
        return slots[std::size_t(prototype) * std::size_t(tiles.tuple_count) + std::size_t((gy % w) * w + gx % w)];
    }
    std::uint32_t colour(int cx, int cy) const {
        return P::interleaved_corner_colour(std::uint32_t(cx), std::uint32_t(cy), tiles.seed);
    }
};

struct MatchReport {
    int pairs_checked = 0;
    int corners_checked = 0;
    int mismatches = 0;
};

// Independent of how the tiles were built: along every shared edge of a
// tiles x tiles region, the two columns (rows) of cells either side must be
// the same whenever the edge's two corner colours are; around every interior
// lattice corner the 2 x 2 cells must be the same whenever its colour is.
MatchReport check_matching(const InterleavedTiles& tiles, const std::vector<std::uint16_t>& slots, int region) {
    const LatticeView view{tiles, slots};
    const int w = tiles.width;
    MatchReport report;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<int>> vertical_edges, horizontal_edges;
    std::map<std::uint32_t, std::vector<int>> corners;
    auto record = [&](auto& table, const auto& key, const std::vector<int>& cells) {
        auto found = table.find(key);
        if (found == table.end()) {
            table.emplace(key, cells);
        } else if (found->second != cells) {
            ++report.mismatches;
        }
    };
    for (int ty = 0; ty < region; ++ty) {
        for (int tx = 0; tx < region; ++tx) {
            if (tx + 1 < region) {  // A = (tx, ty) left of B = (tx + 1, ty)
                std::vector<int> strip;
                for (int y = 0; y < w; ++y) {
                    strip.push_back(view.at(tx * w + w - 1, ty * w + y));
                    strip.push_back(view.at((tx + 1) * w, ty * w + y));
                }
                record(vertical_edges, std::make_pair(view.colour(tx + 1, ty), view.colour(tx + 1, ty + 1)), strip);
                ++report.pairs_checked;
            }
            if (ty + 1 < region) {  // A = (tx, ty) above B = (tx, ty + 1)
                std::vector<int> strip;
                for (int x = 0; x < w; ++x) {
                    strip.push_back(view.at(tx * w + x, ty * w + w - 1));
                    strip.push_back(view.at(tx * w + x, (ty + 1) * w));
                }
                record(horizontal_edges, std::make_pair(view.colour(tx, ty + 1), view.colour(tx + 1, ty + 1)), strip);
                ++report.pairs_checked;
            }
            if (tx > 0 && ty > 0) {  // corner (tx, ty) shared by four tiles
                const int gx = tx * w, gy = ty * w;
                record(corners, view.colour(tx, ty),
                       std::vector<int>{view.at(gx - 1, gy - 1), view.at(gx, gy - 1), view.at(gx - 1, gy), view.at(gx, gy)});
                ++report.corners_checked;
            }
        }
    }
    return report;
}

bool every_tile_is_a_permutation(const InterleavedTiles& tiles) {
    const auto n = std::size_t(tiles.tuple_count);
    for (std::size_t prototype = 0; prototype < std::size_t(InterleavedTiles::prototype_count); ++prototype) {
        std::vector<int> seen(n, 0);
        for (std::size_t slot = 0; slot < n; ++slot) {
            const std::size_t tuple = tiles.slot_tuple[prototype * n + slot];
            if (tuple >= n || ++seen[tuple] != 1) return false;
            if (tiles.tuple_slot[prototype * n + tuple] != slot) return false;
        }
    }
    return true;
}

}  // namespace

TEST_CASE("every pattern stays in range, is deterministic and depends on the seed") {
    for (int pattern : all_patterns) {
        CAPTURE(pattern);
        int differs = 0;
        for (std::uint32_t spp : {1u, 5u, 16u, 64u}) {
            for (std::uint32_t px = 0; px < 6; ++px) {
                for (std::uint32_t j = 0; j < spp; ++j) {
                    const P::PixelSample s = P::pattern_sample(pattern, px, 2 * px + 1, j, spp, 9u);
                    CHECK(s.offset.x >= 0.0f);
                    CHECK(s.offset.x < 1.0f);
                    CHECK(s.offset.y >= 0.0f);
                    CHECK(s.offset.y < 1.0f);
                    CHECK(s.time >= 0.0f);
                    CHECK(s.time < 1.0f);
                    CHECK(std::abs(s.lens.x) <= 1.0f);
                    CHECK(std::abs(s.lens.y) <= 1.0f);
                    CHECK(s.lens.x * s.lens.x + s.lens.y * s.lens.y <= 1.0f + 1e-5f);
                    CHECK(same_sample(s, P::pattern_sample(pattern, px, 2 * px + 1, j, spp, 9u)));
                    if (!same_sample(s, P::pattern_sample(pattern, px, 2 * px + 1, j, spp, 10u))) ++differs;
                }
            }
        }
        CHECK(differs > 500);
    }
}

TEST_CASE("pattern_sample dispatches to the named patterns; hashed is pixel_sample") {
    for (std::uint32_t j = 0; j < 16; ++j) {
        CHECK(same_sample(P::pattern_sample(BC_PATTERN_HASHED, 3, 4, j, 16, 2), P::pixel_sample(3, 4, j, 16, 2)));
        CHECK(same_sample(P::pattern_sample(BC_PATTERN_RANDOM, 3, 4, j, 16, 2), P::pattern_random(3, 4, j, 2)));
        CHECK(same_sample(P::pattern_sample(BC_PATTERN_JITTERED, 3, 4, j, 16, 2), P::pattern_jittered(3, 4, j, 16, 2)));
        CHECK(same_sample(P::pattern_sample(BC_PATTERN_SOBOL, 3, 4, j, 16, 2), P::pattern_sobol(3, 4, j, 16, 2)));
    }
    CHECK(parse_sample_pattern("sobol") == BC_PATTERN_SOBOL);
    CHECK(parse_sample_pattern("hashed") == BC_PATTERN_HASHED);
    CHECK_THROWS_WITH_AS(parse_sample_pattern("halton"),
                         "unknown sample pattern 'halton' (valid: hashed, random, jittered, sobol, padded-sobol)",
                         std::invalid_argument);
}

TEST_CASE("tiled patterns repeat every tile pixels and match their texture") {
    const int tile = 4, spp = 8;
    for (int pattern : all_patterns) {
        CAPTURE(pattern);
        const std::vector<kernelf::PixelSample> texture = make_pattern_tile(pattern, tile, spp, 5u);
        REQUIRE(texture.size() == std::size_t(tile * tile * spp));
        for (std::uint32_t py = 0; py < 11; ++py) {
            for (std::uint32_t px = 0; px < 13; ++px) {
                for (std::uint32_t j = 0; j < std::uint32_t(spp); ++j) {
                    const P::PixelSample s = P::pattern_sample_tiled(pattern, px, py, j, spp, 5u, tile);
                    const std::size_t texel = ((py % tile) * tile + px % tile) * spp + j;
                    CHECK(same_sample(s, texture[texel]));
                    CHECK(same_sample(s, P::pattern_sample_tiled(pattern, px + tile, py + 2 * tile, j, spp, 5u, tile)));
                }
            }
        }
    }
    CHECK_THROWS_AS(make_pattern_tile(7, 4, 4, 1u), std::invalid_argument);
    CHECK_THROWS_AS(make_pattern_tile(BC_PATTERN_SOBOL, 0, 4, 1u), std::invalid_argument);
    CHECK_THROWS_AS(make_pattern_tile(BC_PATTERN_SOBOL, 4, 0, 1u), std::invalid_argument);
}

TEST_CASE("bc_permute is a permutation of [0, n) for every n") {
    for (std::uint32_t n : {1u, 2u, 3u, 5u, 16u, 17u, 36u, 100u, 1000u, 4097u}) {
        for (std::uint32_t key : {0u, 1u, 0xdeadbeefu}) {
            std::vector<int> seen(n, 0);
            for (std::uint32_t i = 0; i < n; ++i) {
                const std::uint32_t image = P::bc_permute(i, n, key);
                REQUIRE(image < n);
                ++seen[image];
            }
            CHECK(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
        }
    }
    // Keys change the permutation.
    int moved = 0;
    for (std::uint32_t i = 0; i < 64; ++i) moved += P::bc_permute(i, 64, 1u) != P::bc_permute(i, 64, 2u);
    CHECK(moved > 32);
}

TEST_CASE("jittered: one sample per position stratum and per time stratum; interval: stratum = index") {
    for (std::uint32_t spp : {4u, 9u, 16u, 20u, 64u}) {
        CAPTURE(spp);
        std::uint32_t n = 1;
        while ((n + 1) * (n + 1) <= spp) ++n;
        for (std::uint32_t px = 0; px < 5; ++px) {
            std::vector<int> cells(n * n, 0), strata(spp, 0);
            for (std::uint32_t j = 0; j < spp; ++j) {
                const P::PixelSample s = P::pattern_jittered(px, 7, j, spp, 3u);
                if (j < n * n) ++cells[std::uint32_t(s.offset.y * float(n)) * n + std::uint32_t(s.offset.x * float(n))];
                ++strata[std::uint32_t(s.time * float(spp))];
                const P::PixelSample interval = P::interval_sample(px, 7, j, spp, 3u);
                CHECK(std::uint32_t(interval.time * float(spp)) == j);
            }
            CHECK(std::all_of(cells.begin(), cells.end(), [](int c) { return c == 1; }));
            CHECK(std::all_of(strata.begin(), strata.end(), [](int c) { return c == 1; }));
        }
    }
}

TEST_CASE("Sobol: dimensions 0 and 1 are (0, m, 2)-nets, every dimension is stratified") {
    for (int m = 1; m <= 10; ++m) {
        CAPTURE(m);
        const std::uint32_t count = 1u << m;
        // Any aligned block of 2^m points is a net, not only the first.
        for (std::uint32_t block : {0u, 1u, 7u}) {
            std::vector<std::pair<double, double>> points;
            for (std::uint32_t i = 0; i < count; ++i) {
                points.emplace_back(sobol_fraction(block * count + i, 0), sobol_fraction(block * count + i, 1));
            }
            CHECK(is_zero_net(points, m));
            for (int dim = 0; dim < 5; ++dim) {
                std::vector<int> strata(count, 0);
                for (std::uint32_t i = 0; i < count; ++i) ++strata[std::size_t(sobol_fraction(block * count + i, dim) * count)];
                CHECK(std::all_of(strata.begin(), strata.end(), [](int c) { return c == 1; }));
            }
        }
    }
    // The direction numbers of dimension 2 (Joe and Kuo's dimension 3, m = 1, 3):
    // V_1 = 1/2, V_2 = 3/4, V_3 = V_1 ^ V_1 / 4 ^ V_2 = 3/8.
    CHECK(sobol_fraction(1, 2) == 0.5);
    CHECK(sobol_fraction(2, 2) == 0.75);
    CHECK(sobol_fraction(4, 2) == 0.375);
}

TEST_CASE("Owen scrambling keeps each digit a function of the digits above it, and nets nets") {
    std::mt19937 rng(12345);
    for (int trial = 0; trial < 2000; ++trial) {
        const auto x = std::uint32_t(rng()), seed = std::uint32_t(rng());
        const int m = 1 + trial % 20;
        const std::uint32_t low = std::uint32_t(rng()) & ((1u << (32 - m)) - 1u);
        const std::uint32_t y = (x & ~((1u << (32 - m)) - 1u)) | low;  // same top m digits as x
        CHECK((P::bc_owen_scramble(x, seed) >> (32 - m)) == (P::bc_owen_scramble(y, seed) >> (32 - m)));
    }
    // Flipping the first digit is a fair coin over seeds.
    int flips = 0;
    for (std::uint32_t seed = 0; seed < 1000; ++seed) flips += (P::bc_owen_scramble(0u, seed) >> 31) != 0u;
    CHECK(flips > 430);
    CHECK(flips < 570);
    // The per-pixel Sobol pattern: 2^m samples of a pixel form a net in (x, y)
    // and are stratified in t.
    for (int m = 2; m <= 8; m += 2) {
        const std::uint32_t spp = 1u << m;
        for (std::uint32_t px = 0; px < 4; ++px) {
            std::vector<std::pair<double, double>> points;
            std::vector<int> strata(spp, 0);
            for (std::uint32_t j = 0; j < spp; ++j) {
                const P::PixelSample s = P::pattern_sobol(px, 3, j, spp, 11u);
                points.emplace_back(s.offset.x, s.offset.y);
                ++strata[std::size_t(s.time * float(spp))];
            }
            CHECK(is_zero_net(points, m));
            CHECK(std::all_of(strata.begin(), strata.end(), [](int c) { return c == 1; }));
        }
    }
}

TEST_CASE("stratified patterns integrate better than random ones") {
    // Coverage of a disk edge through the pixel and a smooth function of time
    // and lens: RMS error over many pixels with 64 samples each.
    auto rms_error = [](int pattern) {
        double sum = 0.0;
        const int pixels = 400;
        const std::uint32_t spp = 64;
        for (int p = 0; p < pixels; ++p) {
            double estimate = 0.0;
            for (std::uint32_t j = 0; j < spp; ++j) {
                const P::PixelSample s = P::pattern_sample(pattern, std::uint32_t(p), 1, j, spp, 4u);
                const double inside = s.offset.x * s.offset.x + s.offset.y * s.offset.y < 0.64 ? 1.0 : 0.0;
                estimate += inside + s.time * s.time + (s.lens.x + 1.0) * (s.lens.y + 1.0);
            }
            // pi 0.64 / 4 + 1/3 + 1 (E[(u+1)(v+1)] = 1 on the disk)
            const double exact = 3.14159265358979 * 0.16 + 1.0 / 3.0 + 1.0;
            const double error = estimate / double(spp) - exact;
            sum += error * error;
        }
        return std::sqrt(sum / double(pixels));
    };
    const double random = rms_error(BC_PATTERN_RANDOM);
    const double hashed = rms_error(BC_PATTERN_HASHED);
    const double jittered = rms_error(BC_PATTERN_JITTERED);
    const double sobol = rms_error(BC_PATTERN_SOBOL);
    const double padded = rms_error(BC_PATTERN_PADDED_SOBOL);
    MESSAGE("RMS error, 64 spp: random " << random << ", hashed " << hashed << ", jittered " << jittered
                                         << ", sobol " << sobol << ", padded-sobol " << padded);
    CHECK(padded < 0.5 * random);
    CHECK(jittered < 0.5 * random);
    CHECK(sobol < 0.5 * random);
    CHECK(sobol < jittered);
}

TEST_CASE("interleaved tuples: Halton (2, 3, 5) mapped to time and the lens disk") {
    CHECK(P::bc_radical_inverse(0, 2) == 0.0f);
    CHECK(P::bc_radical_inverse(1, 2) == 0.5f);
    CHECK(P::bc_radical_inverse(6, 2) == 0.375f);
    CHECK(patternsd::bc_radical_inverse(5, 3) == doctest::Approx(2.0 / 3.0 + 1.0 / 9.0));
    CHECK(patternsd::bc_radical_inverse(7, 5) == doctest::Approx(2.0 / 5.0 + 1.0 / 25.0));
    for (std::uint32_t k = 0; k < 256; ++k) {
        const patternsd::vec3 tuple = patternsd::interleaved_tuple(k);
        CHECK(tuple.z == patternsd::bc_radical_inverse(k, 2));
        CHECK(tuple.x * tuple.x + tuple.y * tuple.y == doctest::Approx(patternsd::bc_radical_inverse(k, 3)));
        const double angle = std::atan2(tuple.y, tuple.x);
        const double turn = (angle < 0 ? angle + 2.0 * 3.14159265358979 : angle) / (2.0 * 3.14159265358979);
        if (k > 0 && k % 3 != 0) {  // radius > 0: the angle is defined
            const double off = std::fmod(turn - patternsd::bc_radical_inverse(k, 5) + 1.0, 1.0);
            CHECK(std::min(off, 1.0 - off) < 1e-9);
        }
    }
}

TEST_CASE("interleaved tiles: every prototype holds every tuple exactly once, for every width and q") {
    for (int width = 2; width <= 9; ++width) {
        for (double q : {0.0, 0.5, 1.0}) {
            CAPTURE(width);
            CAPTURE(q);
            InterleavedTileOptions options;
            options.width = width;
            options.motion_weight = q;
            options.seed = std::uint32_t(width * 10 + int(q * 2));
            const InterleavedTiles tiles = make_interleaved_tiles(options);
            REQUIRE(tiles.tuple_count == width * width);
            REQUIRE(tiles.slot_tuple.size() == std::size_t(81 * width * width));
            CHECK(every_tile_is_a_permutation(tiles));
            const MatchReport report = check_matching(tiles, tiles.slot_tuple, 12);
            CHECK(report.mismatches == 0);
        }
    }
}

TEST_CASE("interleaved tiles: neighbours agree on shared corners and edges across the lattice") {
    const InterleavedTiles tiles = make_interleaved_tiles(InterleavedTileOptions{});
    const MatchReport report = check_matching(tiles, tiles.slot_tuple, 40);
    CHECK(report.pairs_checked == 2 * 40 * 39);
    CHECK(report.corners_checked == 39 * 39);
    CHECK(report.mismatches == 0);
    // All 81 prototypes occur, so the matches above covered every colour pair.
    std::set<std::uint32_t> seen;
    for (std::uint32_t ty = 0; ty < 40; ++ty) {
        for (std::uint32_t tx = 0; tx < 40; ++tx) seen.insert(tiles.prototype_of_tile(tx, ty));
    }
    CHECK(seen.size() == 81);
    // Far from the origin as well (the hash has no period there).
    CHECK(tiles.tuple_at(1000000u, 7u) >= 0);

    // The checker catches Aqsis' defect: bottom corner cells taken from the
    // wrong corner colour (here: BL and BR swapped in every prototype). The
    // tiles stay permutations, but corners no longer match.
    std::vector<std::uint16_t> defective = tiles.slot_tuple;
    const std::size_t n = std::size_t(tiles.tuple_count), w = std::size_t(tiles.width);
    for (std::size_t prototype = 0; prototype < 81; ++prototype) {
        std::swap(defective[prototype * n + (w - 1) * w], defective[prototype * n + (w - 1) * w + (w - 1)]);
    }
    CHECK(check_matching(tiles, defective, 40).mismatches > 0);
    // So does a single interior-to-edge swap in one prototype.
    std::vector<std::uint16_t> one_off = tiles.slot_tuple;
    std::swap(one_off[5 * n + 1], one_off[5 * n + w + 1]);  // top edge cell <-> interior cell
    CHECK(check_matching(tiles, one_off, 40).mismatches > 0);
}

TEST_CASE("interleaved tiles: the optimised tiling beats random permutations on the stated cost") {
    const int region = 16;
    for (double q : {1.0, 0.5, 0.0}) {
        CAPTURE(q);
        InterleavedTileOptions options;
        options.motion_weight = q;
        const InterleavedTiles tiles = make_interleaved_tiles(options);
        const int side = region * tiles.width;
        // The cost without the pairs of equal tuples (whose d = 0 is floored),
        // and how many cells have an equal tuple among their 8 neighbours.
        auto distinct_cost = [&](const std::vector<int>& lattice, int& equal_neighbours) {
            double total = 0.0;
            equal_neighbours = 0;
            for (int y = 0; y < side; ++y) {
                for (int x = 0; x < side; ++x) {
                    const int here = lattice[std::size_t(y * side + x)];
                    for (int j = -tiles.radius; j <= tiles.radius; ++j) {
                        for (int i = -tiles.radius; i <= tiles.radius; ++i) {
                            if ((i == 0 && j == 0) || x + i < 0 || y + j < 0 || x + i >= side || y + j >= side) continue;
                            const int other = lattice[std::size_t((y + j) * side + x + i)];
                            if (other == here) {
                                if (std::abs(i) <= 1 && std::abs(j) <= 1) ++equal_neighbours;
                                continue;
                            }
                            total += interleaved_pair_cost(i, j, tiles.tuples[std::size_t(here)],
                                                           tiles.tuples[std::size_t(other)], q);
                        }
                    }
                }
            }
            return total / double(side * side);
        };
        const std::vector<int> optimised_lattice = assemble_interleaved_lattice(tiles, region, region);
        const double optimised = interleaved_lattice_cost(optimised_lattice, side, side, tiles.tuples, q, tiles.radius);
        int optimised_equal = 0;
        const double optimised_distinct = distinct_cost(optimised_lattice, optimised_equal);
        // Baseline: each tile an independent random permutation of the tuples.
        std::mt19937 rng(777);
        double random = 0.0, random_distinct = 0.0;
        int random_equal = 0;
        const int trials = 4;
        for (int trial = 0; trial < trials; ++trial) {
            std::vector<int> lattice(std::size_t(side) * std::size_t(side));
            std::vector<int> permutation(std::size_t(tiles.tuple_count));
            for (int ty = 0; ty < region; ++ty) {
                for (int tx = 0; tx < region; ++tx) {
                    for (std::size_t k = 0; k < permutation.size(); ++k) permutation[k] = int(k);
                    for (std::size_t k = permutation.size(); k > 1; --k) std::swap(permutation[k - 1], permutation[rng() % k]);
                    for (int slot = 0; slot < tiles.tuple_count; ++slot) {
                        const int gx = tx * tiles.width + slot % tiles.width, gy = ty * tiles.width + slot / tiles.width;
                        lattice[std::size_t(gy) * std::size_t(side) + std::size_t(gx)] = permutation[std::size_t(slot)];
                    }
                }
            }
            random += interleaved_lattice_cost(lattice, side, side, tiles.tuples, q, tiles.radius) / trials;
            int equal = 0;
            random_distinct += distinct_cost(lattice, equal) / trials;
            random_equal += equal;
        }
        random_equal /= trials;
        MESSAGE("tiling cost, width 6, r 2, q " << q << ": optimised " << optimised << " (distinct pairs "
                                                << optimised_distinct << ", equal 8-neighbours " << optimised_equal
                                                << "), random permutations " << random << " (" << random_distinct
                                                << ", " << random_equal << ")");
        std::printf("tiling cost q=%.1f: optimised %.3f (distinct pairs %.3f, equal 8-neighbours %d); "
                    "random permutations %.3f (%.3f, %d)\n",
                    q, optimised, optimised_distinct, optimised_equal, random, random_distinct, random_equal);
        CHECK(optimised < 0.5 * random);
        CHECK(optimised_distinct < random_distinct);
        CHECK(optimised_equal == 0);
        CHECK(random_equal > 0);
    }
}

TEST_CASE("interleaved tiles: deterministic from the seed; bad options are rejected") {
    InterleavedTileOptions options;
    options.seed = 42;
    const InterleavedTiles a = make_interleaved_tiles(options);
    const InterleavedTiles b = make_interleaved_tiles(options);
    CHECK(a.slot_tuple == b.slot_tuple);
    options.seed = 43;
    const InterleavedTiles c = make_interleaved_tiles(options);
    CHECK(a.slot_tuple != c.slot_tuple);
    InterleavedTileOptions bad;
    bad.width = 1;
    CHECK_THROWS_WITH_AS(make_interleaved_tiles(bad), "interleaved tile width must be in [2, 16], got 1",
                         std::invalid_argument);
    bad = InterleavedTileOptions{};
    bad.radius = 0;
    CHECK_THROWS_AS(make_interleaved_tiles(bad), std::invalid_argument);
    bad = InterleavedTileOptions{};
    bad.motion_weight = std::nan("");
    CHECK_THROWS_AS(make_interleaved_tiles(bad), std::invalid_argument);
    CHECK_THROWS_AS(interleaved_lattice_cost(std::vector<int>(5), 2, 2, a.tuples, 0.5, 2), std::invalid_argument);
}
