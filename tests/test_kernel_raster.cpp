// The raster glue (detail/raster_body.inl): each function against the
// frontend expression it replaces, bit for bit (the old expressions are
// written out here as the references, since the frontend copies are to be
// deleted), and against the property it must have on its own.

#include "kernel_generators.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

using namespace blurcull;
using namespace blurcull::testing;
using Kf = kernel<float>;

namespace {

template <class T>
bool same_bits(T a, T b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
template <class V>
bool same_bits2(V a, V b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y);
}

// ---- the frontend expressions the functions replace (as of issue 10) -------------

// CameraModel::raster_to_ndc / ndc_to_raster / sample_ndc / pixel_ndc_bounds
// (float), and render_common.glsl's sample_ndc / grid_ndc (the same, precise).
template <class Real>
glm::vec<2, Real> old_raster_to_ndc(glm::vec<2, Real> raster, int width, int height) {
    return glm::vec<2, Real>(Real(-1) + Real(2) * raster.x / static_cast<Real>(width),
                             Real(1) - Real(2) * raster.y / static_cast<Real>(height));
}
template <class Real>
glm::vec<2, Real> old_ndc_to_raster(glm::vec<2, Real> ndc, int width, int height) {
    return glm::vec<2, Real>((ndc.x + Real(1)) * Real(0.5) * static_cast<Real>(width),
                             (Real(1) - ndc.y) * Real(0.5) * static_cast<Real>(height));
}
template <class Real>
glm::vec<2, Real> old_sample_ndc(int px, int py, glm::vec<2, Real> offset, int width, int height) {
    return old_raster_to_ndc(glm::vec<2, Real>(static_cast<Real>(px) + offset.x, static_cast<Real>(py) + offset.y),
                             width, height);
}
template <class Real>
glm::vec<4, Real> old_pixel_ndc_bounds(int px, int py, int width, int height) {
    auto top_left = old_raster_to_ndc(glm::vec<2, Real>(static_cast<Real>(px), static_cast<Real>(py)), width, height);
    auto bottom_right =
        old_raster_to_ndc(glm::vec<2, Real>(static_cast<Real>(px + 1), static_cast<Real>(py + 1)), width, height);
    return glm::vec<4, Real>(top_left.x, bottom_right.y, bottom_right.x, top_left.y);
}

// cpu_backend.cpp's pixel_rect (double arithmetic, no margin).
glm::ivec4 old_cpu_pixel_rect(double lo_x, double lo_y, double hi_x, double hi_y, int width, int height) {
    auto clamp_floor = [](double v, int limit) {
        if (!(v > 0.0)) return 0;
        if (v >= double(limit)) return limit;
        return static_cast<int>(std::floor(v));
    };
    glm::ivec4 r;
    r.x = clamp_floor((lo_x + 1.0) * 0.5 * width, width);
    r.z = clamp_floor((hi_x + 1.0) * 0.5 * width, width);
    r.y = clamp_floor((1.0 - hi_y) * 0.5 * height, height);
    r.w = clamp_floor((1.0 - lo_y) * 0.5 * height, height);
    r.z = std::min(r.z, width - 1);
    r.w = std::min(r.w, height - 1);
    if (lo_x > 1.0 || hi_x < -1.0 || lo_y > 1.0 || hi_y < -1.0) r.x = r.z + 1;
    return r;
}

// render_setup.comp's rect (float, RECT_MARGIN = 1/64 pixel).
glm::ivec4 old_gl_rect(glm::vec2 lo, glm::vec2 hi, glm::vec2 image_size) {
    auto clamp_floor = [](float v, int limit) {
        if (!(v > 0.0f)) return 0;
        if (v >= float(limit)) return limit;
        return int(std::floor(v));
    };
    const float margin = 1.0f / 64.0f;
    int w = int(image_size.x), h = int(image_size.y);
    glm::ivec4 r(clamp_floor((lo.x + 1.0f) * 0.5f * image_size.x - margin, w),
                 clamp_floor((1.0f - hi.y) * 0.5f * image_size.y - margin, h),
                 clamp_floor((hi.x + 1.0f) * 0.5f * image_size.x + margin, w),
                 clamp_floor((1.0f - lo.y) * 0.5f * image_size.y + margin, h));
    r = glm::ivec4(std::max(r.x, 0), std::max(r.y, 0), std::min(r.z, w - 1), std::min(r.w, h - 1));
    if (lo.x > 1.0f || hi.x < -1.0f || lo.y > 1.0f || hi.y < -1.0f || r.x > r.z || r.y > r.w)
        return glm::ivec4(0, 0, -1, -1);
    return r;
}

// interleaved_backend.cpp's sample of lattice cell (gx, gy), and its cell of a tile slot.
glm::vec2 old_interleaved_ndc(int gx, int gy, int side, glm::vec2 jitter, int width, int height) {
    const glm::vec2 offset((static_cast<float>(gx % side) + jitter.x) / static_cast<float>(side),
                           (static_cast<float>(gy % side) + jitter.y) / static_cast<float>(side));
    return old_sample_ndc(gx / side, gy / side, glm::min(offset, glm::vec2(0.99999994f)), width, height);
}

// CameraModel's a_x, b_x.
glm::vec2 old_coc(float k, float lens_radius, float focus) {
    return glm::vec2(-k * lens_radius, lens_radius > 0.0f ? k * lens_radius / focus : 0.0f);
}

float below_one() { return std::nextafter(1.0f, 0.0f); }

// A sample offset in [0, 1): often 0 or the largest float below 1 (the
// offsets that round onto a pixel's edges).
float offset_coordinate(Rng& rng) {
    int pick = rng.below(8);
    if (pick == 0) return 0.0f;
    if (pick == 1) return below_one();
    return std::min(static_cast<float>(rng.uniform(0.0, 1.0)), below_one());
}

glm::ivec2 image_size_of(Rng& rng) {
    int pick = rng.below(4);
    if (pick == 0) return glm::ivec2(1 + rng.below(4), 1 + rng.below(4));
    if (pick == 1) return glm::ivec2(1920, 1080);
    if (pick == 2) return glm::ivec2(4096 + rng.below(4096), 16 + rng.below(4096));
    return glm::ivec2(1 + rng.below(800), 1 + rng.below(600));
}

bool in_rect(glm::ivec4 r, glm::ivec2 cell) { return cell.x >= r.x && cell.x <= r.z && cell.y >= r.y && cell.y <= r.w; }

// A box around an NDC point: sometimes exactly on it (an edge through the sample).
template <class K>
void box_around(Rng& rng, typename K::vec2 p, typename K::vec2& lo, typename K::vec2& hi) {
    using real = typename K::real;
    auto spread = [&]() {
        int pick = rng.below(4);
        if (pick == 0) return real(0);
        if (pick == 1) return static_cast<real>(rng.uniform(0.0, 1e-6));
        return static_cast<real>(rng.uniform(0.0, 0.3));
    };
    lo = typename K::vec2(p.x - spread(), p.y - spread());
    hi = typename K::vec2(p.x + spread(), p.y + spread());
}

}  // namespace

