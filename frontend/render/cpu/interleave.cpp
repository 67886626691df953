#include "render/cpu/methods.hpp"

#include "render/common/camera_model.hpp"
#include "render/cpu/method_runner.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace blurcull::frontend {

using cpu_methods::Counters;
using cpu_methods::K;

namespace {

// The lattice of width * scale x height * scale cells and the tiles over it.
struct TileLattice {
    int cells_x = 0, cells_y = 0, tiles_x = 0, tiles_y = 0;
};

TileLattice tile_lattice(const MethodPlan& plan, int width, int height) {
    TileLattice lattice;
    const int tile_w = plan.tiles.width;
    lattice.cells_x = width * plan.scale;
    lattice.cells_y = height * plan.scale;
    lattice.tiles_x = (lattice.cells_x + tile_w - 1) / tile_w;
    lattice.tiles_y = (lattice.cells_y + tile_w - 1) / tile_w;
    return lattice;
}

// The prototype tile each tile of the lattice copies, row by row.
std::vector<std::uint32_t> tile_prototypes(const InterleavedTiles& tiles, const TileLattice& lattice) {
    std::vector<std::uint32_t> prototypes(static_cast<std::size_t>(lattice.tiles_x) *
                                          static_cast<std::size_t>(lattice.tiles_y));
    for (int ty = 0; ty < lattice.tiles_y; ++ty) {
        for (int tx = 0; tx < lattice.tiles_x; ++tx) {
            prototypes[static_cast<std::size_t>(ty) * lattice.tiles_x + tx] =
                tiles.prototype_of_tile(static_cast<std::uint32_t>(tx), static_cast<std::uint32_t>(ty));
        }
    }
    return prototypes;
}

// The one sample of tuple k in each tile: its lattice cell and NDC position
// (the NDC is left unset for cells past the image's edge).
struct TupleSamples {
    std::vector<glm::ivec2> cells;
    std::vector<K::vec2> ndcs;
};

TupleSamples tuple_samples_in_tiles(const MethodPlan& plan, const TileLattice& lattice,
                                    const std::vector<std::uint32_t>& prototypes, int k, std::uint32_t seed) {
    const InterleavedTiles& tiles = plan.tiles;
    const int side = plan.scale, tile_w = tiles.width;
    const auto n = static_cast<std::size_t>(tiles.tuple_count);
    const std::size_t tuple_base = static_cast<std::size_t>(k);
    TupleSamples samples;
    samples.cells.resize(prototypes.size());
    samples.ndcs.resize(prototypes.size());
    for (int ty = 0; ty < lattice.tiles_y; ++ty) {
        for (int tx = 0; tx < lattice.tiles_x; ++tx) {
            const std::size_t tile = static_cast<std::size_t>(ty) * lattice.tiles_x + tx;
            const int slot = tiles.tuple_slot[prototypes[tile] * n + tuple_base];
            const glm::ivec2 cell = kernelf::interleaved_cell(glm::ivec2(tx, ty), slot, tile_w);
            samples.cells[tile] = cell;
            if (cell.x >= lattice.cells_x || cell.y >= lattice.cells_y) continue;  // past the image's edge
            const glm::vec2 jitter = patternsf::interleaved_jitter(static_cast<std::uint32_t>(cell.x),
                                                                   static_cast<std::uint32_t>(cell.y), seed);
            samples.ndcs[tile] =
                K::vec2(kernelf::interleaved_sample_ndc(cell, side, jitter, plan.model.image_size()));
        }
    }
    return samples;
}

}  // namespace

RenderResult render_interleave(const Scene& scene, const RenderSettings& settings, const InterleaveOptions& options,
                               std::vector<std::uint32_t>* sample_ids) {
    cpu_methods::MethodRender render(scene, settings, RenderMethod::interleave, options);
    const MethodPlan& plan = render.plan();
    const CameraModel& model = plan.model;
    const InterleavedTiles& tiles = plan.tiles;
    const int side = plan.scale;
    const int width = settings.width, height = settings.height, spp = settings.spp;
    const int tile_w = tiles.width, n = tiles.tuple_count;
    const TileLattice lattice = tile_lattice(plan, width, height);
    const int tiles_x = lattice.tiles_x;
    const std::vector<std::uint32_t> prototypes = tile_prototypes(tiles, lattice);
    const std::size_t sample_count = static_cast<std::size_t>(width) * height * spp;
    std::vector<double> depth(sample_count, std::numeric_limits<double>::infinity());
    std::vector<std::uint32_t> hits(sample_count, no_sample_hit);

    // One work item per tuple: the samples of different tuples are disjoint.
    const double near = model.znear;
    const SurfaceShader& shader = *plan.shader;
    const Counters counters = render.run_raster(n, [&](int k, Counters& local) {
        const kernelf::PixelSample& tuple = plan.pass_samples[static_cast<std::size_t>(k)];
        const K::vec2 uv(tuple.lens);
        const double t = tuple.time;
        const TupleSamples tuple_samples = tuple_samples_in_tiles(plan, lattice, prototypes, k, settings.seed);
        const std::vector<glm::ivec2>& cells = tuple_samples.cells;
        const std::vector<K::vec2>& ndcs = tuple_samples.ndcs;
        cpu_methods::for_each_pass_box(plan, k, local, [&](std::uint32_t triangle, const K::MovingTriangle& tri,
                                                           const PassBox& box) {
            const CellRect& r = box.rect;
            for (int ty = r.y0 / tile_w; ty <= r.y1 / tile_w; ++ty) {
                for (int tx = r.x0 / tile_w; tx <= r.x1 / tile_w; ++tx) {
                    const std::size_t tile = static_cast<std::size_t>(ty) * tiles_x + tx;
                    const int gx = cells[tile].x, gy = cells[tile].y;
                    if (gx < r.x0 || gx > r.x1 || gy < r.y0 || gy > r.y1) continue;
                    const int px = gx / side, py = gy / side, sx = gx % side, sy = gy % side;
                    const std::size_t sample =
                        (static_cast<std::size_t>(py) * width + px) * spp + static_cast<std::size_t>(sy * side + sx);
                    cpu_methods::test_pass_sample(tri, box.bound, ndcs[tile], uv, t, near, triangle, shader, local,
                                                  depth[sample], hits[sample]);
                }
            }
        });
    });
    return render.finish(hits, counters, sample_ids);
}

}  // namespace blurcull::frontend
