// The samplers of the stochastic renderers (patterns_body.inl: sampler_setup,
// sampler_sample, the Sobol patterns; docs/sampling.md, "The sampler"): the
// Sobol points against Joe and Kuo's direction numbers, the net properties
// of every power-of-two prefix of a pixel's samples, determinism by seed, and
// that the two-step sampler draws exactly pattern_sample's samples (hashed:
// pixel_sample's, the samples of every image before --sampler existed).
#include <blurcull/pattern_names.hpp>
#include <blurcull/patterns.hpp>

#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <set>
#include <stdexcept>
#include <vector>

namespace {

using P = blurcull::patternsf;

bool same_sample(const P::PixelSample& a, const P::PixelSample& b) {
    return std::memcmp(&a.offset, &b.offset, sizeof a.offset) == 0 && std::memcmp(&a.lens, &b.lens, sizeof a.lens) == 0 &&
           std::memcmp(&a.time, &b.time, sizeof a.time) == 0;
}

// Points of [0, 1)^d as 32-bit fractions; every elementary box with
// `digits[k]` binary digits in dimension k must hold exactly `per_box`.
bool every_box_holds(const std::vector<std::vector<std::uint32_t>>& points, const std::vector<int>& digits,
                     std::size_t per_box) {
    std::vector<std::size_t> count;
    std::size_t boxes = 1;
    for (int d : digits) boxes <<= d;
    count.assign(boxes, 0);
    for (const std::vector<std::uint32_t>& p : points) {
        std::size_t box = 0;
        for (std::size_t k = 0; k < digits.size(); ++k) {
            const int d = digits[k];
            box = (box << d) | (d == 0 ? 0u : (p[k] >> (32 - d)));
        }
        ++count[box];
    }
    for (std::size_t c : count) {
        if (c != per_box) return false;
    }
    return true;
}

// A (t, m, s)-net in base 2: every elementary box of volume 2^(t - m) holds 2^t points.
bool is_net(const std::vector<std::vector<std::uint32_t>>& points, int m, int t) {
    const std::size_t s = points.empty() ? 0 : points[0].size();
    std::vector<int> digits(s, 0);
    const int q = m - t;
    // Every split of q digits over the s dimensions.
    std::vector<int> split(s, 0);
    for (;;) {
        int used = 0;
        for (int d : split) used += d;
        if (used == q && !every_box_holds(points, split, std::size_t(1) << t)) return false;
        std::size_t k = 0;
        while (k < s && ++split[k] > q) split[k++] = 0;
        if (k == s) return true;
    }
}

// The fraction of a coordinate in [0, 1) as bc_unit left it (24 bits): the top bits survive.
std::uint32_t fraction_bits(float unit) { return static_cast<std::uint32_t>(double(unit) * 0x1p32); }

// Sobol dimension dim by an independent construction: the direction numbers
// in a table from the recurrence, the point as the xor of those of index's bits.
std::uint32_t table_sobol(std::uint32_t index, int dim) {
    struct Poly {
        unsigned s, a, m[3];
    };
    // new-joe-kuo-6.21201, dimensions 2..5.
    const Poly polys[4] = {{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}, {3, 2, {1, 1, 1}}};
    std::uint32_t v[33] = {};
    for (unsigned k = 1; k <= 32; ++k) {
        if (dim == 0) {
            v[k] = 1u << (32 - k);
            continue;
        }
        const Poly& p = polys[dim - 1];
        if (k <= p.s) {
            v[k] = p.m[k - 1] << (32 - k);
        } else {
            v[k] = v[k - p.s] ^ (v[k - p.s] >> p.s);
            for (unsigned j = 1; j < p.s; ++j) {
                if ((p.a >> (p.s - 1 - j)) & 1u) v[k] ^= v[k - j];
            }
        }
    }
    std::uint32_t x = 0;
    for (unsigned k = 1; k <= 32; ++k) {
        if ((index >> (k - 1)) & 1u) x ^= v[k];
    }
    return x;
}

}  // namespace

TEST_CASE("Sobol: Joe and Kuo's initial direction numbers, and the whole sequence against a table construction") {
    // m_k 2^(32 - k) for dimensions 2..5 of new-joe-kuo-6.21201 (here 1..4).
    CHECK(P::bc_sobol(1u, 1) == 0x80000000u);
    CHECK(P::bc_sobol(2u, 2) == 3u << 30);
    CHECK(P::bc_sobol(4u, 3) == 1u << 29);
    CHECK(P::bc_sobol(2u, 4) == 1u << 30);
    CHECK(P::bc_sobol(4u, 4) == 1u << 29);
    int mismatches = 0;
    for (int dim = 0; dim < 5; ++dim) {
        for (std::uint32_t i = 0; i < 4096; ++i) mismatches += P::bc_sobol(i, dim) != table_sobol(i, dim);
        for (std::uint32_t i : {0xffffffffu, 0x80000001u, 0x12345678u}) mismatches += P::bc_sobol(i, dim) != table_sobol(i, dim);
    }
    CHECK(mismatches == 0);
}

