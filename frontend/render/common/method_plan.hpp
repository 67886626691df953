// What the CPU renderers of interleave, interval and accum
// (render/cpu/methods.hpp) and the GL backend's methods
// (render/gl/gl_sampling_methods.cpp) share: every choice of samples and boxes
// is made here once, so both backends test the same samples against the same
// boxes.
#pragma once

#include "render/common/camera_model.hpp"
#include "render/common/render_types.hpp"
#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/interleaved_tiles.hpp>
#include <blurcull/patterns.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace blurcull::frontend {

class SurfaceShader;

struct InterleaveOptions {
    int tile_width = 6;  // tiles of tile_width^2 lattice cells, N = tile_width^2 tuples (Aqsis: 6)
    int radius = 2;      // window radius of the tile optimisation's cost
};

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
    RenderMethod method = RenderMethod::interleave;
    CameraModel model;
    std::vector<glm::vec3> colours;  // each triangle's flat colour (shade_all)
    // The shading contract's per-hit resolve and alpha mask test
    // (surface_shading.hpp); it refers to the scene the plan was made for.
    std::shared_ptr<const SurfaceShader> shader;
    std::uint32_t seed = 0;  // RenderSettings::seed: interval's and interleave's sample positions
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
    std::vector<std::string> warnings;  // for RenderResult::warnings
};

// Throws std::invalid_argument (bad settings, unknown method, interleave with
// a non-square spp) or SceneError.
MethodPlan make_method_plan(const Scene& scene, const RenderSettings& settings, const InterleaveOptions& options = {});

// The box that pass k tests triangle i (visible) in and the lattice cells
// that can hold a sample in it (box_cell_rect); empty rect when off screen.
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

// One sample as the passes test it: its NDC position, lens position and time.
struct MethodSample {
    glm::vec2 ndc;
    glm::vec2 lens;
    float time;
};

// Where sample j of pixel (px, py) of the plan is (the CPU renderers' and
// the GL shaders' positions): interval, stratum j's interval_sample; accum,
// pass j's offset, lens and time; interleave, the lattice cell (px s + j % s,
// py s + j / s) at its jitter, with the lens and time of the tuple its tile
// holds there (tuple_of_cell, from method_tuple_of_cell).
MethodSample method_sample(const MethodPlan& plan, const std::vector<std::int32_t>& tuple_of_cell, int px, int py,
                           int j);

// Interleave: the tuple of each lattice cell (gy * width * scale + gx); empty
// for the other methods.
std::vector<std::int32_t> method_tuple_of_cell(const MethodPlan& plan, int width, int height);

// Pixel (px, py) = mean of the colours of ids[(py W + px) per_pixel + 0 .. per_pixel - 1]:
// each sample's SurfaceShader::sample_colour at its method_sample (the flat
// colour for a triangle that does not shade per hit), summed in sample order.
Image resolve_method_samples(const Scene& scene, const MethodPlan& plan, const std::vector<std::uint32_t>& ids,
                             int width, int height);

}  // namespace blurcull::frontend