TEST_CASE("raster_to_ndc, ndc_to_raster, pixel_sample_ndc and pixel_rect_ndc are CameraModel's arithmetic") {
    Rng rng(0x7a57e1ull);
    for (int n = 0; n < 20000; ++n) {
        glm::ivec2 size = image_size_of(rng);
        Kf::vec2 image(static_cast<float>(size.x), static_cast<float>(size.y));
        int px = rng.below(size.x), py = rng.below(size.y);
        Kf::vec2 offset(offset_coordinate(rng), offset_coordinate(rng));
        Kf::vec2 raster(static_cast<float>(rng.uniform(-10.0, size.x + 10.0)), static_cast<float>(rng.uniform(-10.0, size.y + 10.0)));
        CHECK(same_bits2(Kf::raster_to_ndc(raster, image), old_raster_to_ndc(raster, size.x, size.y)));
        Kf::vec2 ndc(static_cast<float>(rng.uniform(-1.5, 1.5)), static_cast<float>(rng.uniform(-1.5, 1.5)));
        CHECK(same_bits2(Kf::ndc_to_raster(ndc, image), old_ndc_to_raster(ndc, size.x, size.y)));
        CHECK(same_bits2(Kf::pixel_sample_ndc(Kf::ivec2(px, py), offset, image),
                         old_sample_ndc(px, py, offset, size.x, size.y)));
        // The footprint of a pixel block as render_cpu and render_bounds.comp form it.
        int px1 = std::min(size.x - 1, px + rng.below(8)), py1 = std::min(size.y - 1, py + rng.below(8));
        Kf::vec4 box = Kf::pixel_rect_ndc(Kf::ivec4(px, py, px1, py1), image);
        glm::vec4 lo = old_pixel_ndc_bounds<float>(px, py1, size.x, size.y);
        glm::vec4 hi = old_pixel_ndc_bounds<float>(px1, py, size.x, size.y);
        CHECK(same_bits2(Kf::vec2(box.x, box.y), Kf::vec2(lo.x, lo.y)));
        CHECK(same_bits2(Kf::vec2(box.z, box.w), Kf::vec2(hi.z, hi.w)));
    }
}

