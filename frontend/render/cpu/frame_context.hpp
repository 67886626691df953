// What every worker of the CPU tile rasterizer shares (FrameContext), and
// the words of its levels (docs/cpu-renderer.md):
//
//   work tile   tile_size x tile_size pixels (16): what the binning sorts
//               triangles into and a worker takes; its samples stay loaded
//               while its triangles are drawn.
//   block       CpuOptions::block pixels (16): the coarser level of the
//               footprint hierarchy, bounded first and skipped whole when its
//               bounds hold nothing. It is what the kernel calls a *tile*
//               (sample_bounds_in_tile, with_tile_planes,
//               BC_CULL_EDGE_PLANES_PER_BLOCK, BC_CULL_HYPERPLANES_PER_TILE).
//   footprint   CpuOptions::footprint pixels (4): the unit per-footprint
//               sample bounds are computed for (the kernel's footprint).
#pragma once

#include "render/common/camera_model.hpp"
#include "render/common/render_types.hpp"
#include "render/common/surface_shading.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/cpu/frame_setup.hpp"
#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>

#include <atomic>
#include <cstdint>
#include <vector>

namespace blurcull::frontend::cpu_tiles {

// The set bits of x, inline (the x86-64 baseline has no POPCNT, and
// __builtin_popcount then calls libgcc once per 32 samples).
constexpr std::uint64_t bit_count(std::uint32_t x) {
    x = x - ((x >> 1) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    x = (x + (x >> 4)) & 0x0F0F0F0Fu;
    return (x * 0x01010101u) >> 24;
}
static_assert(bit_count(0u) == 0 && bit_count(0xFFFFFFFFu) == 32 && bit_count(0x80000001u) == 2);

// What every worker shares: the frame's constants and its setup.
template <class Real>
struct FrameContext {
    const Scene& scene;
    const RenderSettings& settings;
    const CameraModel& model;
    const FrameSetup<Real>& setup;
    const SurfaceShader& shader;  // the alpha test of the raster decision and the resolve
    int cull;         // the cull method, BC_CULL_*
    int cull_traits;  // kernel cull_traits(cull)
    Real near;
    std::uint32_t spp;  // samples per pixel drawn: a progressive pass's, else settings.spp
    int footprint;
    int block;          // a multiple of the footprint
    bool cull_bounds;   // the method bounds lens and time per footprint
    bool time_sorted;   // footprints tile the work tiles: their samples are sorted by time
    // When set, each sample's winning triangle (or no_sample_hit) goes to
    // (*sample_ids)[(py * width + px) * spp + j], for a resolve after the raster.
    std::vector<std::uint32_t>* sample_ids = nullptr;
    // A progressive pass (CpuOptions::sums): its samples are the pattern's
    // first_sample .. first_sample + spp - 1 of settings.spp, added to *sums.
    SampleSums* sums = nullptr;
    std::uint32_t first_sample = 0;
    const std::atomic<bool>* cancel = nullptr;
    // edges: a block gets its edge planes only where it leaves at least this
    // many samples to visit (CpuOptions::edge_min_samples).
    double edge_min_samples = 0;
    bool occlusion = false;  // CpuOptions::occlusion
};

// The triangle a tile is rasterizing, as the rasterizer's parts see it.
template <class K>
struct TileTriangle {
    std::uint32_t index;
    const typename K::MovingTriangle* tri;
    const CoverageSetup* fast;  // its fast coverage test
    // Its screen bound (the rasterizer's, or a stratum's): held by the
    // rasterizer, so that the 24 hull edges are not copied per triangle.
    const typename K::ScreenBound* bound;
    bool needs_bounds;  // the method bounds lens and time, and the triangle moves or is defocused
    bool check_screen;  // false while the footprint is inside the screen bound
    bool share_axes;    // footprint bounds from per-column and per-row axis bounds
};

}  // namespace blurcull::frontend::cpu_tiles