TEST_CASE("sobol: every power-of-two prefix of a pixel's samples is a (0, m, 2)-net in (x, y), stratified in t, u, v") {
    for (std::uint32_t spp : {1u, 4u, 16u, 64u, 256u}) {
        for (std::uint32_t px = 0; px < 6; ++px) {
            const P::SamplerSetup setup = P::sampler_setup(BC_PATTERN_SOBOL, px, 7u * px + 2u, spp, 5u);
            for (int m = 0; (1u << m) <= spp; ++m) {
                std::vector<std::vector<std::uint32_t>> xy, time;
                std::vector<std::vector<std::uint32_t>> lens_x;
                for (std::uint32_t j = 0; j < (1u << m); ++j) {
                    const P::PixelSample s = P::sampler_sample(setup, j);
                    xy.push_back({fraction_bits(s.offset.x), fraction_bits(s.offset.y)});
                    time.push_back({fraction_bits(s.time)});
                }
                INFO("spp ", spp, " pixel ", px, " prefix 2^", m);
                CHECK(is_net(xy, m, 0));
                CHECK(is_net(time, m, 0));
                // The lens square (before the disk map): Sobol dimensions 3, 4 are each stratified.
                for (int dim : {3, 4}) {
                    std::vector<std::vector<std::uint32_t>> square;
                    const std::uint32_t key = dim == 3 ? setup.sobol.dim_key3 : setup.sobol.dim_key4;
                    for (std::uint32_t j = 0; j < (1u << m); ++j) {
                        const std::uint32_t shuffled = P::bc_sobol_shuffle(j, setup.sobol.index_key, setup.sobol.index_mask);
                        square.push_back({fraction_bits(P::bc_sobol_unit(shuffled, dim, key))});
                    }
                    CHECK(is_net(square, m, 0));
                }
            }
        }
    }
}

TEST_CASE("padded-sobol: the pixel position and the lens square are (0, m, 2)-nets, (u, v, t) a (1, m, 3)-net") {
    for (std::uint32_t spp : {4u, 16u, 64u, 256u}) {
        for (std::uint32_t px = 0; px < 6; ++px) {
            const P::SamplerSetup setup = P::sampler_setup(BC_PATTERN_PADDED_SOBOL, px, 3u, spp, 9u);
            const P::SobolSetup& sobol = setup.sobol;
            for (int m = 1; (1u << m) <= spp; ++m) {
                std::vector<std::vector<std::uint32_t>> xy, uv, uvt;
                for (std::uint32_t j = 0; j < (1u << m); ++j) {
                    const P::PixelSample s = P::sampler_sample(setup, j);
                    xy.push_back({fraction_bits(s.offset.x), fraction_bits(s.offset.y)});
                    const std::uint32_t lens_time = P::bc_sobol_shuffle(j, sobol.index_key2, sobol.index_mask);
                    const std::uint32_t u = fraction_bits(P::bc_sobol_unit(lens_time, 0, sobol.dim_key3));
                    const std::uint32_t v = fraction_bits(P::bc_sobol_unit(lens_time, 1, sobol.dim_key4));
                    uv.push_back({u, v});
                    uvt.push_back({u, v, fraction_bits(s.time)});
                    // The sample's lens is the concentric map of exactly this square point.
                    const P::vec2 square(P::bc_sobol_unit(lens_time, 0, sobol.dim_key3),
                                         P::bc_sobol_unit(lens_time, 1, sobol.dim_key4));
                    CHECK(same_sample(s, P::PixelSample{s.offset, P::bc_lens_of(square), s.time}));
                }
                INFO("spp ", spp, " pixel ", px, " prefix 2^", m);
                CHECK(is_net(xy, m, 0));
                CHECK(is_net(uv, m, 0));
                CHECK(is_net(uvt, m, 1));
            }
        }
    }
}