TEST_CASE_TEMPLATE("raster <-> NDC: the grid's corners exactly, round trips within rounding", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(0x5a11ull);
    for (int n = 0; n < 20000; ++n) {
        glm::ivec2 size = image_size_of(rng);
        typename K::vec2 image(static_cast<Real>(size.x), static_cast<Real>(size.y));
        // Corners: top-left (0, 0) is NDC (-1, 1), bottom-right (W, H) is (1, -1).
        CHECK(same_bits2(K::raster_to_ndc(typename K::vec2(Real(0)), image), typename K::vec2(Real(-1), Real(1))));
        CHECK(same_bits2(K::raster_to_ndc(image, image), typename K::vec2(Real(1), Real(-1))));
        // Samples of the image stay in [-1, 1]^2, even an offset rounded onto the edge.
        typename K::vec2 edge = K::pixel_sample_ndc(typename K::ivec2(size.x - 1, size.y - 1),
                                                    typename K::vec2(static_cast<Real>(below_one())), image);
        CHECK(edge.x <= Real(1));
        CHECK(edge.y >= Real(-1));
        typename K::vec2 raster(static_cast<Real>(rng.uniform(0.0, size.x)), static_cast<Real>(rng.uniform(0.0, size.y)));
        typename K::vec2 back = K::ndc_to_raster(K::raster_to_ndc(raster, image), image);
        // A few ulps of the image size.
        Real tolerance = Real(4) * std::numeric_limits<Real>::epsilon() * static_cast<Real>(std::max(size.x, size.y));
        CHECK(std::abs(back.x - raster.x) <= tolerance);
        CHECK(std::abs(back.y - raster.y) <= tolerance);
    }
}

TEST_CASE("box_cell_rect is render_setup.comp's rect below 2048 cells, and holds render_cpu's") {
    Rng rng(0x7ec7ull);
    for (int n = 0; n < 50000; ++n) {
        glm::ivec2 size(1 + rng.below(2048), 1 + rng.below(2048));
        Kf::vec2 image(static_cast<float>(size.x), static_cast<float>(size.y));
        Kf::vec2 lo(static_cast<float>(rng.uniform(-1.2, 1.2)), static_cast<float>(rng.uniform(-1.2, 1.2)));
        Kf::vec2 hi(lo.x + static_cast<float>(rng.uniform(0.0, rng.below(2) ? 1e-3 : 1.0)),
                    lo.y + static_cast<float>(rng.uniform(0.0, rng.below(2) ? 1e-3 : 1.0)));
        Kf::ivec4 rect = Kf::box_cell_rect(lo, hi, image);
        Kf::ivec4 gl_rect = old_gl_rect(lo, hi, image);
        CHECK(rect == gl_rect);
        // render_cpu's rect (double, no margin) is inside: no sample it tested is lost.
        glm::ivec4 cpu = old_cpu_pixel_rect(lo.x, lo.y, hi.x, hi.y, size.x, size.y);
        if (cpu.x <= cpu.z && cpu.y <= cpu.w) {
            CHECK(in_rect(rect, glm::ivec2(cpu.x, cpu.y)));
            CHECK(in_rect(rect, glm::ivec2(cpu.z, cpu.w)));
        }
    }
}

