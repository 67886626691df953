#include "render/cpu/frame_setup.hpp"

#include "render/common/moving_triangle.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <thread>

namespace blurcull::frontend::cpu_tiles {
namespace {

// The pixels of each stratum's screen box (kernel stratum_screen_box of
// the triangle's screen bound `whole`), inside its rectangle `r`, appended to
// `rects`. False when they do not pay: the strata's rectangles, on average,
// hold more than 3/4 of r's pixels (a triangle that hardly moves and is
// nearly in focus), so visiting the strata one by one would cost more
// (shorter runs) than it spares; the caller then drops them.
template <class Real>
bool add_stratum_rects(const CameraModel& model, const typename kernel<Real>::MovingTriangle& tri, Real near,
                       const typename kernel<Real>::ScreenBound& whole, const PixelRect& r, SampleStrata strata,
                       HugePageVector<StratumBox<kernel<Real>>>& rects) {
    using K = blurcull::kernel<Real>;
    double area = 0.0;
    // Every sample of the image has |NDC| <= 1; 2 leaves room for their rounding.
    const Real scale = K::depth_floor_scale(tri, typename K::vec2(0, 1), typename K::vec2(-1, 1),
                                            typename K::vec2(-1, 1), Real(2));
    for (int s = 0; s < strata.count(); ++s) {
        typename K::vec2 time, u, v;
        strata.ranges(s, time, u, v);
        const typename K::vec4 box = K::stratum_screen_box(tri, near, whole, time, u, v);
        PixelRect q = box.x > box.z ? PixelRect{0, 0, -1, -1}
                                    : pixel_rect<K>(model, typename K::vec2(box.x, box.y), typename K::vec2(box.z, box.w));
        q = PixelRect{std::max(q.x0, r.x0), std::max(q.y0, r.y0), std::min(q.x1, r.x1), std::min(q.y1, r.y1)};
        rects.push_back(StratumBox<K>{box, q, K::depth_floor(tri, time, scale)});
        if (q.x0 <= q.x1 && q.y0 <= q.y1) area += double(q.x1 - q.x0 + 1) * double(q.y1 - q.y0 + 1);
    }
    const double whole_area = double(r.x1 - r.x0 + 1) * double(r.y1 - r.y0 + 1);
    return area <= 0.75 * whole_area * double(strata.count());
}


}  // namespace

// Each chunk keeps its hull edges apart, then they are joined in triangle order.
template <class Real>
void set_up_triangles(const Scene& scene, const CameraModel& model, int cull, int threads, SampleStrata strata,
                      FrameSetup<Real>& setup) {
    using K = blurcull::kernel<Real>;
    const Real near = static_cast<Real>(model.znear);
    setup.pieces = plan_segment_pieces(scene, model);
    const std::size_t count = setup.pieces.size();
    setup.triangles.resize(count);
    setup.rects.resize(count);
    setup.classes.resize(count);
    setup.bounds.resize(count);
    setup.fast_tests.resize(count);
    setup.strata = strata;
    // Every element of these arrays is written by the worker of its chunk
    // below (HugePageVector's resize leaves them unwritten).
    setup.stratum_boxes.resize(count);
    const std::size_t chunks = static_cast<std::size_t>(std::max(1, std::min(threads, 64)));
    std::vector<std::vector<typename K::vec3>> chunk_edges(chunks);
    std::vector<HugePageVector<StratumBox<K>>>& chunk_rects = setup.stratum_chunks;
    chunk_rects.assign(chunks, {});
    std::vector<std::size_t> chunk_invalid(chunks, 0);
    auto set_up = [&](std::size_t chunk) {
        const std::size_t first = count * chunk / chunks, last = count * (chunk + 1) / chunks;
        // Room for every triangle's strata: address space only until used, and no copies as it grows.
        if (strata.count() > 1) chunk_rects[chunk].reserve((last - first) * static_cast<std::size_t>(strata.count()));
        for (std::size_t i = first; i < last; ++i) {
            setup.triangles[i] = make_segment_triangle<Real>(scene, model, setup.pieces[i]);
            setup.classes[i] = K::classify(setup.triangles[i]);
            setup.rects[i] = PixelRect{0, 0, -1, -1};
            setup.bounds[i] = typename FrameSetup<Real>::StoredBound{};
            setup.fast_tests[i] = CoverageSetup{};
            setup.stratum_boxes[i] = nullptr;
            if (setup.classes[i] == BC_INVALID) {
                ++chunk_invalid[chunk];  // validate_scene checked the input; only overflow gets here
                continue;
            }
            const typename K::ScreenBound bound = K::screen_bound(setup.triangles[i], near, cull);
            if (bound.empty) continue;
            setup.rects[i] = pixel_rect<K>(model, bound.lo, bound.hi);
            const PixelRect& r = setup.rects[i];
            if (r.x0 <= r.x1 && r.y0 <= r.y1) {
                setup.fast_tests[i] = make_coverage_setup<Real>(setup.triangles[i], sample_box(model, r));
                if (strata.count() > 1 && setup.classes[i] != 0 && setup.pieces[i].segments == 1) {
                    const std::size_t offset = chunk_rects[chunk].size();
                    if (add_stratum_rects<Real>(model, setup.triangles[i], near, bound, r, strata, chunk_rects[chunk]))
                        setup.stratum_boxes[i] = chunk_rects[chunk].data() + offset;
                    else
                        chunk_rects[chunk].resize(offset);
                }
            }
            auto& stored = setup.bounds[i];
            stored.lo = bound.lo;
            stored.hi = bound.hi;
            stored.hull_offset = chunk_edges[chunk].size();
            stored.hull_count = bound.hull_count;
            for (int e = 0; e < bound.hull_count; ++e) chunk_edges[chunk].push_back(bound.hull_edge[e]);
        }
    };
    std::vector<std::thread> workers;
    for (std::size_t c = 1; c < chunks; ++c) workers.emplace_back(set_up, c);
    set_up(0);
    for (std::thread& worker : workers) worker.join();
    for (std::size_t c = 0; c < chunks; ++c) {
        const std::size_t base = setup.hull_edges.size();
        for (std::size_t i = count * c / chunks; i < count * (c + 1) / chunks; ++i) setup.bounds[i].hull_offset += base;
        setup.hull_edges.insert(setup.hull_edges.end(), chunk_edges[c].begin(), chunk_edges[c].end());
        setup.invalid += chunk_invalid[c];
    }
}

// The nearest view depth a triangle reaches over the shutter: the smallest w

namespace {

template <class Real>
Real nearest_vertex_depth(const typename kernel<Real>::MovingTriangle& tri) {
    Real w = tri.p[0].z;
    for (int j = 1; j < 6; ++j) w = std::min(w, tri.p[j].z);
    return w;
}


}  // namespace

// each motion-segment window (the pieces' groups, kept in their order) the
// triangles go nearest first, so that the occlusion test finds the tiles'
// samples covered by near triangles before the far ones come: the depth
// rule's winner (nearest, then lowest index) does not depend on the order.
template <class Real>
void bin_triangles(int width, int height, FrameSetup<Real>& setup) {
    setup.tiles_x = (width + tile_size - 1) / tile_size;
    setup.tiles_y = (height + tile_size - 1) / tile_size;
    setup.bins.assign(static_cast<std::size_t>(setup.tiles_x) * setup.tiles_y, {});
    // Each triangle as one 64-bit key: its nearest depth as a float's bits
    // (a non-negative float's bits order as its value; any order gives the
    // same image, so the rounding to float only blurs the ties), then its
    // index. Windows are contiguous runs of indices: each is sorted alone.
    const std::size_t count = setup.rects.size();
    std::vector<std::uint64_t> keys(count);
    for (std::size_t i = 0; i < count; ++i) {
        const Real w = nearest_vertex_depth<Real>(setup.triangles[i]);
        // Behind the eye: first (0); NaN or beyond float: last.
        const float key = w > Real(0) ? static_cast<float>(std::min<Real>(w, std::numeric_limits<float>::max()))
                          : w == w    ? 0.0f
                                      : std::numeric_limits<float>::max();
        std::uint32_t bits = 0;
        std::memcpy(&bits, &key, sizeof bits);
        keys[i] = (std::uint64_t(bits) << 32) | std::uint64_t(i);
    }
    for (std::size_t first = 0; first < count;) {
        std::size_t last = first + 1;
        while (last < count && setup.pieces[last].segment == setup.pieces[first].segment &&
               setup.pieces[last].segments == setup.pieces[first].segments)
            ++last;
        std::sort(keys.begin() + static_cast<std::ptrdiff_t>(first), keys.begin() + static_cast<std::ptrdiff_t>(last));
        first = last;
    }
    for (std::uint64_t key : keys) {
        const std::uint32_t i = static_cast<std::uint32_t>(key & 0xFFFFFFFFu);
        const PixelRect& r = setup.rects[i];
        if (r.x0 > r.x1 || r.y0 > r.y1) continue;
        for (int ty = r.y0 / tile_size; ty <= r.y1 / tile_size; ++ty) {
            for (int tx = r.x0 / tile_size; tx <= r.x1 / tile_size; ++tx) {
                setup.bins[static_cast<std::size_t>(ty) * setup.tiles_x + tx].push_back(i);
            }
        }
    }
}


template void set_up_triangles<float>(const Scene&, const CameraModel&, int, int, SampleStrata, FrameSetup<float>&);
template void set_up_triangles<double>(const Scene&, const CameraModel&, int, int, SampleStrata, FrameSetup<double>&);
template void bin_triangles<float>(int, int, FrameSetup<float>&);
template void bin_triangles<double>(int, int, FrameSetup<double>&);

}  // namespace blurcull::frontend::cpu_tiles