TEST_CASE("the net checks can fail: unscrambled 5D Sobol's lens pair and random points are not (0, m, 2)-nets") {
    // Dimensions 3 and 4 have t = 1 for 2^3 points (Joe and Kuo's t-values), so
    // the 5D pattern keeps only (x, y) a (0, m, 2)-net; padded-sobol's lens exists for that.
    std::vector<std::vector<std::uint32_t>> pair34, random;
    for (std::uint32_t i = 0; i < 8; ++i) pair34.push_back({P::bc_sobol(i, 3), P::bc_sobol(i, 4)});
    CHECK_FALSE(is_net(pair34, 3, 0));
    CHECK(is_net(pair34, 3, 1));
    for (std::uint32_t j = 0; j < 16; ++j) {
        const P::PixelSample s = P::pattern_sample(BC_PATTERN_RANDOM, 1u, 2u, j, 16u, 3u);
        random.push_back({fraction_bits(s.offset.x), fraction_bits(s.offset.y)});
    }
    CHECK_FALSE(is_net(random, 4, 0));
}

TEST_CASE("the sampler draws pattern_sample's samples for every pattern; hashed is pixel_sample") {
    for (int pattern = 0; pattern < BC_PATTERN_COUNT; ++pattern) {
        for (std::uint32_t spp : {1u, 3u, 16u, 100u}) {
            for (std::uint32_t px = 0; px < 5; ++px) {
                const P::SamplerSetup setup = P::sampler_setup(pattern, px, px + 11u, spp, 42u);
                for (std::uint32_t j = 0; j < spp; ++j) {
                    const P::PixelSample s = P::sampler_sample(setup, j);
                    INFO(blurcull::sample_pattern_name(pattern), " spp ", spp, " sample ", j);
                    CHECK(same_sample(s, P::pattern_sample(pattern, px, px + 11u, j, spp, 42u)));
                    if (pattern == BC_PATTERN_HASHED) CHECK(same_sample(s, P::pixel_sample(px, px + 11u, j, spp, 42u)));
                    CHECK(s.offset.x >= 0.0f);
                    CHECK(s.offset.x < 1.0f);
                    CHECK(s.offset.y >= 0.0f);
                    CHECK(s.offset.y < 1.0f);
                    CHECK(s.time >= 0.0f);
                    CHECK(s.time < 1.0f);
                    CHECK(s.lens.x * s.lens.x + s.lens.y * s.lens.y <= 1.0f + 1e-6f);
                }
            }
        }
    }
}

TEST_CASE("sobol samplers: deterministic by seed and pixel, different for another seed or pixel") {
    for (int pattern : {BC_PATTERN_SOBOL, BC_PATTERN_PADDED_SOBOL}) {
        int other_seed = 0, other_pixel = 0, total = 0;
        std::set<std::uint32_t> first_times;
        for (std::uint32_t px = 0; px < 32; ++px) {
            const P::SamplerSetup a = P::sampler_setup(pattern, px, 5u, 16u, 7u);
            const P::SamplerSetup again = P::sampler_setup(pattern, px, 5u, 16u, 7u);
            const P::SamplerSetup reseeded = P::sampler_setup(pattern, px, 5u, 16u, 8u);
            const P::SamplerSetup neighbour = P::sampler_setup(pattern, px + 1u, 5u, 16u, 7u);
            for (std::uint32_t j = 0; j < 16; ++j) {
                const P::PixelSample s = P::sampler_sample(a, j);
                CHECK(same_sample(s, P::sampler_sample(again, j)));
                other_seed += !same_sample(s, P::sampler_sample(reseeded, j));
                other_pixel += !same_sample(s, P::sampler_sample(neighbour, j));
                ++total;
            }
            first_times.insert(fraction_bits(P::sampler_sample(a, 0).time));
        }
        INFO(blurcull::sample_pattern_name(pattern));
        CHECK(other_seed == total);
        CHECK(other_pixel == total);
        // The per-pixel scrambles decorrelate pixels: sample 0's time differs from pixel to pixel.
        CHECK(first_times.size() == 32);
    }
}

TEST_CASE("sampler names: every id has one, parse_sample_pattern inverts it, bad names and ids are refused") {
    for (int pattern = 0; pattern < BC_PATTERN_COUNT; ++pattern) {
        CHECK(blurcull::parse_sample_pattern(blurcull::sample_pattern_name(pattern)) == pattern);
    }
    CHECK(blurcull::sample_pattern_list() == "hashed, random, jittered, sobol, padded-sobol");
    CHECK_THROWS_WITH_AS(blurcull::parse_sample_pattern("halton"),
                         "unknown sample pattern 'halton' (valid: hashed, random, jittered, sobol, padded-sobol)",
                         std::invalid_argument);
    CHECK_THROWS_AS(blurcull::make_pattern_tile(BC_PATTERN_COUNT, 4, 4, 1u), std::invalid_argument);
}