TEST_CASE_TEMPLATE("box_cell_rect holds every sample whose NDC lies in the box", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(0xb0c5ull + sizeof(Real));
    int edges = 0, clamped = 0;
    for (int n = 0; n < 200000; ++n) {
        glm::ivec2 size = image_size_of(rng);
        // Pixel samples (scale 1) or an interleave lattice of scale^2 cells per pixel.
        int scale = rng.below(2) ? 1 : 1 + rng.below(5);
        Kf::vec2 image(static_cast<float>(size.x), static_cast<float>(size.y));
        glm::ivec2 cell;
        Kf::vec2 sample;
        if (scale == 1) {
            cell = glm::ivec2(rng.below(size.x), rng.below(size.y));
            if (rng.below(8) == 0) cell = glm::ivec2(size.x - 1, rng.below(2) ? 0 : size.y - 1);  // the image's edge
            sample = Kf::pixel_sample_ndc(cell, Kf::vec2(offset_coordinate(rng), offset_coordinate(rng)), image);
        } else {
            cell = glm::ivec2(rng.below(size.x * scale), rng.below(size.y * scale));
            Kf::vec2 jitter(offset_coordinate(rng), offset_coordinate(rng));
            sample = Kf::interleaved_sample_ndc(cell, scale, jitter, image);
        }
        typename K::vec2 lo, hi;
        box_around<K>(rng, typename K::vec2(sample), lo, hi);
        typename K::vec2 s(sample);
        if (s.x == lo.x || s.y == hi.y) ++edges;
        REQUIRE(s.x >= lo.x);
        REQUIRE(s.x <= hi.x);
        REQUIRE(s.y >= lo.y);
        REQUIRE(s.y <= hi.y);
        typename K::vec2 cells(static_cast<Real>(size.x * scale), static_cast<Real>(size.y * scale));
        typename K::ivec4 rect = K::box_cell_rect(lo, hi, cells);
        if (lo.x < Real(-1) || hi.x > Real(1) || lo.y < Real(-1) || hi.y > Real(1)) ++clamped;
        CAPTURE(size.x);
        CAPTURE(size.y);
        CAPTURE(scale);
        CAPTURE(cell.x);
        CAPTURE(cell.y);
        CHECK(in_rect(rect, cell));
        CHECK(rect.x >= 0);
        CHECK(rect.y >= 0);
        CHECK(rect.z < size.x * scale);
        CHECK(rect.w < size.y * scale);
    }
    CHECK(edges > 1000);
    CHECK(clamped > 1000);
    // Off screen: empty.
    typename K::vec2 cells(Real(64), Real(48));
    auto box_of = [](double x0, double y0, double x1, double y1) {
        return typename K::vec4(static_cast<Real>(x0), static_cast<Real>(y0), static_cast<Real>(x1), static_cast<Real>(y1));
    };
    for (typename K::vec4 box : {box_of(1.01, -0.5, 2, 0.5), box_of(-3, -0.5, -1.01, 0.5), box_of(-0.5, 1.01, 0.5, 2),
                                 box_of(-0.5, -3, 0.5, -1.01)}) {
        typename K::ivec4 rect = K::box_cell_rect(typename K::vec2(box.x, box.y), typename K::vec2(box.z, box.w), cells);
        CHECK(rect == typename K::ivec4(0, 0, -1, -1));
    }
    // A sub-pixel box inside one pixel: that pixel only.
    typename K::vec4 inside = K::pixel_rect_ndc(typename K::ivec4(10, 20, 10, 20), cells);
    typename K::vec2 centre((inside.x + inside.z) / Real(2), (inside.y + inside.w) / Real(2));
    CHECK(K::box_cell_rect(centre, centre, cells) == typename K::ivec4(10, 20, 10, 20));
}

