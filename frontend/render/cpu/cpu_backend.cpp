#include "render/cpu/cpu_backend.hpp"

#include "render/common/camera_model.hpp"
#include "render/common/huge_page_allocator.hpp"
#include "render/common/method_plan.hpp"
#include "render/cpu/fast_coverage.hpp"
#include "render/cpu/exact_lanes.hpp"
#include "render/cpu/farthest_depths.hpp"
#include "render/common/moving_triangle.hpp"
#include "render/common/motion_segments.hpp"
#include "render/common/pixel_samples.hpp"
#include "render/common/progress.hpp"
#include "render/common/shading.hpp"
#include "render/common/surface_shading.hpp"
#include "render/cpu/parallel_items.hpp"
#include "render/cpu/sample_chain.hpp"
#include "render/cpu/sample_strata.hpp"
#include "scene/scene_checks.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

namespace blurcull::frontend {
namespace {

// The CPU path runs the kernel in double by default: its bounds are then
// conservative against the very oracle that decides coverage (the property
// tests prove it for double against double), so every culling method gives
// the same image. CpuOptions::precision float runs kernel<float>, the GL
// backend's arithmetic, to compare decisions with it.
using Clock = std::chrono::steady_clock;

constexpr int tile_size = 16;  // pixels per side of a binning and work tile

// The set bits of x, inline (the x86-64 baseline has no POPCNT, and
// __builtin_popcount then calls libgcc once per 32 samples).
constexpr std::uint64_t bit_count(std::uint32_t x) {
    x = x - ((x >> 1) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    x = (x + (x >> 4)) & 0x0F0F0F0Fu;
    return (x * 0x01010101u) >> 24;
}
static_assert(bit_count(0u) == 0 && bit_count(0xFFFFFFFFu) == 32 && bit_count(0x80000001u) == 2);


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
SampleBox sample_box(const CameraModel& model, const PixelRect& r) {
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

template <class K>
struct TileSample {
    typename K::vec2 ndc;
    typename K::vec2 lens;
    typename K::real time;
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

// Sets up every triangle of the scene, in parallel over contiguous chunks;
// each chunk keeps its hull edges apart, then they are joined in triangle order.
template <class Real>
void set_up_triangles(const Scene& scene, const CameraModel& model, int method, int threads, SampleStrata strata,
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
            const typename K::ScreenBound bound = K::screen_bound(setup.triangles[i], near, method);
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
// of its vertices at the shutter's ends (w is linear in time).
template <class Real>
Real nearest_vertex_depth(const typename kernel<Real>::MovingTriangle& tri) {
    Real w = tri.p[0].z;
    for (int j = 1; j < 6; ++j) w = std::min(w, tri.p[j].z);
    return w;
}

// Bins each triangle into the work tiles its pixel rectangle meets. Within
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

// One worker's rasterization of work tiles: its sample, depth and hit
// buffers, and its counters. A tile is loaded (its samples, sorted by time
// per footprint when that pays), its binned triangles rasterized nearest
// first with the depth rule, and resolved into the image.
template <class Real>
class TileRasterizer {
public:
    using K = blurcull::kernel<Real>;
    using Sample = TileSample<K>;

    explicit TileRasterizer(const FrameContext<Real>& frame)
        : frame_(frame),
          sample_count_(static_cast<std::size_t>(tile_size) * tile_size * frame.spp),
          by_time_(sample_count_),
          by_time_t_(sample_count_),
          depth_(sample_count_),
          hit_(sample_count_),
          lanes_(sample_count_),
          time_lanes_(sample_count_),
          shutter_time_(sample_count_),
          in_window_(sample_count_),
          pixel_samples_(frame.spp),
          strata_lanes_(frame.setup.strata.count() > 1 ? sample_count_ : 0),
          strata_slot_(frame.setup.strata.count() > 1 ? sample_count_ : 0),
          stratum_(frame.setup.strata.count() > 1 ? sample_count_ : 0) {}

    // Rasterizes work tile `tile` (row-major over the tiles) into its pixels of `image`.
    void render_tile(int tile, Image& image) {
        const Clock::time_point started = Clock::now();
        const int tx = tile % frame_.setup.tiles_x, ty = tile / frame_.setup.tiles_x;
        window_segment_ = 0;
        window_segments_ = 1;
        window_ = glm::vec2(0.0f, 1.0f);
        x0_ = tx * tile_size;
        y0_ = ty * tile_size;
        x1_ = std::min(x0_ + tile_size, frame_.settings.width) - 1;
        y1_ = std::min(y0_ + tile_size, frame_.settings.height) - 1;
        tw_ = x1_ - x0_ + 1;
        load_samples();
        strata_grouped_ = false;
        footprints_x_ = (tw_ + frame_.footprint - 1) / frame_.footprint;
        if (frame_.time_sorted) sort_footprints_by_time();
        for (std::uint32_t index : frame_.setup.bins[static_cast<std::size_t>(tile)]) {
            const SegmentPiece& piece = frame_.setup.pieces[index];
            if (piece.segment != window_segment_ || piece.segments != window_segments_) enter_window(piece);
            rasterize_triangle(index);
        }
        const Clock::time_point rasterized = Clock::now();
        resolve(image);
        const Clock::time_point resolved = Clock::now();
        raster_seconds += std::chrono::duration<double>(rasterized - started).count();
        resolve_seconds += std::chrono::duration<double>(resolved - rasterized).count();
    }

    // This worker's counts: exact tests, hits, sample bounds set up, and empty ones.
    std::uint64_t tested = 0, hits = 0, bounded = 0, bounded_empty = 0, visited = 0;
    std::uint64_t occluded = 0;  // samples skipped by the occlusion test (CpuOptions::occlusion)
    // This worker's time in its tiles' raster (samples, triangles) and resolve steps.
    double raster_seconds = 0.0, resolve_seconds = 0.0;

private:
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

    // Sample k of the tile in the kernel's precision, from lanes_ (its
    // coordinates are floats: exact in either precision); its time is the
    // current motion-segment window's local time.
    Sample sample(std::size_t k) const {
        return Sample{typename K::vec2(static_cast<Real>(lanes_.sx()[k]), static_cast<Real>(lanes_.sy()[k])),
                      typename K::vec2(static_cast<Real>(lanes_.u()[k]), static_cast<Real>(lanes_.v()[k])),
                      static_cast<Real>(lanes_.t()[k])};
    }
    // Its screen position and lens position as the shader takes them (floats).
    glm::vec2 ndc_of(std::size_t k) const { return glm::vec2(lanes_.fsx()[k], lanes_.fsy()[k]); }
    glm::vec2 lens_of(std::size_t k) const { return glm::vec2(lanes_.fu()[k], lanes_.fv()[k]); }

    std::size_t slot(int px, int py, std::uint32_t j) const {
        return (static_cast<std::size_t>(py - y0_) * tw_ + (px - x0_)) * frame_.spp + j;
    }

    // The tile's samples (the settings' sampler's), with empty depth and hits.
    void load_samples() {
        for (int py = y0_; py <= y1_; ++py) {
            for (int px = x0_; px <= x1_; ++px) {
                const patternsf::SamplerSetup pattern = patternsf::sampler_setup(
                    frame_.settings.sampler, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py),
                    static_cast<std::uint32_t>(frame_.settings.spp), frame_.settings.seed);
                pixel_samples(pattern, frame_.first_sample, frame_.spp, pixel_samples_.data(),
                              lens_samples_for(frame_.model.lens_radius));
                for (std::uint32_t j = 0; j < frame_.spp; ++j) {
                    const kernelf::PixelSample& s = pixel_samples_[j];
                    const std::size_t k = slot(px, py, j);
                    const glm::vec2 ndc = frame_.model.sample_ndc(px, py, s.offset);
                    lanes_.set(k, ndc.x, ndc.y, s.lens.x, s.lens.y, s.time);
                    shutter_time_[k] = s.time;
                    in_window_[k] = 1;
                    depth_[k] = std::numeric_limits<Real>::infinity();
                    hit_[k] = none;
                }
            }
        }
    }

    // The tile's samples by stratum, then pixel (row-major), then index:
    // copied into strata_lanes_ (slots in strata_slot_), stratum s's samples
    // of pixel p from strata_start_[s * pixels + p] (a counting sort).
    void group_by_stratum() {
        const SampleStrata& strata = frame_.setup.strata;
        const std::size_t pixels = static_cast<std::size_t>(tw_) * static_cast<std::size_t>(y1_ - y0_ + 1);
        const std::size_t count = pixels * frame_.spp;
        strata_start_.assign(static_cast<std::size_t>(strata.count()) * pixels + 1, 0);
        for (std::size_t k = 0; k < count; ++k) {
            stratum_[k] = static_cast<std::uint8_t>(strata.of(lanes_.fu()[k], lanes_.fv()[k], lanes_.ft()[k]));
            ++strata_start_[static_cast<std::size_t>(stratum_[k]) * pixels + k / frame_.spp + 1];
        }
        for (std::size_t i = 1; i < strata_start_.size(); ++i) strata_start_[i] += strata_start_[i - 1];
        std::vector<std::uint32_t>& next = strata_next_;
        next.assign(strata_start_.begin(), strata_start_.end() - 1);
        for (std::size_t k = 0; k < count; ++k) {
            const std::uint32_t q = next[static_cast<std::size_t>(stratum_[k]) * pixels + k / frame_.spp]++;
            strata_lanes_.copy(q, lanes_, k);
            strata_slot_[q] = static_cast<std::uint32_t>(k);
        }
        // Every farthest depth is due: triangles may have drawn before the grouping.
        farthest_.reset(strata.count(), tw_, y1_ - y0_ + 1, strata_start_.data(), strata_slot_.data(), depth_.data());
    }

    // Motion segments: the tile's samples as seen by the pieces of one window,
    // each at its local time (kernel::segment_local_time, in float like the
    // samples, so the fast test sees the time covers() sees), and marked when
    // the window does not hold it. The footprints' time order (by_time_t_)
    // stays in shutter time: test_time_run maps a piece's bounds back to it.
    void enter_window(const SegmentPiece& piece) {
        window_segment_ = piece.segment;
        window_segments_ = piece.segments;
        window_ = kernelf::segment_window(piece.segment, piece.segments);
        for (std::size_t k = 0; k < sample_count_; ++k) {
            const float local = kernelf::segment_local_time(window_, shutter_time_[k]);
            in_window_[k] = kernelf::segment_holds(window_, shutter_time_[k]) ? 1 : 0;
            lanes_.set_time(k, local);
        }
        if (frame_.time_sorted)
            for (std::size_t q = 0; q < by_time_.size(); ++q) time_lanes_.set_time(q, lanes_.ft()[by_time_[q]]);
    }

    // Per footprint of the tile's grid, its samples sorted by time (copied
    // into time_lanes_, slots in by_time_), so that a footprint's bounds
    // visit only the contiguous run of their shutter interval.
    void sort_footprints_by_time() {
        const int footprint = frame_.footprint;
        const int th = y1_ - y0_ + 1;
        const int footprints_y = (th + footprint - 1) / footprint;
        footprint_start_.assign(static_cast<std::size_t>(footprints_x_) * footprints_y + 1, 0);
        std::size_t next = 0;
        for (int fy = 0; fy < footprints_y; ++fy) {
            for (int fx = 0; fx < footprints_x_; ++fx) {
                const std::size_t first = next;
                footprint_start_[static_cast<std::size_t>(fy) * footprints_x_ + fx] = first;
                for (int py = y0_ + fy * footprint; py <= std::min(y1_, y0_ + fy * footprint + footprint - 1); ++py)
                    for (int px = x0_ + fx * footprint; px <= std::min(x1_, x0_ + fx * footprint + footprint - 1); ++px)
                        for (std::uint32_t j = 0; j < frame_.spp; ++j)
                            by_time_[next++] = static_cast<std::uint32_t>(slot(px, py, j));
                std::sort(by_time_.begin() + static_cast<std::ptrdiff_t>(first),
                          by_time_.begin() + static_cast<std::ptrdiff_t>(next),
                          [&](std::uint32_t a, std::uint32_t b) { return lanes_.ft()[a] < lanes_.ft()[b]; });
                for (std::size_t q = first; q < next; ++q) {
                    time_lanes_.copy(q, lanes_, by_time_[q]);
                    by_time_t_[q] = shutter_time_[by_time_[q]];
                }
            }
        }
        footprint_start_.back() = next;
    }

    // The triangle being rasterized.
    struct Current {
        std::uint32_t index;
        const typename K::MovingTriangle* tri;
        const CoverageSetup* fast;  // its fast coverage test
        // Its screen bound (bound_, or a stratum's in stratum_bound_): held
        // by the rasterizer, so that the 24 hull edges are not copied per triangle.
        const typename K::ScreenBound* bound;
        bool needs_bounds;  // the method bounds lens and time, and the triangle moves or is defocused
        bool check_screen;  // false while the footprint is inside the screen bound
        bool share_axes;    // footprint bounds from per-column and per-row axis bounds
    };

    // One axis's bounds per footprint column (row) of the triangle's
    // rectangle, computed when first needed.
    struct AxisCache {
        std::vector<typename K::SampleAxisBounds> bounds;
        std::vector<char> ready;
        int origin = 0;  // first pixel of column (row) 0

        void reset(int first, int last, int footprint) {
            origin = first - first % footprint;
            ready.assign(static_cast<std::size_t>((last - origin) / footprint + 1), 0);
            bounds.resize(ready.size());
        }
        template <class Compute>
        const typename K::SampleAxisBounds& get(int pixel, int footprint, Compute compute) {
            const std::size_t i = static_cast<std::size_t>((pixel - origin) / footprint);
            if (!ready[i]) {
                bounds[i] = compute();
                ready[i] = 1;
            }
            return bounds[i];
        }
    };

    // NDC box (lo.xy, hi.xy) of the pixels [px0, px1] x [py0, py1] (rows grow downwards).
    typename K::vec4 footprint(int px0, int py0, int px1, int py1) const {
        return typename K::vec4(kernelf::pixel_rect_ndc(glm::ivec4(px0, py0, px1, py1), frame_.model.image_size()));
    }

    // The sample bounds of a block or footprint, counted; a footprint's from
    // its block's bounds `tile` when given (kernel::sample_bounds_in_tile).
    typename K::SampleBounds bounds_of(const Current& current, int px0, int py0, int px1, int py1,
                                       const typename K::SampleBounds* tile = nullptr) {
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const typename K::vec2 lo(box.x, box.y), hi(box.z, box.w);
        typename K::SampleBounds sb = tile ? K::sample_bounds_in_tile(*current.tri, lo, hi, frame_.cull, *tile)
                                           : K::sample_bounds(*current.tri, lo, hi, frame_.cull);
        ++bounded;
        if (sb.empty) ++bounded_empty;
        return sb;
    }

    // Edge-plane bounds of a block (BC_CULL_EDGE_PLANES_PER_BLOCK): its
    // bounds without planes, and the planes only where the samples it leaves
    // to visit (its pixels' samples in its shutter interval) are enough to
    // repay their setup; elsewhere the block's footprints are culled without
    // them (fewer culls, never a wrong one).
    typename K::SampleBounds edge_block_bounds(const Current& current, int px0, int py0, int px1, int py1) {
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const typename K::vec2 lo(box.x, box.y), hi(box.z, box.w);
        typename K::SampleBounds sb = K::sample_bounds_without_planes(*current.tri, lo, hi, frame_.cull);
        ++bounded;
        if (!sb.empty) {
            const typename K::vec2 range = K::sample_time_range(sb);
            const double share = std::clamp(double(range.y) - double(range.x), 0.0, 1.0);
            const double visits = double((px1 - px0 + 1) * (py1 - py0 + 1)) * double(frame_.spp) * share;
            if (visits >= frame_.edge_min_samples) sb = K::add_sample_planes(*current.tri, lo, hi, frame_.cull, sb);
        }
        if (sb.empty) ++bounded_empty;
        return sb;
    }

    // A footprint's shared-axes bounds with its block's planes (kernel
    // with_tile_planes on the footprint's box).
    typename K::SampleBounds with_block_planes(const typename K::SampleBounds& own, int px0, int py0, int px1, int py1,
                                               const typename K::SampleBounds& block) const {
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        return K::with_tile_planes(typename K::vec2(box.x, box.y), typename K::vec2(box.z, box.w), frame_.cull, own,
                                   block);
    }

    // The sample bounds of a footprint, counted: with share_axes from its
    // column's and its row's axis bounds (the kernel's sample_bounds split
    // in two: the same bounds, each axis computed once per column or row).
    typename K::SampleBounds footprint_bounds(const Current& current, int px0, int py0, int px1, int py1) {
        if (!current.share_axes) return bounds_of(current, px0, py0, px1, py1);
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const int fp = frame_.footprint, method = frame_.cull;
        const typename K::MovingTriangle& tri = *current.tri;
        ++bounded;
        const auto& x = columns_.get(px0, fp, [&] { return K::sample_axis_bounds(tri, 0, box.x, box.z, method); });
        typename K::SampleBounds sb = K::no_sample_bounds();
        sb.empty = true;
        if (!x.empty) {
            const auto& y = rows_.get(py0, fp, [&] { return K::sample_axis_bounds(tri, 1, box.y, box.w, method); });
            sb = K::combine_axis_bounds(x, y);
        }
        if (sb.empty) ++bounded_empty;
        return sb;
    }

    // Blocks of the image grid clipped to the triangle's rectangle; the
    // bounds hold for any footprint. A block whose bounds hold nothing is
    // skipped whole; the others are bounded again per footprint when
    // footprints are smaller than blocks (for edges: the footprint's
    // two-stage bounds with the block's edge planes, set up once per block).
    void rasterize_triangle(std::uint32_t index) {
        const PixelRect& r = frame_.setup.rects[index];
        frame_.setup.screen_bound(index, bound_);
        Current current{index, &frame_.setup.triangles[index], &frame_.setup.fast_tests[index], &bound_,
                        frame_.cull_bounds && frame_.setup.classes[index] != 0, true, false};
        const int rx0 = std::max(r.x0, x0_), rx1 = std::min(r.x1, x1_);
        const int ry0 = std::max(r.y0, y0_), ry1 = std::min(r.y1, y1_);
        // Footprints share their axis bounds where they carry no planes of
        // their own: a cull without planes, or edge planes that come from
        // the block (with_tile_planes adds them). The hyperplanes' footprint
        // test needs each footprint's own bounds.
        const int traits = frame_.cull_traits;
        const bool edges_in_blocks = (traits & BC_CULL_EDGE_PLANES_PER_BLOCK) != 0 && frame_.block > frame_.footprint;
        current.share_axes = current.needs_bounds && ((traits & BC_CULL_ADDS_PLANES) == 0 || edges_in_blocks) &&
                             K::sample_bounds_apply(*current.tri);
        if (current.share_axes) {
            columns_.reset(rx0, rx1, frame_.footprint);
            rows_.reset(ry0, ry1, frame_.footprint);
        }
        // bbox, hull: a moving or defocused triangle stratum by stratum (the
        // setup gives strata only to one-segment pieces, whose samples keep
        // their shutter times).
        if (const StratumBox<K>* boxes = frame_.setup.stratum_boxes[index]) {
            rasterize_by_strata(current, boxes);
            flush_exact(current);
            return;
        }
        const int block = frame_.block, footprint = frame_.footprint;
        for (int by = ry0 - (ry0 % block); by <= ry1; by += block) {
            for (int bx = rx0 - (rx0 % block); bx <= rx1; bx += block) {
                const int bx0 = std::max(bx, rx0), bx1 = std::min(bx + block - 1, rx1);
                const int by0 = std::max(by, ry0), by1 = std::min(by + block - 1, ry1);
                if (!current.needs_bounds) {
                    test_samples(current, bx0, by0, bx1, by1, K::no_sample_bounds());
                    continue;
                }
                // The block's own bound pays only where it can spare several
                // footprint bounds (on one footprint it is the same bound);
                // for edges it also carries the planes its footprints share
                // (sample_bounds_in_tile: their setup once per block).
                const int spanned = (bx1 / footprint - bx0 / footprint + 1) + (by1 / footprint - by0 / footprint + 1);
                // edges: a block with too few samples for its planes to pay
                // (even all of them visited) is culled as clip2 culls it.
                // hyperplane: its planes always come from the block.
                const bool edges_method = (traits & BC_CULL_EDGE_PLANES_PER_BLOCK) != 0;
                const bool hyperplane = (traits & BC_CULL_HYPERPLANES_PER_TILE) != 0;
                const double block_samples = double((bx1 - bx0 + 1) * (by1 - by0 + 1)) * double(frame_.spp);
                const bool edges = (edges_method && block_samples >= frame_.edge_min_samples) || hyperplane;
                typename K::SampleBounds block_bounds = K::no_sample_bounds();
                const bool block_bounded = block > footprint && (spanned > 4 || edges);
                if (block_bounded) {
                    block_bounds = edges_method ? edge_block_bounds(current, bx0, by0, bx1, by1)
                                                : bounds_of(current, bx0, by0, bx1, by1);
                    if (block_bounds.empty) continue;
                    // edges, the block's part of the triangle inside one
                    // footprint: the block's bounds are that footprint's.
                    if (edges && spanned == 2) {
                        test_samples(current, bx0, by0, bx1, by1, block_bounds);
                        continue;
                    }
                }
                const bool planes = (traits & BC_CULL_ADDS_PLANES) != 0 && K::plane_pieces(block_bounds) > 0;
                for (int fy = by0 - (by0 % footprint); fy <= by1; fy += footprint) {
                    for (int fx = bx0 - (bx0 % footprint); fx <= bx1; fx += footprint) {
                        const int px0 = std::max(fx, bx0), px1 = std::min(fx + footprint - 1, bx1);
                        const int py0 = std::max(fy, by0), py1 = std::min(fy + footprint - 1, by1);
                        // edges: the footprint's two-stage bounds (from the
                        // shared axes) with the block's planes.
                        const typename K::SampleBounds sb =
                            !planes ? footprint_bounds(current, px0, py0, px1, py1)
                            : current.share_axes
                                ? with_block_planes(footprint_bounds(current, px0, py0, px1, py1), px0, py0, px1, py1,
                                                    block_bounds)
                                : bounds_of(current, px0, py0, px1, py1, &block_bounds);
                        if (!sb.empty) test_samples(current, px0, py0, px1, py1, sb);
                    }
                }
            }
        }
        flush_exact(current);
    }

    // A moving or defocused triangle under bbox or hull, stratum by stratum:
    // each stratum's samples only in the pixels of its screen box (the
    // setup's stratum_boxes), through test_run with the stratum's box as the
    // screen bound. Its per-sample test runs only with a hull (hull): for
    // bbox the box chose the pixels, and the few samples per pixel it would
    // cull cost more to test than the fast test spends on them.
    void rasterize_by_strata(const Current& current, const StratumBox<K>* strata) {
        if (!strata_grouped_) group_by_stratum();  // once per tile, when a triangle first needs it
        strata_grouped_ = true;
        // No lens or time bounds here (bbox, hull): test_run's chain is the screen test alone.
        static const typename K::SampleBounds no_bounds = K::no_sample_bounds();
        const std::size_t pixels = static_cast<std::size_t>(tw_) * static_cast<std::size_t>(y1_ - y0_ + 1);
        const auto slot_of = [this](std::size_t q) { return static_cast<std::size_t>(strata_slot_[q]); };
        Current stratum = current;
        stratum.check_screen = bound_.hull_count > 0;
        stratum_bound_.empty = false;
        stratum_bound_.hull_count = bound_.hull_count;
        for (int e = 0; e < bound_.hull_count; ++e) stratum_bound_.hull_edge[e] = bound_.hull_edge[e];
        stratum.bound = &stratum_bound_;
        for (int s = 0; s < frame_.setup.strata.count(); ++s) {
            const PixelRect& r = strata[s].rect;
            const int x0 = std::max(r.x0, x0_), x1 = std::min(r.x1, x1_);
            const int y0 = std::max(r.y0, y0_), y1 = std::min(r.y1, y1_);
            if (x0 > x1 || y0 > y1) continue;
            stratum_bound_.lo = typename K::vec2(strata[s].box.x, strata[s].box.y);
            stratum_bound_.hi = typename K::vec2(strata[s].box.z, strata[s].box.w);
            // Occlusion off: a floor no stored depth is below.
            const Real floor = frame_.occlusion ? strata[s].depth_floor : Real(0);
            const bool occludable = floor > Real(0);
            // Stratum s's samples of pixels [from, to) of tile row py: one
            // contiguous run of strata_lanes_ (first, count).
            const auto run = [&](int py, int from, int to) {
                const std::size_t row = static_cast<std::size_t>(s) * pixels +
                                        static_cast<std::size_t>(py - y0_) * static_cast<std::size_t>(tw_) -
                                        static_cast<std::size_t>(x0_);
                const std::uint32_t first = strata_start_[row + static_cast<std::size_t>(from)];
                return std::pair<std::uint32_t, std::uint32_t>{first,
                                                               strata_start_[row + static_cast<std::size_t>(to)] - first};
            };
            // Every sample of the stratum's rectangle is nearer than the
            // triangle can be: nothing to test.
            if (occludable && farthest_.tile(s) < floor) {
                for (int py = y0; py <= y1; ++py) occluded += run(py, x0, x1 + 1).second;
                continue;
            }
            for (int py = y0; py <= y1; ++py) {
                if (!occludable) {
                    const auto [first, count] = run(py, x0, x1 + 1);
                    test_run(stratum, no_bounds, strata_lanes_, first, count, slot_of);
                    continue;
                }
                const std::size_t ly = static_cast<std::size_t>(py - y0_);
                if (farthest_.row(s, ly) < floor) {
                    occluded += run(py, x0, x1 + 1).second;
                    continue;
                }
                // Runs of pixels whose samples of this stratum are not all
                // nearer than the triangle can be.
                const auto hidden = [&](int px) {
                    return farthest_.pixel(s, static_cast<std::size_t>(px - x0_), ly) < floor;
                };
                int px = x0;
                while (px <= x1) {
                    const int hidden_from = px;
                    while (px <= x1 && hidden(px)) ++px;
                    occluded += run(py, hidden_from, px).second;
                    if (px > x1) break;
                    const int run_start = px;
                    while (px <= x1 && !hidden(px)) ++px;
                    const auto [first, count] = run(py, run_start, px);
                    test_run(stratum, no_bounds, strata_lanes_, first, count, slot_of);
                }
            }
        }
    }

    // Tests a footprint's samples that may pass `sb`.
    void test_samples(Current& current, int px0, int py0, int px1, int py1, const typename K::SampleBounds& sb) {
        // The screen bound per footprint first: skip it whole, or spare its
        // samples the per-sample screen test.
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const int state =
            K::screen_footprint(*current.bound, typename K::vec2(box.x, box.y), typename K::vec2(box.z, box.w));
        if (state == BC_FOOTPRINT_OUTSIDE) return;
        if (edge_planes_cull_footprint(sb, px0, py0, px1, py1)) return;
        current.check_screen = state != BC_FOOTPRINT_INSIDE;
        if (frame_.time_sorted && current.needs_bounds && test_time_run(current, px0, py0, px1, py1, sb)) return;
        for (int py = py0; py <= py1; ++py) {
            const std::size_t first = slot(px0, py, 0);
            test_run(current, sb, lanes_, first, static_cast<std::size_t>(px1 - px0 + 1) * frame_.spp,
                     [](std::size_t k) { return k; });
        }
    }

    // The footprint's samples inside the bounds' shutter interval, one
    // contiguous run of its time-sorted copy, when that visits fewer samples
    // than the footprint's rows (false: not worth it, nothing done). The run
    // spans the whole footprint cell of the tile's grid; where the triangle's
    // rectangle clips the cell, the screen test is kept on: the cell's
    // pixels outside the rectangle hold no sample inside the screen bound.
    bool test_time_run(Current& current, int px0, int py0, int px1, int py1, const typename K::SampleBounds& sb) {
        typename K::vec2 range = K::sample_time_range(sb);
        // A motion segment's bounds are in its local time: back to shutter
        // time, inside its window (in float, the samples' precision).
        if (window_segments_ > 1) range = typename K::vec2(kernelf::segment_shutter_range(window_, glm::vec2(range)));
        const int fp = frame_.footprint;
        const int fx = (px0 - x0_) / fp, fy = (py0 - y0_) / fp;
        const int cx0 = x0_ + fx * fp, cy0 = y0_ + fy * fp;
        const int cx1 = std::min(x1_, cx0 + fp - 1), cy1 = std::min(y1_, cy0 + fp - 1);
        const double cell_pixels = double((cx1 - cx0 + 1) * (cy1 - cy0 + 1));
        const double pixels = double((px1 - px0 + 1) * (py1 - py0 + 1));
        const double share = std::max(0.0, double(range.y) - double(range.x));
        if (!(share * cell_pixels < pixels)) return false;
        const std::size_t f = static_cast<std::size_t>(fy) * footprints_x_ + static_cast<std::size_t>(fx);
        const double* times = by_time_t_.data();
        const double* begin = times + footprint_start_[f];
        const double* end = times + footprint_start_[f + 1];
        const double* lo = std::lower_bound(begin, end, double(range.x));
        const double* hi = std::upper_bound(lo, end, double(range.y));
        current.check_screen = current.check_screen || cx0 != px0 || cy0 != py0 || cx1 != px1 || cy1 != py1;
        const auto slot_of = [this](std::size_t i) { return static_cast<std::size_t>(by_time_[i]); };
        // edges: the runs of the shutter pieces whose planes cull the whole
        // footprint are skipped (not visited).
        const int pieces = K::plane_pieces(sb);
        if (pieces > 0 && window_segments_ == 1) {
            const typename K::vec4 pad_box = padded_footprint(px0, py0, px1, py1);
            const typename K::vec2 s_lo(pad_box.x, pad_box.y), s_hi(pad_box.z, pad_box.w);
            for (int q = 0; q < pieces; ++q) {
                if (!K::plane_piece_culls_box(sb, q, s_lo, s_hi)) continue;
                // The piece's samples: after the previous piece's end (which
                // holds its own end), up to its own end.
                const typename K::vec2 piece_time = K::plane_piece_time(sb, q);
                const double* from = q == 0 ? std::lower_bound(lo, hi, double(piece_time.x))
                                            : std::upper_bound(lo, hi, double(piece_time.x));
                const double* to = std::max(from, std::upper_bound(lo, hi, double(piece_time.y)));
                test_run(current, sb, time_lanes_, static_cast<std::size_t>(lo - times),
                         static_cast<std::size_t>(from - lo), slot_of);
                lo = to;
            }
        }
        test_run(current, sb, time_lanes_, static_cast<std::size_t>(lo - times), static_cast<std::size_t>(hi - lo),
                 slot_of);
        return true;
    }

    // edges: whether every shutter piece's planes cull the whole footprint
    // (then none of its samples can pass; not visited).
    bool edge_planes_cull_footprint(const typename K::SampleBounds& sb, int px0, int py0, int px1, int py1) const {
        const int pieces = K::plane_pieces(sb);
        if (pieces == 0) return false;
        const typename K::vec4 box = padded_footprint(px0, py0, px1, py1);
        const typename K::vec2 s_lo(box.x, box.y), s_hi(box.z, box.w);
        for (int q = 0; q < pieces; ++q)
            if (!K::plane_piece_culls_box(sb, q, s_lo, s_hi)) return false;
        return true;
    }

    // The NDC box of a footprint grown by a few float roundings: it holds
    // every sample position of its pixels (floats), with room to spare.
    typename K::vec4 padded_footprint(int px0, int py0, int px1, int py1) const {
        const typename K::vec4 box = footprint(px0, py0, px1, py1);
        const Real ulps = Real(8) * Real(std::numeric_limits<float>::epsilon());
        const Real pad_x = ulps * std::max(Real(1), std::max(std::abs(box.x), std::abs(box.z)));
        const Real pad_y = ulps * std::max(Real(1), std::max(std::abs(box.y), std::abs(box.w)));
        return typename K::vec4(box.x - pad_x, box.y - pad_y, box.z + pad_x, box.w + pad_y);
    }

    // Samples first .. first + count - 1 of `lanes` (slot_of(i) the slot of
    // its sample i), 32 at a time: the culls (samples_passing, the kernel's
    // chain), the fast test on those that passed, covers on what it kept.
    template <class SlotOf>
    void test_run(const Current& current, const typename K::SampleBounds& sb, const SampleLanes& lanes,
                  std::size_t first, std::size_t count, SlotOf slot_of) {
        visited += count;
        for (std::size_t done = 0; done < count; done += 32) {
            const std::size_t at = first + done;
            const int n = static_cast<int>(std::min<std::size_t>(32, count - done));
            std::uint32_t passed =
                current.needs_bounds ? samples_passing<Real>(*current.bound, current.check_screen, sb, lanes, at, n)
                                     : samples_passing_screen<Real>(*current.bound, current.check_screen, lanes, at, n);
            if (window_segments_ > 1) {
                // Another motion segment's time: culled.
                for (std::uint32_t bits = passed; bits != 0; bits &= bits - 1) {
                    const std::uint32_t i = static_cast<std::uint32_t>(__builtin_ctz(bits));
                    if (!in_window_[slot_of(at + i)]) passed &= ~(1u << i);
                }
            }
            if (passed == 0) continue;
            tested += bit_count(passed);
            const std::uint32_t kept = may_cover32(*current.fast, lanes.fsx() + at, lanes.fsy() + at, lanes.fu() + at,
                                                   lanes.fv() + at, lanes.ft() + at, passed);
            for (std::uint32_t maybe = passed & kept; maybe != 0; maybe &= maybe - 1)
                test_exactly(current, slot_of(at + static_cast<std::size_t>(__builtin_ctz(maybe))));
        }
    }

    // The exact test of a sample the fast test kept (sample_test's last
    // step), and the depth rule. In double the samples wait in `pending_`
    // and go through covers four at a time (covers4: covers' verdicts and
    // depths bit for bit); flush_exact at the end of each triangle keeps the
    // triangle order of the depth rule.
    void test_exactly(const Current& current, std::size_t k) {
        if constexpr (std::is_same_v<Real, double>) {
            pending_[pending_count_++] = k;
            if (pending_count_ == pending_.size()) flush_exact(current);
        } else {
            const Sample s = sample(k);
            Real z = Real(0);
            if (K::covers(*current.tri, s.ndc, s.lens, s.time, frame_.near, z)) record_hit(current, k, z);
        }
    }

    // covers4 on the pending samples (the last one repeated into unused lanes).
    void flush_exact(const Current& current) {
        if constexpr (std::is_same_v<Real, double>) {
            if (pending_count_ == 0) return;
            double sx[4], sy[4], u[4], v[4], t[4], z[4];
            for (std::size_t i = 0; i < 4; ++i) {
                const std::size_t k = pending_[std::min(i, pending_count_ - 1)];
                sx[i] = lanes_.sx()[k];
                sy[i] = lanes_.sy()[k];
                u[i] = lanes_.u()[k];
                v[i] = lanes_.v()[k];
                t[i] = lanes_.t()[k];
            }
            const std::uint32_t covered = covers4(*current.tri, sx, sy, u, v, t, frame_.near, z);
            for (std::size_t i = 0; i < pending_count_; ++i)
                if ((covered >> i) & 1u) record_hit(current, pending_[i], z[i]);
            pending_count_ = 0;
        } else {
            (void)current;
        }
    }

    // A covered sample at depth z: the alpha mask, the count, the depth rule.
    void record_hit(const Current& current, std::size_t k, Real z) {
        // The scene triangle wins, lowest index on equal depths also across
        // the motion-segment groups (within one group the order does it).
        const std::uint32_t source = frame_.setup.pieces[current.index].source;
        // alphaMode MASK: a masked-out sample is not covered (before the
        // depth test); the shader takes the sample's shutter time.
        if (frame_.shader.masked(source) &&
            !frame_.shader.sample_kept(source, ndc_of(k), lens_of(k), shutter_time_[k]))
            return;
        ++hits;
        if (K::depth_nearer(z, depth_[k]) || (z == depth_[k] && source < hit_[k])) {
            depth_[k] = z;
            hit_[k] = source;
            if (strata_grouped_) {
                const std::size_t pixel = k / frame_.spp;
                farthest_.changed(stratum_[k], pixel % static_cast<std::size_t>(tw_),
                                  pixel / static_cast<std::size_t>(tw_));
            }
        }
    }

    // The box filter of the tile's samples into its pixels; a progressive
    // pass continues its pixel's sums from the passes before.
    void resolve(Image& image) const {
        const int summed = static_cast<int>(frame_.first_sample + frame_.spp);
        for (int py = y0_; py <= y1_; ++py) {
            for (int px = x0_; px <= x1_; ++px) {
                const std::size_t at = image.index(px, py);
                glm::vec3 sum = frame_.sums != nullptr ? frame_.sums->colour[at] : glm::vec3(0.0f);
                std::uint32_t covered = frame_.sums != nullptr ? frame_.sums->covered[at] : 0;
                for (std::uint32_t j = 0; j < frame_.spp; ++j) {
                    const std::size_t k = slot(px, py, j);
                    sum += frame_.shader.sample_colour(hit_[k], ndc_of(k), lens_of(k), shutter_time_[k]);
                    covered += hit_[k] != none;
                    if (frame_.sample_ids != nullptr) {
                        const std::size_t pixel = static_cast<std::size_t>(py) * frame_.settings.width + px;
                        (*frame_.sample_ids)[pixel * frame_.spp + j] = hit_[k] == none ? no_sample_hit : hit_[k];
                    }
                }
                if (frame_.sums != nullptr) {
                    frame_.sums->colour[at] = sum;
                    frame_.sums->covered[at] = covered;
                }
                image.at(px, py) = resolve_box(sum, summed);
                image.coverage[at] = resolve_coverage(covered, summed);
            }
        }
    }

    const FrameContext<Real>& frame_;
    std::size_t sample_count_;  // samples of a whole tile
    std::vector<std::uint32_t> by_time_;  // slot of each time_lanes_ sample
    std::vector<double> by_time_t_;       // its shutter time (the sort key)
    std::vector<std::size_t> footprint_start_;
    std::vector<Real> depth_;
    std::vector<std::uint32_t> hit_;
    SampleLanes lanes_;       // the tile's samples, in slot order
    SampleLanes time_lanes_;  // the same, per footprint sorted by time (time_sorted)
    AxisCache columns_, rows_;  // the current triangle's axis bounds (share_axes)
    std::vector<float> shutter_time_;  // each sample's own time (lanes_ hold the window's local time)
    std::vector<char> in_window_;      // whether the current motion-segment window holds the sample
    std::vector<kernelf::PixelSample> pixel_samples_;  // load_samples' scratch: one pixel's samples
    SampleLanes strata_lanes_;                 // lanes_ grouped by stratum (group_by_stratum)
    std::vector<std::uint32_t> strata_slot_;   // slot of each strata_lanes_ sample
    std::vector<std::uint8_t> stratum_;        // stratum of each slot
    std::vector<std::uint32_t> strata_start_;  // first strata_lanes_ sample of each (stratum, pixel)
    std::vector<std::uint32_t> strata_next_;   // group_by_stratum's scratch
    bool strata_grouped_ = false;              // strata_lanes_ hold this tile's samples
    FarthestDepths<Real> farthest_;            // the occlusion test's depths (group_by_stratum)
    typename K::ScreenBound bound_{}, stratum_bound_{};  // the current triangle's, and its stratum's
    std::array<std::size_t, 4> pending_{};  // samples waiting for covers4 (double only)
    std::size_t pending_count_ = 0;
    int window_segment_ = 0, window_segments_ = 1;  // the window lanes_ are loaded for
    glm::vec2 window_{0.0f, 1.0f};
    int x0_ = 0, y0_ = 0, x1_ = -1, y1_ = -1, tw_ = 0, footprints_x_ = 0;
};

// Rasterization: tiles are handed out dynamically; within a tile the
// triangles run nearest first, and the depth rule (nearest, then lowest
// index) makes the result independent of that order and of the schedule.
// The workers' summed time in the raster and the resolve steps of their tiles.
struct RasterSplit {
    double raster_seconds, resolve_seconds;
};

template <class Real>
RasterSplit rasterize_tiles(const FrameContext<Real>& frame, int threads, Clock::time_point start,
                            RenderResult& result) {
    std::atomic<std::uint64_t> total_tested{0}, total_hit{0}, total_bounded{0}, total_bounded_empty{0},
        total_visited{0}, total_occluded{0};
    std::mutex seconds_lock;
    double raster_seconds = 0.0, resolve_seconds = 0.0;
    const int tile_count = frame.setup.tiles_x * frame.setup.tiles_y;
    Progress progress(frame.settings.progress, start, tile_count);
    cpu_methods::run_parallel_items(
        threads, tile_count, [&] { return TileRasterizer<Real>(frame); },
        [&](TileRasterizer<Real>& rasterizer, int tile) {
            if (frame.cancel != nullptr && frame.cancel->load(std::memory_order_relaxed)) return;
            rasterizer.render_tile(tile, result.image);
            progress.advance();
        },
        [&](const TileRasterizer<Real>& rasterizer) {
            total_tested.fetch_add(rasterizer.tested);
            total_hit.fetch_add(rasterizer.hits);
            total_bounded.fetch_add(rasterizer.bounded);
            total_bounded_empty.fetch_add(rasterizer.bounded_empty);
            total_visited.fetch_add(rasterizer.visited);
            total_occluded.fetch_add(rasterizer.occluded);
            const std::lock_guard<std::mutex> lock(seconds_lock);
            raster_seconds += rasterizer.raster_seconds;
            resolve_seconds += rasterizer.resolve_seconds;
        });
    progress.finish();
    if (frame.cancel != nullptr && frame.cancel->load()) throw RenderCancelled();
    RenderStats& stats = result.stats;
    stats.samples_tested = total_tested.load();
    stats.samples_hit = total_hit.load();
    stats.bounds_computed = total_bounded.load();
    stats.bounds_empty = total_bounded_empty.load();
    stats.samples_visited = total_visited.load();
    if (frame.occlusion) stats.counters.emplace_back("samples_occluded", double(total_occluded.load()));
    return RasterSplit{raster_seconds, resolve_seconds};
}

template <class Real>
RenderResult render_cpu_in(const Scene& scene, const RenderSettings& settings, const CpuOptions& options,
                           std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point start = Clock::now();
    const CameraModel model(scene.camera, settings.width, settings.height);
    const CullMethodInfo& cull = cull_method_info(settings.cull);
    const int footprint = options.footprint;
    // Blocks: the coarser level of the footprint hierarchy, a multiple of the footprint.
    const int block = options.block > footprint ? options.block - options.block % footprint : footprint;
    // Only the per-footprint methods bound lens and time; a static, in-focus
    // triangle has neither to bound, whatever the method.
    const bool cull_bounds = cull.bounds_samples;
    const int threads = cpu_methods::render_threads(settings);

    RenderResult result;
    result.stats.triangles = scene.triangles.size();

    // Setup: clip-space triangles, their screen rectangles, binned into tiles.
    Clock::time_point phase = Clock::now();
    const SurfaceShader shader(scene, model);
    FrameSetup<Real> setup;
    // Strata only where no per-footprint bound culls lens and time (bbox, hull).
    const SampleStrata strata = cull_bounds ? SampleStrata{} : SampleStrata{options.time_strata, options.lens_strata};
    set_up_triangles(scene, model, cull.kernel_method, threads, strata, setup);
    if (setup.invalid > 0) {
        result.warnings.push_back("cpu: skipped " + std::to_string(setup.invalid) +
                                  " triangles whose clip coordinates overflow");
    }
    result.stats.ms_per_phase.emplace_back("setup", ms_since(phase));
    phase = Clock::now();
    bin_triangles(settings.width, settings.height, setup);
    result.stats.ms_per_phase.emplace_back("binning", ms_since(phase));

    phase = Clock::now();
    result.image = Image(settings.width, settings.height);
    result.image.coverage.resize(result.image.pixels.size());
    const FrameContext<Real> frame{scene,
                                   settings,
                                   model,
                                   setup,
                                   shader,
                                   cull.kernel_method,
                                   blurcull::kernel<Real>::cull_traits(cull.kernel_method),
                                   static_cast<Real>(model.znear),
                                   static_cast<std::uint32_t>(options.sums != nullptr ? options.pass_samples
                                                                                      : settings.spp),
                                   footprint,
                                   block,
                                   cull_bounds,
                                   // Footprints that tile the work tiles get their samples sorted by time.
                                   cull_bounds && footprint <= tile_size && tile_size % footprint == 0,
                                   sample_ids,
                                   options.sums,
                                   options.sums != nullptr ? static_cast<std::uint32_t>(options.sums->samples) : 0u,
                                   options.cancel,
                                   double(options.edge_min_samples),
                                   options.occlusion};
    if (sample_ids != nullptr)
        sample_ids->assign(static_cast<std::size_t>(settings.width) * settings.height * frame.spp, no_sample_hit);
    const RasterSplit split = rasterize_tiles(frame, threads, start, result);
    if (options.sums != nullptr) options.sums->samples += options.pass_samples;
    // The tiles' phase in wall time, split into raster and resolve by the
    // workers' shares of their time (the two interleave tile by tile).
    const double tiles_ms = ms_since(phase), worker_seconds = split.raster_seconds + split.resolve_seconds;
    const double resolve_share = worker_seconds > 0.0 ? split.resolve_seconds / worker_seconds : 0.0;
    result.stats.ms_per_phase.emplace_back("raster", tiles_ms * (1.0 - resolve_share));
    result.stats.ms_per_phase.emplace_back("resolve", tiles_ms * resolve_share);
    result.stats.ms_total = ms_since(start);
    return result;
}

// A progressive pass must continue sums of this image size and fit in settings.spp.
void validate_pass(const RenderSettings& settings, const SampleSums& sums, int pass_samples) {
    const std::size_t pixels = static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height);
    if (sums.colour.size() != pixels || sums.covered.size() != pixels)
        throw std::invalid_argument("cpu: the progressive sums are not of a " + std::to_string(settings.width) + "x" +
                                    std::to_string(settings.height) + " image");
    if (pass_samples < 1 || sums.samples < 0 || sums.samples > settings.spp - pass_samples)
        throw std::invalid_argument("cpu: a progressive pass of " + std::to_string(pass_samples) +
                                    " samples after " + std::to_string(sums.samples) + " does not fit in " +
                                    std::to_string(settings.spp) + " spp");
}

}  // namespace

RenderResult render_cpu(const Scene& scene, const RenderSettings& settings, const CpuOptions& options,
                        std::vector<std::uint32_t>* sample_ids) {
    validate_settings(settings);
    require_valid_scene(scene);
    if (options.footprint < 1) throw std::invalid_argument("cpu: footprint must be >= 1 pixel");
    if (options.block < 0) throw std::invalid_argument("cpu: block must be >= 0 pixels");
    auto power_of_two = [](int n, int most) { return n >= 1 && n <= most && (n & (n - 1)) == 0; };
    if (!power_of_two(options.time_strata, 16) || !power_of_two(options.lens_strata, 4))
        throw std::invalid_argument("cpu: time strata must be 1, 2, 4, 8 or 16 and lens strata 1, 2 or 4 (got " +
                                    std::to_string(options.time_strata) + " and " +
                                    std::to_string(options.lens_strata) + ")");
    if (options.sums != nullptr) validate_pass(settings, *options.sums, options.pass_samples);
    switch (options.precision) {
    case KernelPrecision::float32:
        return render_cpu_in<float>(scene, settings, options, sample_ids);
    case KernelPrecision::float64:
        return render_cpu_in<double>(scene, settings, options, sample_ids);
    }
    throw std::invalid_argument("cpu: unknown kernel precision");
}

const std::vector<KernelPrecisionInfo>& kernel_precisions() {
    static const std::vector<KernelPrecisionInfo> precisions = {
        {KernelPrecision::float64, "double", "kernel<double>, the reference"},
        {KernelPrecision::float32, "float", "kernel<float>, the gl backend's arithmetic"},
    };
    return precisions;
}

const char* to_string(KernelPrecision precision) {
    return kernel_precisions()[static_cast<std::size_t>(precision)].name;
}

std::vector<std::string> kernel_precision_names() {
    std::vector<std::string> names;
    for (const KernelPrecisionInfo& info : kernel_precisions()) names.emplace_back(info.name);
    return names;
}

KernelPrecision parse_kernel_precision(const std::string& name) {
    std::string valid;
    for (const KernelPrecisionInfo& info : kernel_precisions()) {
        if (name == info.name) return info.precision;
        valid += (valid.empty() ? "" : " or ") + std::string(info.name);
    }
    throw std::invalid_argument("kernel precision '" + name + "' is not " + valid);
}


}  // namespace blurcull::frontend
