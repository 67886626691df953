// The CPU backend's frame setup (docs/cpu-renderer.md, "Setup and
// binning"): once per frame, every triangle (motion-segment piece) in clip
// space, its class, pixel rectangle, screen bound, fast-test setup and
// strata boxes, then binned into the work tiles that the tile rasterizer
// (render/cpu/tile_rasterizer.hpp) draws one by one.
#pragma once

#include "render/common/camera_model.hpp"
#include "render/common/huge_page_allocator.hpp"
#include "render/common/motion_segments.hpp"
#include "render/cpu/fast_coverage.hpp"
#include "render/cpu/sample_strata.hpp"
#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace blurcull::frontend::cpu_tiles {

// Pixels per side of a binning and work tile (the unit a worker takes; the
// kernel's "tile" is the CPU's block, frame_context.hpp).
constexpr int tile_size = 16;

struct PixelRect {
    int x0, y0, x1, y1;  // inclusive
};

// The pixels that can hold a sample in the NDC box [lo, hi] (kernel's
// box_cell_rect), clamped to the image; empty (x0 > x1) when it misses it.
template <class K>
PixelRect pixel_rect(const CameraModel& model, typename K::vec2 lo, typename K::vec2 hi) {
    using Real = typename K::real;
    const glm::ivec4 r = K::box_cell_rect(lo, hi, typename K::vec2(Real(model.width), Real(model.height)));
    return PixelRect{r.x, r.y, r.z, r.w};
}

// The NDC box of a pixel rectangle's samples (every pixel of it, whole).
inline SampleBox sample_box(const CameraModel& model, const PixelRect& r) {
    const glm::vec4 top_left = model.pixel_ndc_bounds(r.x0, r.y0);
    const glm::vec4 bottom_right = model.pixel_ndc_bounds(r.x1, r.y1);
    return SampleBox{top_left.x, bottom_right.y, bottom_right.z, top_left.w};
}

// One stratum's screen box (NDC lo.xy, hi.xy) and its pixels.
template <class K>
struct StratumBox {
    typename K::vec4 box;
    PixelRect rect;
    // kernel depth_floor: the stratum's samples of a pixel whose
    // stored depths are all below it are occluded (0: none can be skipped).
    typename K::real depth_floor;
};

// What the setup phase computes once per frame for every triangle: its
// clip-space form, class, pixel rectangle and screen bound, and the tiles it
// is binned into.
template <class Real>
struct FrameSetup {
    using K = blurcull::kernel<Real>;
    // A triangle's screen bound, computed once: its box, and its hull edges
    // (if any) as a range of `hull_edges`.
    struct StoredBound {
        typename K::vec2 lo, hi;
        std::size_t hull_offset = 0;
        int hull_count = 0;
    };
    // The motion-segment piece of each entry below (one whole-shutter piece
    // per scene triangle when K = 1): its source triangle and window.
    std::vector<SegmentPiece> pieces;
    HugePageVector<typename K::MovingTriangle> triangles;
    HugePageVector<PixelRect> rects;
    HugePageVector<int> classes;
    HugePageVector<StoredBound> bounds;
    // The fast coverage test's setup (render/cpu/fast_coverage.hpp), for the
    // samples of the triangle's pixel rectangle.
    HugePageVector<CoverageSetup> fast_tests;
    HugePageVector<typename K::vec3> hull_edges;
    // bbox and hull: the strata the tiles group their samples by, and per
    // moving or defocused triangle (one motion segment) the pixels of each
    // stratum's screen box: strata.count() boxes from stratum_boxes[i]
    // (nullptr: the triangle is not drawn by strata), in the setup chunks'
    // arrays (each reserved whole first, so the pointers stay valid).
    SampleStrata strata;
    std::vector<HugePageVector<StratumBox<K>>> stratum_chunks;
    HugePageVector<const StratumBox<K>*> stratum_boxes;
    std::size_t invalid = 0;  // triangles skipped: their clip coordinates overflow
    int tiles_x = 0, tiles_y = 0;
    std::vector<std::vector<std::uint32_t>> bins;  // per work tile, the triangles whose rectangle meets it

    // The stored bound of triangle i into the kernel's ScreenBound `bound`
    // (its hull edges past hull_count are left as they were: unused).
    void screen_bound(std::size_t i, typename K::ScreenBound& bound) const {
        const StoredBound& stored = bounds[i];
        bound.empty = false;
        bound.lo = stored.lo;
        bound.hi = stored.hi;
        bound.hull_count = stored.hull_count;
        for (int e = 0; e < stored.hull_count; ++e) bound.hull_edge[e] = hull_edges[stored.hull_offset + e];
    }
};

// Sets up every triangle of the scene (FrameSetup above), in parallel over
// `threads` contiguous chunks: the screen bound with cull method `cull`, and
// strata boxes for the moving or defocused one-segment pieces when `strata`
// has more than one stratum.
template <class Real>
void set_up_triangles(const Scene& scene, const CameraModel& model, int cull, int threads, SampleStrata strata,
                      FrameSetup<Real>& setup);

// Bins each triangle into the work tiles its pixel rectangle meets, nearest
// first within each motion-segment window (render/cpu/frame_setup.cpp).
template <class Real>
void bin_triangles(int width, int height, FrameSetup<Real>& setup);

extern template void set_up_triangles<float>(const Scene&, const CameraModel&, int, int, SampleStrata,
                                             FrameSetup<float>&);
extern template void set_up_triangles<double>(const Scene&, const CameraModel&, int, int, SampleStrata,
                                              FrameSetup<double>&);
extern template void bin_triangles<float>(int, int, FrameSetup<float>&);
extern template void bin_triangles<double>(int, int, FrameSetup<double>&);

}  // namespace blurcull::frontend::cpu_tiles