TEST_CASE("interleaved_cell and interleaved_sample_ndc are render_interleave's arithmetic") {
    Rng rng(0x1e7ull);
    for (int n = 0; n < 20000; ++n) {
        int tile_w = 2 + rng.below(15), side = 1 + rng.below(6);
        glm::ivec2 tile(rng.below(300), rng.below(300));
        int slot = rng.below(tile_w * tile_w);
        CHECK(Kf::interleaved_cell(tile, slot, tile_w) ==
              glm::ivec2(tile.x * tile_w + slot % tile_w, tile.y * tile_w + slot / tile_w));
        glm::ivec2 size = image_size_of(rng);
        glm::ivec2 cell(rng.below(size.x * side), rng.below(size.y * side));
        auto seed = static_cast<std::uint32_t>(rng.below(1 << 30));
        glm::vec2 jitter = patternsf::interleaved_jitter(static_cast<std::uint32_t>(cell.x), static_cast<std::uint32_t>(cell.y), seed);
        if (rng.below(8) == 0) jitter = glm::vec2(below_one());
        Kf::vec2 image(static_cast<float>(size.x), static_cast<float>(size.y));
        CHECK(same_bits2(Kf::interleaved_sample_ndc(cell, side, jitter, image),
                         old_interleaved_ndc(cell.x, cell.y, side, jitter, size.x, size.y)));
    }
}

TEST_CASE_TEMPLATE("interleave placement: tile slots cover each tile once, samples lie in their cells", Real, float, double) {
    using K = kernel<Real>;
    // Every tuple once per tile (Fatahalian et al.'s InterleaveUVT, Aqsis'
    // tiles; docs/sampling.md): tuple k of tile t at interleaved_cell(t, tuple_slot[prototype(t) N + k]).
    InterleavedTileOptions options;
    options.width = 4;
    options.seed = 3;
    InterleavedTiles tiles = make_interleaved_tiles(options);
    const int w = tiles.width, count = tiles.tuple_count;
    for (int ty = 0; ty < 5; ++ty) {
        for (int tx = 0; tx < 5; ++tx) {
            std::vector<int> seen(static_cast<std::size_t>(count), 0);
            std::uint32_t prototype = tiles.prototype_of_tile(static_cast<std::uint32_t>(tx), static_cast<std::uint32_t>(ty));
            for (int k = 0; k < count; ++k) {
                int slot = tiles.tuple_slot[static_cast<std::size_t>(prototype) * static_cast<std::size_t>(count) + static_cast<std::size_t>(k)];
                typename K::ivec2 cell = K::interleaved_cell(typename K::ivec2(tx, ty), slot, w);
                CHECK(cell.x / w == tx);
                CHECK(cell.y / w == ty);
                CHECK(tiles.tuple_at(static_cast<std::uint32_t>(cell.x), static_cast<std::uint32_t>(cell.y)) == k);
                ++seen[static_cast<std::size_t>((cell.y % w) * w + cell.x % w)];
            }
            CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
        }
    }
    // Cell (px s + i, py s + j) is pixel (px, py)'s sample j s + i: its NDC
    // lies in that pixel's sub-cell (i, j), up to the rounding of its position.
    Rng rng(0x9e11ull);
    for (int n = 0; n < 20000; ++n) {
        int side = 1 + rng.below(6);
        glm::ivec2 size = image_size_of(rng);
        typename K::ivec2 cell(rng.below(size.x * side), rng.below(size.y * side));
        typename K::vec2 jitter(static_cast<Real>(offset_coordinate(rng)), static_cast<Real>(offset_coordinate(rng)));
        typename K::vec2 image(static_cast<Real>(size.x), static_cast<Real>(size.y));
        typename K::vec2 raster = K::ndc_to_raster(K::interleaved_sample_ndc(cell, side, jitter, image), image);
        Real slack = Real(8) * std::numeric_limits<Real>::epsilon() * static_cast<Real>(std::max(size.x, size.y));
        CHECK(raster.x * static_cast<Real>(side) >= static_cast<Real>(cell.x) - slack * static_cast<Real>(side));
        CHECK(raster.x * static_cast<Real>(side) <= static_cast<Real>(cell.x + 1) + slack * static_cast<Real>(side));
        CHECK(raster.y * static_cast<Real>(side) >= static_cast<Real>(cell.y) - slack * static_cast<Real>(side));
        CHECK(raster.y * static_cast<Real>(side) <= static_cast<Real>(cell.y + 1) + slack * static_cast<Real>(side));
    }
}

