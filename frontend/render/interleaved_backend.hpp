// CPU renderers of the other published ways to sample motion and defocus blur
// (docs/sampling.md), next to render_cpu's stochastic rasterizer:
//  * interleave — interleaved sampling, Fatahalian et al. 2009's InterleaveUVT
//    with Aqsis 2.0's colour-cornered tiles of (u, v, t) tuples;
//  * interval   — Pixar's INTERVAL: one sample per shutter stratum per pixel,
//    a screen box per stratum;
//  * accum      — the accumulation buffer (Haeberli and Akeley 1990).
// Same scene, camera model, shading, coverage test (kernel<double>::covers),
// z-buffer rule (strict, triangles in index order), resolve and statistics as
// render_cpu; deterministic whatever the thread count. Each throws
// std::invalid_argument for bad settings and SceneError for a bad scene.
#pragma once

#include "render/camera_model.hpp"
#include "render/render_types.hpp"
#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace blurcull::frontend {

struct InterleaveOptions {
    int tile_width = 6;  // tiles of tile_width^2 lattice cells, N = tile_width^2 tuples (Aqsis: 6)
    int radius = 2;      // window radius of the tile optimisation's cost
};

// settings.spp must be a square s^2: pixel (px, py) holds the s x s lattice
// cells (px s + i, py s + j), sample j s + i, each jittered inside its cell
// and taking the (u, v, t) tuple its tile slot holds. For each tuple k the
// triangle is placed at (u, v, t)_k (a static, sharp 2D triangle) and only the
// lattice cells holding tuple k inside its screen box are tested. The tuples
// are rounded to float, like every other pattern's samples.
// stats.bounds_computed counts the placements, bounds_empty those off screen.
// With sample_ids, sample j of pixel p's triangle (or no_sample_hit) goes to
// (*sample_ids)[p * spp + j], p = py * width + px (all three methods).
RenderResult render_interleave(const Scene& scene, const RenderSettings& settings, const InterleaveOptions& options = {},
                               std::vector<std::uint32_t>* sample_ids = nullptr);

// N = settings.spp shutter strata; sample j of a pixel (patternsf::interval_sample)
// has its time in stratum j. Per stratum, each triangle's screen box over that
// sub-interval and the whole lens bounds the pixels whose sample j is tested.
// stats.bounds_computed counts the boxes, bounds_empty those off screen.
RenderResult render_interval(const Scene& scene, const RenderSettings& settings,
                             std::vector<std::uint32_t>* sample_ids = nullptr);

// K = settings.spp pinhole passes; pass k renders the triangles placed at
// (u, v, t)_k with one sample per pixel at one sub-pixel offset, both
// patternsf::accum_sample(k, settings.seed) (Halton points, Cranley-Patterson
// rotated by the seed), z-buffered; a pixel is the mean of its K passes.
// stats.bounds_computed counts the placements, bounds_empty those off screen.
RenderResult render_accum(const Scene& scene, const RenderSettings& settings,
                          std::vector<std::uint32_t>* sample_ids = nullptr);

// "stochastic", "interleave", "interval", "accum".
const std::vector<std::string>& render_method_names();

// Throws std::invalid_argument("unknown render method 'x' (valid: stochastic,
// interleave, interval, accum)") for any other name.
void validate_render_method(const std::string& method);

// Renders with the renderer settings.method names: render_cpu (with default
// CpuOptions) for "stochastic", else one of the above with default options.
RenderResult render_with_method(const Scene& scene, const RenderSettings& settings);

// ---- what the CPU renderers above and the GL backend (gl_methods.cpp) share --
// Every choice of samples and boxes is made here once, so both backends test
// the same samples against the same boxes.

constexpr std::uint32_t no_sample_hit = 0xffffffffu;

// Raster-space rectangle (x right, y down) of lattice cells (pixels when
// scale = 1), inclusive; empty when x0 > x1.
struct CellRect {
    int x0, y0, x1, y1;
    bool empty() const { return x0 > x1 || y0 > y1; }
};

// One frame of interleave, interval or accum: checked input, the double
// precision triangles and colours, and the passes.
struct MethodPlan {
    std::string method;
    CameraModel model;
    std::vector<glm::vec3> colours;
    std::vector<kernel<double>::MovingTriangle> triangles;
    std::vector<bool> visible;  // some sample of the screen may see it (its whole-shutter box)
    bool any_motion = false;
    bool any_defocus = false;
    int passes = 0;     // interleave: N tuples; interval: spp strata; accum: spp pinhole passes
    int scale = 1;      // lattice cells per pixel side: sqrt(spp) for interleave, else 1
    int per_pixel = 1;  // samples per pixel (spp)
    // interleave and accum: pass k's lens and time (and accum's sub-pixel offset).
    std::vector<kernelf::PixelSample> pass_samples;
    InterleavedTiles tiles;  // interleave only
};

// Throws std::invalid_argument (bad settings, unknown method, interleave with
// a non-square spp) or SceneError.
MethodPlan make_method_plan(const Scene& scene, const RenderSettings& settings, const InterleaveOptions& options = {});

// The box that pass k tests triangle i (visible) in and its rectangle of
// lattice cells, one cell wider on each side; empty rect when off screen.
struct PassBox {
    kernel<double>::ScreenBound bound;
    CellRect rect;
};
PassBox method_pass_box(const MethodPlan& plan, int pass, std::size_t triangle);

// Interleave: the lattice (width * scale x height * scale cells) is covered by
// tiles_x x tiles_y tiles of tiles.width^2 cells, each holding every tuple
// once. Element k * tiles_x * tiles_y + ty * tiles_x + tx is tuple k's cell
// (gx, gy) in tile (tx, ty) as gy * width * scale + gx, or no_sample_hit when
// that cell is past the image's edge.
struct InterleaveTupleCells {
    int tiles_x = 0, tiles_y = 0;
    std::vector<std::uint32_t> cells;
};
InterleaveTupleCells interleave_tuple_cells(const MethodPlan& plan, int width, int height);

// Pixel (px, py) = mean of the colours of ids[(py W + px) per_pixel + 0 .. per_pixel - 1].
Image resolve_method_samples(const Scene& scene, const MethodPlan& plan, const std::vector<std::uint32_t>& ids,
                             int width, int height);

}  // namespace blurcull::frontend
