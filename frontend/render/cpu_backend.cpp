#include "render/cpu_backend.hpp"

#include "render/camera_model.hpp"
#include "render/cpu/coverage_test.hpp"
#include "render/moving_triangle.hpp"
#include "render/progress.hpp"
#include "render/shading.hpp"
#include "scene/scene_checks.hpp"

#include <blurcull/kernel.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <mutex>
#include <thread>
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

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct PixelRect {
    int x0, y0, x1, y1;  // inclusive
};

// Pixels whose footprint meets the NDC box [lo, hi], clamped to the image;
// empty (x0 > x1) when they miss it.
template <class Vec2>
PixelRect pixel_rect(const CameraModel& model, Vec2 lo, Vec2 hi) {
    const double w = model.width, h = model.height;
    // raster x = (X + 1) w / 2, raster y = (1 - Y) h / 2 (rows grow downwards)
    auto clamp_floor = [](double v, int limit) {
        if (!(v > 0.0)) return 0;  // also NaN
        if (v >= double(limit)) return limit;
        return static_cast<int>(std::floor(v));
    };
    PixelRect r;
    r.x0 = clamp_floor((double(lo.x) + 1.0) * 0.5 * w, model.width);
    r.x1 = clamp_floor((double(hi.x) + 1.0) * 0.5 * w, model.width);
    r.y0 = clamp_floor((1.0 - double(hi.y)) * 0.5 * h, model.height);
    r.y1 = clamp_floor((1.0 - double(lo.y)) * 0.5 * h, model.height);
    r.x1 = std::min(r.x1, model.width - 1);
    r.y1 = std::min(r.y1, model.height - 1);
    if (double(lo.x) > 1.0 || double(hi.x) < -1.0 || double(lo.y) > 1.0 || double(hi.y) < -1.0) r.x0 = r.x1 + 1;
    return r;
}

// The NDC box of a pixel rectangle's samples (every pixel of it, whole).
SampleBox sample_box(const CameraModel& model, const PixelRect& r) {
    if (r.x0 > r.x1 || r.y0 > r.y1) return SampleBox{0.0, 0.0, 0.0, 0.0};
    const glm::vec4 top_left = model.pixel_ndc_bounds(r.x0, r.y0);
    const glm::vec4 bottom_right = model.pixel_ndc_bounds(r.x1, r.y1);
    return SampleBox{top_left.x, bottom_right.y, bottom_right.z, top_left.w};
}

// A tile's samples in float, one array per coordinate: the fast coverage
// test's input (exact: the samples are floats).
class FloatSamples {
public:
    explicit FloatSamples(std::size_t size) : sx_(size), sy_(size), u_(size), v_(size), t_(size) {}
    void set(std::size_t k, glm::vec2 ndc, glm::vec2 lens, float time) {
        sx_[k] = ndc.x;
        sy_[k] = ndc.y;
        u_[k] = lens.x;
        v_[k] = lens.y;
        t_[k] = time;
    }
    bool may_cover(const CoverageSetup& setup, std::size_t k) const {
        return frontend::may_cover(setup, sx_[k], sy_[k], u_[k], v_[k], t_[k]);
    }
    // Samples first .. first + 31, those in `wanted` (the arrays are padded by 32).
    std::uint32_t may_cover32(const CoverageSetup& setup, std::size_t first, std::uint32_t wanted) const {
        return frontend::may_cover32(setup, &sx_[first], &sy_[first], &u_[first], &v_[first], &t_[first], wanted);
    }

private:
    std::vector<float> sx_, sy_, u_, v_, t_;
};

template <class K>
struct TileSample {
    typename K::vec2 ndc;
    typename K::vec2 lens;
    typename K::real time;
};