TEST_CASE_TEMPLATE("sample_test is the backends' chain: bounds, screen, covers", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(0xc4a1ull + sizeof(Real));
    std::vector<Family> families = all_families();
    long covered = 0, missed = 0, culled = 0;
    for (int n = 0; n < 4000; ++n) {
        Config cfg = make_config(rng, families[static_cast<std::size_t>(n) % families.size()]);
        typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
        Real near = static_cast<Real>(cfg.near);
        typename K::vec2 s_lo(cfg.s_lo), s_hi(cfg.s_hi);
        for (int method = 0; method < 4; ++method) {
            typename K::ScreenBound screen = K::screen_bound(tri, near, method);
            typename K::SampleBounds bounds = K::sample_bounds(tri, s_lo, s_hi, method);
            for (int k = 0; k < 8; ++k) {
                Sample5 d = make_sample(rng, cfg);
                typename K::vec2 s(d.s), uv(d.uv);
                Real t = static_cast<Real>(d.t);
                bool check_screen = rng.below(4) != 0;
                // render_cpu's test_sample, written out.
                int expected = BC_SAMPLE_CULLED;
                Real expected_depth = Real(0);
                if (K::sample_passes(bounds, uv, t) && (!check_screen || K::screen_contains(screen, s))) {
                    expected = K::covers(tri, s, uv, t, near, expected_depth) ? BC_SAMPLE_COVERED : BC_SAMPLE_MISSED;
                }
                Real depth = Real(-1);
                int got = K::sample_test(tri, screen, check_screen, bounds, s, uv, t, near, depth);
                CHECK(got == expected);
                CHECK(same_bits(depth, expected_depth));
                if (got == BC_SAMPLE_COVERED) CHECK(depth >= near);
                // The methods' and GL's form, without lens/time bounds: screen_contains, then covers.
                Real plain_depth = Real(0);
                int plain = !K::screen_contains(screen, s) ? BC_SAMPLE_CULLED
                            : K::covers(tri, s, uv, t, near, plain_depth) ? BC_SAMPLE_COVERED
                                                                          : BC_SAMPLE_MISSED;
                CHECK(K::sample_test(tri, screen, true, K::no_sample_bounds(), s, uv, t, near, depth) == plain);
                covered += got == BC_SAMPLE_COVERED;
                missed += got == BC_SAMPLE_MISSED;
                culled += got == BC_SAMPLE_CULLED;
            }
        }
    }
    CHECK(covered > 1000);
    CHECK(missed > 1000);
    CHECK(culled > 1000);
}

TEST_CASE("no_sample_bounds passes every sample of every pattern (sample_test without bounds is the old chain)") {
    const Kf::SampleBounds none = Kf::no_sample_bounds();
    for (std::uint32_t p = 0; p < 4000; ++p) {
        std::uint32_t px = p % 61, py = p / 61, spp = 1 + p % 37, seed = p * 2654435761u;
        for (std::uint32_t j = 0; j < spp; j += 5) {
            Kf::PixelSample s = Kf::pixel_sample(px, py, j, spp, seed);
            CHECK(Kf::sample_passes(none, s.lens, s.time));
            s = patternsf::interval_sample(px, py, j, spp, seed);
            CHECK(Kf::sample_passes(none, s.lens, s.time));
        }
        Kf::PixelSample accum = patternsf::accum_sample(p, seed);
        CHECK(Kf::sample_passes(none, accum.lens, accum.time));
        Kf::vec3 tuple = patternsf::interleaved_tuple(p);
        CHECK(Kf::sample_passes(none, Kf::vec2(tuple.x, tuple.y), tuple.z));
    }
}

TEST_CASE_TEMPLATE("depth rules: strict nearer on the CPU, near / w with the lower index on the GPU", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(0xde9ull);
    const Real inf = std::numeric_limits<Real>::infinity();
    CHECK(K::depth_nearer(Real(1), inf));
    CHECK_FALSE(K::depth_nearer(Real(2), Real(2)));  // ties: the first (lower index) stays
    CHECK_FALSE(K::depth_nearer(std::numeric_limits<Real>::quiet_NaN(), inf));
    for (int n = 0; n < 20000; ++n) {
        Real near = static_cast<Real>(rng.uniform(1e-3, 1.0));
        Real a = near * static_cast<Real>(rng.uniform(1.0, rng.below(2) ? 2.0 : 1e6));
        Real b = rng.below(8) == 0 ? a : near * static_cast<Real>(rng.uniform(1.0, 1e3));
        // The old expressions: render_cpu's z < depth; render_common.glsl's
        // clamp(near / depth, 0, 1); render_static_group.frag's winner.
        CHECK(K::depth_nearer(a, b) == (a < b));
        Real key_a = K::depth_key(near, a), key_b = K::depth_key(near, b);
        CHECK(same_bits(key_a, std::min(std::max(near / a, Real(0)), Real(1))));
        CHECK(key_a > Real(0));
        CHECK(key_a <= Real(1));
        auto ia = static_cast<std::uint32_t>(rng.below(100)), ib = static_cast<std::uint32_t>(rng.below(100));
        CHECK(K::depth_key_wins(key_a, ia, key_b, ib) == (key_a > key_b || (key_a == key_b && ia < ib)));
        // The two rules order alike: a strictly nearer sample never loses on the GPU to a farther one.
        if (K::depth_nearer(a, b)) CHECK(key_a >= key_b);
    }
}

TEST_CASE_TEMPLATE("camera_coc is thin_lens_coc with CameraModel's no-lens case", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(0xc0cull);
    for (int n = 0; n < 20000; ++n) {
        float k = static_cast<float>(rng.uniform(0.1, 20.0));
        float radius = rng.below(4) == 0 ? 0.0f : static_cast<float>(rng.uniform(1e-4, 2.0));
        float focus = static_cast<float>(rng.uniform(0.05, 100.0));
        if (radius == 0.0f && rng.below(2)) focus = rng.below(2) ? 0.0f : std::numeric_limits<float>::infinity();
        if constexpr (sizeof(Real) == sizeof(float)) {
            // CameraModel's a_x = -k_x R, b_x = R > 0 ? k_x R / F : 0.
            CHECK(same_bits2(Kf::camera_coc(k, radius, focus), old_coc(k, radius, focus)));
        }
        typename K::vec2 ab = K::camera_coc(Real(k), Real(radius), Real(focus));
        CHECK(same_bits(ab.x, -Real(k) * Real(radius)));
        if (radius > 0.0f) {
            CHECK(same_bits2(ab, K::thin_lens_coc(Real(k), Real(radius), Real(focus))));
            // Sharp at the focus depth.
            CHECK(std::abs(K::coc_at(ab, Real(focus))) <= Real(4) * std::numeric_limits<Real>::epsilon() * std::abs(ab.x));
        } else {
            CHECK(same_bits(ab.y, Real(0)));
        }
    }
}