template <class Real>
RenderResult render_cpu_in(const Scene& scene, const RenderSettings& settings, const CpuOptions& options) {
    using K = blurcull::kernel<Real>;
    using Sample = TileSample<K>;
    const Clock::time_point start = Clock::now();
    const CameraModel model(scene.camera, settings.width, settings.height);
    const int method = kernel_cull_method(settings.cull);
    const Real near = static_cast<Real>(model.znear);
    const int width = settings.width, height = settings.height;
    const auto spp = static_cast<std::uint32_t>(settings.spp);
    const int footprint = options.footprint;
    // Blocks: the coarser level of the footprint hierarchy, a multiple of the footprint.
    const int block = options.block > footprint ? options.block - options.block % footprint : footprint;
    // Only the per-footprint methods bound lens and time; a static, in-focus
    // triangle has neither to bound, whatever the method.
    const bool cull_bounds = method == BC_CULL_DUALSPACE || method == BC_CULL_CLIP2;
    const typename K::SampleBounds no_bounds = K::no_sample_bounds();
    // Footprints that tile the work tiles get their samples sorted by time.
    const bool time_sorted = cull_bounds && footprint <= tile_size && tile_size % footprint == 0;

    RenderResult result;
    RenderStats& stats = result.stats;
    stats.triangles = scene.triangles.size();

    // Setup: clip-space triangles, their screen rectangles, binned into tiles.
    Clock::time_point phase = Clock::now();
    const std::vector<glm::vec3> colours = shade_all(scene);
    const std::size_t count = scene.triangles.size();
    std::size_t invalid = 0;
    std::vector<typename K::MovingTriangle> triangles(count);
    std::vector<PixelRect> rects(count);
    std::vector<int> classes(count);
    // The fast coverage test's setup (render/cpu/coverage_test.hpp), for the
    // samples of the triangle's pixel rectangle.
    std::vector<CoverageSetup> fast_tests(count);
    // Each triangle's screen bound, computed once: its box, and its hull edges
    // (if any) as a range of `hull_edges`.
    struct StoredBound {
        typename K::vec2 lo, hi;
        std::size_t hull_offset = 0;
        int hull_count = 0;
    };
    std::vector<StoredBound> bounds(count);
    std::vector<typename K::vec3> hull_edges;
    const int threads =
        settings.threads > 0 ? settings.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    {
        // In parallel over contiguous chunks; each chunk keeps its hull edges
        // apart, then they are joined in triangle order.
        const std::size_t chunks = static_cast<std::size_t>(std::max(1, std::min(threads, 64)));
        std::vector<std::vector<typename K::vec3>> chunk_edges(chunks);
        std::vector<std::size_t> chunk_invalid(chunks, 0);
        auto set_up = [&](std::size_t chunk) {
            const std::size_t first = count * chunk / chunks, last = count * (chunk + 1) / chunks;
            for (std::size_t i = first; i < last; ++i) {
                triangles[i] = make_moving_triangle<Real>(scene, model, i);
                classes[i] = K::classify(triangles[i]);
                rects[i] = PixelRect{0, 0, -1, -1};
                if (classes[i] == BC_INVALID) {
                    ++chunk_invalid[chunk];  // validate_scene checked the input; only overflow gets here
                    continue;
                }
                const typename K::ScreenBound bound = K::screen_bound(triangles[i], near, method);
                if (bound.empty) continue;
                rects[i] = pixel_rect(model, bound.lo, bound.hi);
                if (rects[i].x0 <= rects[i].x1 && rects[i].y0 <= rects[i].y1)
                    fast_tests[i] = make_coverage_setup<Real>(triangles[i], sample_box(model, rects[i]));
                StoredBound& stored = bounds[i];
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
            const std::size_t base = hull_edges.size();
            for (std::size_t i = count * c / chunks; i < count * (c + 1) / chunks; ++i) bounds[i].hull_offset += base;
            hull_edges.insert(hull_edges.end(), chunk_edges[c].begin(), chunk_edges[c].end());
            invalid += chunk_invalid[c];
        }
    }
    const int tiles_x = (width + tile_size - 1) / tile_size;
    const int tiles_y = (height + tile_size - 1) / tile_size;
    std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(tiles_x) * tiles_y);
    for (std::size_t i = 0; i < count; ++i) {
        const PixelRect& r = rects[i];
        if (r.x0 > r.x1 || r.y0 > r.y1) continue;
        for (int ty = r.y0 / tile_size; ty <= r.y1 / tile_size; ++ty) {
            for (int tx = r.x0 / tile_size; tx <= r.x1 / tile_size; ++tx) {
                bins[static_cast<std::size_t>(ty) * tiles_x + tx].push_back(static_cast<std::uint32_t>(i));
            }
        }
    }
    if (invalid > 0) {
        std::fprintf(stderr, "warning: cpu: skipped %zu triangles whose clip coordinates overflow\n", invalid);
    }
    stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    // Rasterization: tiles are handed out dynamically; within a tile the
    // triangles run in index order and the depth test is strict, so the
    // result does not depend on the schedule.
    phase = Clock::now();
    result.image = Image(width, height);
    std::atomic<int> next_tile{0};
    std::atomic<std::uint64_t> total_tested{0}, total_hit{0}, total_bounded{0}, total_bounded_empty{0};
    const int tile_count = tiles_x * tiles_y;
    Progress progress(settings.progress, start, tile_count);

    auto work = [&]() {
        std::vector<Sample> samples(static_cast<std::size_t>(tile_size) * tile_size * spp);
        // The same samples in float, one array per coordinate, for the fast
        // test's lanes (padded so the last pixel's batches stay inside).
        FloatSamples lanes(samples.size() + 32);
        // Per footprint of the tile's grid, its sample slots sorted by time, so
        // that a footprint's bounds visit only their shutter interval.
        std::vector<std::uint32_t> by_time(samples.size());
        std::vector<Real> by_time_t(samples.size());
        std::vector<std::size_t> footprint_start;
        std::vector<Real> depth(samples.size());
        std::vector<std::uint32_t> hit(samples.size());
        std::uint64_t tested = 0, hits = 0, bounded = 0, bounded_empty = 0;
        constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
        for (int tile = next_tile.fetch_add(1); tile < tile_count; tile = next_tile.fetch_add(1)) {
            const int tx = tile % tiles_x, ty = tile / tiles_x;
            const int x0 = tx * tile_size, y0 = ty * tile_size;
            const int x1 = std::min(x0 + tile_size, width) - 1, y1 = std::min(y0 + tile_size, height) - 1;
            const int tw = x1 - x0 + 1;
            auto slot = [&](int px, int py, std::uint32_t j) {
                return (static_cast<std::size_t>(py - y0) * tw + (px - x0)) * spp + j;
            };
            for (int py = y0; py <= y1; ++py) {
                for (int px = x0; px <= x1; ++px) {
                    const kernelf::PixelSampleSetup pattern = kernelf::pixel_sample_setup(
                        static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py), spp, settings.seed);
                    for (std::uint32_t j = 0; j < spp; ++j) {
                        const kernelf::PixelSample s = kernelf::pixel_sample_from(pattern, j);
                        const std::size_t k = slot(px, py, j);
                        const glm::vec2 ndc = model.sample_ndc(px, py, s.offset);
                        samples[k] = Sample{typename K::vec2(ndc), typename K::vec2(s.lens), static_cast<Real>(s.time)};
                        lanes.set(k, ndc, s.lens, s.time);
                        depth[k] = std::numeric_limits<Real>::infinity();
                        hit[k] = none;
                    }
                }
            }
            const int footprints_x = (tw + footprint - 1) / footprint;
            if (time_sorted) {
                const int th = y1 - y0 + 1;
                const int footprints_y = (th + footprint - 1) / footprint;
                footprint_start.assign(static_cast<std::size_t>(footprints_x) * footprints_y + 1, 0);
                std::size_t next = 0;
                for (int fy = 0; fy < footprints_y; ++fy) {
                    for (int fx = 0; fx < footprints_x; ++fx) {
                        const std::size_t first = next;
                        footprint_start[static_cast<std::size_t>(fy) * footprints_x + fx] = first;
                        for (int py = y0 + fy * footprint; py <= std::min(y1, y0 + fy * footprint + footprint - 1); ++py)
                            for (int px = x0 + fx * footprint; px <= std::min(x1, x0 + fx * footprint + footprint - 1); ++px)
                                for (std::uint32_t j = 0; j < spp; ++j) by_time[next++] = static_cast<std::uint32_t>(slot(px, py, j));
                        std::sort(by_time.begin() + static_cast<std::ptrdiff_t>(first),
                                  by_time.begin() + static_cast<std::ptrdiff_t>(next),
                                  [&](std::uint32_t a, std::uint32_t b) { return samples[a].time < samples[b].time; });
                        for (std::size_t q = first; q < next; ++q) by_time_t[q] = samples[by_time[q]].time;
                    }
                }
                footprint_start.back() = next;
            }
            for (std::uint32_t index : bins[static_cast<std::size_t>(tile)]) {
                const typename K::MovingTriangle& tri = triangles[index];
                const PixelRect& r = rects[index];
                const StoredBound& stored = bounds[index];
                typename K::ScreenBound bound;
                bound.empty = false;
                bound.lo = stored.lo;
                bound.hi = stored.hi;
                bound.hull_count = stored.hull_count;
                for (int e = 0; e < stored.hull_count; ++e) bound.hull_edge[e] = hull_edges[stored.hull_offset + e];
                const int rx0 = std::max(r.x0, x0), rx1 = std::min(r.x1, x1);
                const int ry0 = std::max(r.y0, y0), ry1 = std::min(r.y1, y1);
                const bool needs_bounds = cull_bounds && classes[index] != 0;
                // NDC rectangle of a block of pixels (rows grow downwards).
                auto footprint_lo = [&](int px0, int py1) {
                    const glm::vec4 corner = model.pixel_ndc_bounds(px0, py1);
                    return typename K::vec2(corner.x, corner.y);
                };
                auto footprint_hi = [&](int px1, int py0) {
                    const glm::vec4 corner = model.pixel_ndc_bounds(px1, py0);
                    return typename K::vec2(corner.z, corner.w);
                };
                auto bounds_of = [&](int px0, int py0, int px1, int py1) {
                    typename K::SampleBounds sb =
                        K::sample_bounds(tri, footprint_lo(px0, py1), footprint_hi(px1, py0), method);
                    ++bounded;
                    if (sb.empty) ++bounded_empty;
                    return sb;
                };
                bool check_screen = true;  // false while the footprint is inside the screen bound
                const CoverageSetup& fast = fast_tests[index];
                auto sample_culled = [&](std::size_t k, const typename K::SampleBounds& sb) {
                    const Sample& s = samples[k];
                    // The lens/time test first: it is cheaper than a hull and culls more.
                    return !K::sample_passes(sb, s.lens, s.time) ||
                           (check_screen && !K::screen_contains(bound, s.ndc));
                };
                // The exact test of a sample the fast test did not reject.
                auto test_exactly = [&](std::size_t k) {
                    const Sample& s = samples[k];
                    Real z = Real(0);
                    if (!K::covers(tri, s.ndc, s.lens, s.time, near, z)) return;
                    ++hits;
                    if (z < depth[k]) {
                        depth[k] = z;
                        hit[k] = index;
                    }
                };
                auto test_samples = [&](int px0, int py0, int px1, int py1, const typename K::SampleBounds& sb) {
                    // The screen bound per footprint first: skip it whole, or
                    // spare its samples the per-sample screen test.
                    const int state = K::screen_footprint(bound, footprint_lo(px0, py1), footprint_hi(px1, py0));
                    if (state == BC_FOOTPRINT_OUTSIDE) return;
                    check_screen = state != BC_FOOTPRINT_INSIDE;
                    const typename K::vec2 range =
                        time_sorted && needs_bounds ? K::sample_time_range(sb) : typename K::vec2(Real(0), Real(1));
                    // Only the footprint's samples inside the bounds' shutter interval, when
                    // that skips enough of them to pay for visiting them out of memory order.
                    if (range.y - range.x < Real(0.5)) {
                        const std::size_t f = static_cast<std::size_t>((py0 - y0) / footprint) * footprints_x +
                                              static_cast<std::size_t>((px0 - x0) / footprint);
                        const auto begin = by_time_t.begin() + static_cast<std::ptrdiff_t>(footprint_start[f]);
                        const auto end = by_time_t.begin() + static_cast<std::ptrdiff_t>(footprint_start[f + 1]);
                        for (auto it = std::lower_bound(begin, end, range.x); it != end && *it <= range.y; ++it) {
                            const std::uint32_t k = by_time[static_cast<std::size_t>(it - by_time_t.begin())];
                            const int local = static_cast<int>(k / spp);
                            const int px = x0 + local % tw, py = y0 + local / tw;
                            if (px < px0 || px > px1 || py < py0 || py > py1) continue;
                            if (sample_culled(k, sb)) continue;
                            ++tested;
                            if (lanes.may_cover(fast, k)) test_exactly(k);
                        }
                        return;
                    }
                    for (int py = py0; py <= py1; ++py) {
                        for (int px = px0; px <= px1; ++px) {
                            const std::size_t first = slot(px, py, 0);
                            // Up to 32 samples at a time: the culls, then the fast test
                            // on them, then covers on what it kept.
                            for (std::uint32_t j0 = 0; j0 < spp; j0 += 32) {
                                std::uint32_t passed = 0;
                                for (std::uint32_t j = j0; j < std::min(spp, j0 + 32); ++j) {
                                    if (sample_culled(first + j, sb)) continue;
                                    passed |= 1u << (j - j0);
                                    ++tested;
                                }
                                if (passed == 0) continue;
                                for (std::uint32_t maybe = passed & lanes.may_cover32(fast, first + j0, passed); maybe != 0;
                                     maybe &= maybe - 1)
                                    test_exactly(first + j0 + static_cast<std::uint32_t>(__builtin_ctz(maybe)));
                            }
                        }
                    }
                };
                // Blocks of the image grid clipped to the triangle's rectangle;
                // the bounds hold for any footprint. A block whose bounds hold
                // nothing is skipped whole; the others are bounded again per
                // footprint when footprints are smaller than blocks.
                for (int by = ry0 - (ry0 % block); by <= ry1; by += block) {
                    for (int bx = rx0 - (rx0 % block); bx <= rx1; bx += block) {
                        const int bx0 = std::max(bx, rx0), bx1 = std::min(bx + block - 1, rx1);
                        const int by0 = std::max(by, ry0), by1 = std::min(by + block - 1, ry1);
                        if (!needs_bounds) {
                            test_samples(bx0, by0, bx1, by1, no_bounds);
                            continue;
                        }
                        if (block > footprint) {
                            if (bounds_of(bx0, by0, bx1, by1).empty) continue;
                        }
                        for (int fy = by0 - (by0 % footprint); fy <= by1; fy += footprint) {
                            for (int fx = bx0 - (bx0 % footprint); fx <= bx1; fx += footprint) {
                                const int px0 = std::max(fx, bx0), px1 = std::min(fx + footprint - 1, bx1);
                                const int py0 = std::max(fy, by0), py1 = std::min(fy + footprint - 1, by1);
                                const typename K::SampleBounds sb = bounds_of(px0, py0, px1, py1);
                                if (!sb.empty) test_samples(px0, py0, px1, py1, sb);
                            }
                        }
                    }
                }
            }
            for (int py = y0; py <= y1; ++py) {
                for (int px = x0; px <= x1; ++px) {
                    glm::vec3 sum(0.0f);
                    for (std::uint32_t j = 0; j < spp; ++j) {
                        const std::uint32_t id = hit[slot(px, py, j)];
                        sum += id == none ? scene.background : colours[id];
                    }
                    result.image.at(px, py) = resolve_box(sum, settings.spp);
                }
            }
            progress.advance();
        }
        total_tested.fetch_add(tested);
        total_hit.fetch_add(hits);
        total_bounded.fetch_add(bounded);
        total_bounded_empty.fetch_add(bounded_empty);
    };

    std::vector<std::thread> helpers;
    try {
        for (int i = 1; i < std::min(threads, tile_count); ++i) helpers.emplace_back(work);
    } catch (...) {
        next_tile.store(tile_count);
        for (std::thread& helper : helpers) helper.join();
        throw;
    }
    work();
    for (std::thread& helper : helpers) helper.join();
    progress.finish();
    stats.ms_per_phase.emplace_back("raster+resolve", ms_since(phase));

    stats.samples_tested = total_tested.load();
    stats.samples_hit = total_hit.load();
    stats.bounds_computed = total_bounded.load();
    stats.bounds_empty = total_bounded_empty.load();
    stats.ms_total = ms_since(start);
    return result;
}

}  // namespace

RenderResult render_cpu(const Scene& scene, const RenderSettings& settings, const CpuOptions& options) {
    validate_settings(settings);
    validate_scene(scene);
    if (options.footprint < 1) throw std::invalid_argument("cpu: footprint must be >= 1 pixel");
    if (options.block < 0) throw std::invalid_argument("cpu: block must be >= 0 pixels");
    switch (options.precision) {
    case KernelPrecision::float32:
        return render_cpu_in<float>(scene, settings, options);
    case KernelPrecision::float64:
        return render_cpu_in<double>(scene, settings, options);
    }
    throw std::invalid_argument("cpu: unknown kernel precision");
}

KernelPrecision parse_kernel_precision(const std::string& name) {
    if (name == "double") return KernelPrecision::float64;
    if (name == "float") return KernelPrecision::float32;
    throw std::invalid_argument("--precision: '" + name + "' is not float or double");
}

}  // namespace blurcull::frontend
