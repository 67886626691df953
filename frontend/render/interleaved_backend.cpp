#include "render/interleaved_backend.hpp"

#include "render/camera_model.hpp"
#include "render/cpu_backend.hpp"
#include "render/moving_triangle.hpp"
#include "render/progress.hpp"
#include "render/shading.hpp"
#include "scene/scene_checks.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace blurcull::frontend {
namespace {

// Double precision like render_cpu: the coverage test is the same oracle, and
// the boxes that restrict it are conservative against it.
using K = blurcull::kernel<double>;
using Clock = std::chrono::steady_clock;

constexpr std::uint32_t no_hit = no_sample_hit;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The triangle frozen at lens position uv and time t: static and sharp.
K::MovingTriangle placed(const K::MovingTriangle& tri, K::vec2 uv, double t) {
    K::MovingTriangle result{};
    for (int i = 0; i < 3; ++i) {
        const K::vec3 p = K::vertex_at(tri, i, t, uv);
        result.p[i] = p;
        result.p[i + 3] = p;
        result.c[i] = K::vec2(0.0);
        result.c[i + 3] = K::vec2(0.0);
    }
    return result;
}

// The triangle over the shutter interval [t0, t1] (all lens positions).
K::MovingTriangle restricted(const K::MovingTriangle& tri, double t0, double t1) {
    K::MovingTriangle result{};
    for (int i = 0; i < 3; ++i) {
        result.p[i] = (1.0 - t0) * tri.p[i] + t0 * tri.p[i + 3];
        result.p[i + 3] = (1.0 - t1) * tri.p[i] + t1 * tri.p[i + 3];
        result.c[i] = (1.0 - t0) * tri.c[i] + t0 * tri.c[i + 3];
        result.c[i + 3] = (1.0 - t1) * tri.c[i] + t1 * tri.c[i + 3];
    }
    return result;
}

// Raster-space rectangle (x right, y down, in units of 1/scale pixel) of the
// lattice cells that may hold a sample inside the NDC box, clamped to the
// lattice, one cell wider on each side so float rounding of sample positions
// cannot push a sample out of it; empty (x0 > x1) when the box misses the screen.
CellRect cell_rect(const CameraModel& model, const K::ScreenBound& bound, int scale) {
    CellRect r{0, 0, -1, -1};
    if (bound.empty || bound.lo.x > 1.0 || bound.hi.x < -1.0 || bound.lo.y > 1.0 || bound.hi.y < -1.0) return r;
    const int cells_x = model.width * scale, cells_y = model.height * scale;
    auto cell = [](double v, int limit) {
        if (!(v > 0.0)) return 0;  // also NaN
        if (v >= double(limit)) return limit - 1;
        return static_cast<int>(std::floor(v));
    };
    r.x0 = std::max(cell((bound.lo.x + 1.0) * 0.5 * cells_x, cells_x) - 1, 0);
    r.x1 = std::min(cell((bound.hi.x + 1.0) * 0.5 * cells_x, cells_x) + 1, cells_x - 1);
    r.y0 = std::max(cell((1.0 - bound.hi.y) * 0.5 * cells_y, cells_y) - 1, 0);
    r.y1 = std::min(cell((1.0 - bound.lo.y) * 0.5 * cells_y, cells_y) + 1, cells_y - 1);
    return r;
}

struct Sample {
    K::vec2 ndc;
    K::vec2 lens;
    double time;
};

int thread_count(const RenderSettings& settings, int items) {
    const int threads =
        settings.threads > 0 ? settings.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    return std::max(1, std::min(threads, items));
}

struct Counters {
    std::uint64_t tested = 0, hit = 0, bounded = 0, bounded_empty = 0;
};

// Runs work(item, counters) for item = 0 .. items-1 on the settings' threads.
// Items must write disjoint memory; the counters are summed afterwards.
Counters run_items(const RenderSettings& settings, int items, const std::function<void(int, Counters&)>& work) {
    std::atomic<int> next{0};
    std::atomic<std::uint64_t> tested{0}, hit{0}, bounded{0}, bounded_empty{0};
    auto worker = [&]() {
        Counters local;
        for (int item = next.fetch_add(1); item < items; item = next.fetch_add(1)) work(item, local);
        tested.fetch_add(local.tested);
        hit.fetch_add(local.hit);
        bounded.fetch_add(local.bounded);
        bounded_empty.fetch_add(local.bounded_empty);
    };
    std::vector<std::thread> helpers;
    try {
        for (int i = 1; i < thread_count(settings, items); ++i) helpers.emplace_back(worker);
    } catch (...) {
        next.store(items);
        for (std::thread& helper : helpers) helper.join();
        throw;
    }
    worker();
    for (std::thread& helper : helpers) helper.join();
    return Counters{tested.load(), hit.load(), bounded.load(), bounded_empty.load()};
}

void store_counters(RenderStats& stats, const Counters& counters) {
    stats.samples_tested = counters.tested;
    stats.samples_hit = counters.hit;
    stats.bounds_computed = counters.bounded;
    stats.bounds_empty = counters.bounded_empty;
}

// Depth test of one covered sample: strict, so with triangles in index order
// the first of equal depths wins, as in render_cpu.
inline void depth_test(double z, std::uint32_t triangle, double& depth, std::uint32_t& hit) {
    if (z < depth) {
        depth = z;
        hit = triangle;
    }
}

// The common end of every renderer here: resolve the per-sample hits into the
// image, record the resolve's time, the counters and the total time.
void finish_render(RenderResult& result, const Scene& scene, const MethodPlan& plan, std::vector<std::uint32_t>& hits,
                   const Counters& counters, int width, int height, Clock::time_point start,
                   std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point phase = Clock::now();
    result.image = resolve_method_samples(scene, plan, hits, width, height);
    result.stats.ms_per_phase.emplace_back("resolve", ms_since(phase));
    store_counters(result.stats, counters);
    if (sample_ids != nullptr) *sample_ids = std::move(hits);
    result.stats.ms_total = ms_since(start);
}

int exact_square_root(int n) {
    int root = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
    while (root * root > n) --root;
    while ((root + 1) * (root + 1) <= n) ++root;
    return root;
}

// Stratum j of `strata`, widened a little: the float sample times of stratum
// j may round just outside [j, j + 1] / N.
void stratum_interval(int j, int strata, double& t0, double& t1) {
    t0 = std::max(0.0, double(j) / strata - 1e-6);
    t1 = std::min(1.0, double(j + 1) / strata + 1e-6);
}

}  // namespace

MethodPlan make_method_plan(const Scene& scene, const RenderSettings& settings, const InterleaveOptions& options) {
    validate_settings(settings);
    validate_render_method(settings.method);
    if (settings.method == "stochastic") throw std::invalid_argument("method plan: 'stochastic' has no fixed passes");
    int side = 1;
    if (settings.method == "interleave") {
        side = exact_square_root(settings.spp);
        if (side * side != settings.spp) {
            throw std::invalid_argument("interleave: samples per pixel must be a square (1, 4, 9, 16, ...), got " +
                                        std::to_string(settings.spp));
        }
    }
    require_valid_scene(scene);
    MethodPlan plan;
    plan.method = settings.method;
    plan.model = CameraModel(scene.camera, settings.width, settings.height);
    plan.colours = shade_all(scene);
    const std::size_t count = scene.triangles.size();
    plan.triangles.resize(count);
    plan.visible.resize(count);
    std::size_t invalid = 0;
    for (std::size_t i = 0; i < count; ++i) {
        plan.triangles[i] = make_moving_triangle<double>(scene, plan.model, i);
        const int needs = K::classify(plan.triangles[i]);
        if (needs == BC_INVALID) {
            ++invalid;  // validate_scene checked the input; only overflow gets here
            continue;
        }
        const K::ScreenBound bound = K::screen_bound(plan.triangles[i], plan.model.znear, BC_CULL_BBOX);
        plan.visible[i] = !bound.empty && bound.lo.x <= 1.0 && bound.hi.x >= -1.0 && bound.lo.y <= 1.0 &&
                          bound.hi.y >= -1.0;
        if ((needs & BC_NEEDS_MOTION) != 0) plan.any_motion = true;
        if ((needs & BC_NEEDS_DEFOCUS) != 0) plan.any_defocus = true;
    }
    if (invalid > 0) {
        std::fprintf(stderr, "warning: skipped %zu triangles whose clip coordinates overflow\n", invalid);
    }
    plan.per_pixel = settings.spp;
    if (settings.method == "interleave") {
        plan.scale = side;
        // Spread tuples in what the scene blurs (Aqsis' q).
        InterleavedTileOptions tile_options;
        tile_options.width = options.tile_width;
        tile_options.radius = options.radius;
        tile_options.motion_weight =
            plan.any_motion && !plan.any_defocus ? 1.0 : (plan.any_defocus && !plan.any_motion ? 0.0 : 0.5);
        tile_options.seed = settings.seed;
        plan.tiles = make_interleaved_tiles(tile_options);
        plan.passes = plan.tiles.tuple_count;
        for (const glm::dvec3& tuple : plan.tiles.tuples) {
            kernelf::PixelSample s;
            s.offset = glm::vec2(0.0f);
            s.lens = glm::vec2(static_cast<float>(tuple.x), static_cast<float>(tuple.y));
            s.time = static_cast<float>(tuple.z);
            plan.pass_samples.push_back(s);
        }
    } else if (settings.method == "interval") {
        plan.passes = settings.spp;
    } else {
        plan.passes = settings.spp;
        for (int k = 0; k < plan.passes; ++k) {
            plan.pass_samples.push_back(patternsf::accum_sample(static_cast<std::uint32_t>(k), settings.seed));
        }
    }
    return plan;
}

PassBox method_pass_box(const MethodPlan& plan, int pass, std::size_t triangle) {
    const K::MovingTriangle& tri = plan.triangles[triangle];
    const double near = plan.model.znear;
    PassBox box;
    if (plan.method == "interval") {
        double t0 = 0.0, t1 = 1.0;
        stratum_interval(pass, plan.passes, t0, t1);
        box.bound = K::screen_bound(restricted(tri, t0, t1), near, BC_CULL_BBOX);
    } else {
        const kernelf::PixelSample& s = plan.pass_samples[static_cast<std::size_t>(pass)];
        box.bound = K::screen_bound(placed(tri, K::vec2(s.lens), double(s.time)), near, BC_CULL_BBOX);
    }
    box.rect = cell_rect(plan.model, box.bound, plan.scale);
    return box;
}

InterleaveTupleCells interleave_tuple_cells(const MethodPlan& plan, int width, int height) {
    const InterleavedTiles& tiles = plan.tiles;
    const int cells_x = width * plan.scale, cells_y = height * plan.scale, tile_w = tiles.width;
    InterleaveTupleCells table;
    table.tiles_x = (cells_x + tile_w - 1) / tile_w;
    table.tiles_y = (cells_y + tile_w - 1) / tile_w;
    const std::size_t tile_count = static_cast<std::size_t>(table.tiles_x) * static_cast<std::size_t>(table.tiles_y);
    const auto n = static_cast<std::size_t>(tiles.tuple_count);
    table.cells.assign(n * tile_count, no_hit);
    for (int ty = 0; ty < table.tiles_y; ++ty) {
        for (int tx = 0; tx < table.tiles_x; ++tx) {
            const std::size_t tile = static_cast<std::size_t>(ty) * static_cast<std::size_t>(table.tiles_x) + static_cast<std::size_t>(tx);
            const std::size_t prototype =
                tiles.prototype_of_tile(static_cast<std::uint32_t>(tx), static_cast<std::uint32_t>(ty));
            for (std::size_t k = 0; k < n; ++k) {
                const int slot = tiles.tuple_slot[prototype * n + k];
                const int gx = tx * tile_w + slot % tile_w, gy = ty * tile_w + slot / tile_w;
                if (gx >= cells_x || gy >= cells_y) continue;  // past the image's edge
                table.cells[k * tile_count + tile] =
                    static_cast<std::uint32_t>(gy) * static_cast<std::uint32_t>(cells_x) + static_cast<std::uint32_t>(gx);
            }
        }
    }
    return table;
}

Image resolve_method_samples(const Scene& scene, const MethodPlan& plan, const std::vector<std::uint32_t>& ids,
                             int width, int height) {
    Image image(width, height);
    const int per_pixel = plan.per_pixel;
    for (int py = 0; py < image.height; ++py) {
        for (int px = 0; px < image.width; ++px) {
            const std::size_t base = image.index(px, py) * static_cast<std::size_t>(per_pixel);
            glm::vec3 sum(0.0f);
            for (int j = 0; j < per_pixel; ++j) {
                const std::uint32_t id = ids[base + static_cast<std::size_t>(j)];
                sum += id == no_hit ? scene.background : plan.colours[id];
            }
            image.at(px, py) = resolve_box(sum, per_pixel);
        }
    }
    return image;
}

RenderResult render_interleave(const Scene& scene, const RenderSettings& settings, const InterleaveOptions& options,
                               std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point start = Clock::now();
    Clock::time_point phase = Clock::now();
    RenderSettings interleave_settings = settings;
    interleave_settings.method = "interleave";
    const MethodPlan plan = make_method_plan(scene, interleave_settings, options);
    const CameraModel& model = plan.model;
    const InterleavedTiles& tiles = plan.tiles;
    const int side = plan.scale;
    const int width = settings.width, height = settings.height, spp = settings.spp;
    const int tile_w = tiles.width, n = tiles.tuple_count;
    const int cells_x = width * side, cells_y = height * side;
    const int tiles_x = (cells_x + tile_w - 1) / tile_w, tiles_y = (cells_y + tile_w - 1) / tile_w;
    std::vector<std::uint32_t> prototypes(static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y));
    for (int ty = 0; ty < tiles_y; ++ty) {
        for (int tx = 0; tx < tiles_x; ++tx) {
            prototypes[static_cast<std::size_t>(ty) * tiles_x + tx] =
                tiles.prototype_of_tile(static_cast<std::uint32_t>(tx), static_cast<std::uint32_t>(ty));
        }
    }
    const std::size_t sample_count = static_cast<std::size_t>(width) * height * spp;
    std::vector<double> depth(sample_count, std::numeric_limits<double>::infinity());
    std::vector<std::uint32_t> hits(sample_count, no_hit);
    RenderResult result;
    result.stats.triangles = scene.triangles.size();
    result.stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    // One work item per tuple: the samples of different tuples are disjoint.
    phase = Clock::now();
    const double near = model.znear;
    Progress progress(settings.progress, start, n);
    const Counters counters = run_items(settings, n, [&](int k, Counters& local) {
        const kernelf::PixelSample& tuple = plan.pass_samples[static_cast<std::size_t>(k)];
        const K::vec2 uv(tuple.lens);
        const double t = tuple.time;
        const std::size_t tuple_base = static_cast<std::size_t>(k);
        // The one sample of tuple k in each tile: lattice cell and NDC, computed once.
        std::vector<glm::ivec2> cells(prototypes.size());
        std::vector<K::vec2> ndcs(prototypes.size());
        for (int ty = 0; ty < tiles_y; ++ty) {
            for (int tx = 0; tx < tiles_x; ++tx) {
                const std::size_t tile = static_cast<std::size_t>(ty) * tiles_x + tx;
                const int slot = tiles.tuple_slot[prototypes[tile] * static_cast<std::size_t>(n) + tuple_base];
                const int gx = tx * tile_w + slot % tile_w, gy = ty * tile_w + slot / tile_w;
                cells[tile] = glm::ivec2(gx, gy);
                if (gx >= cells_x || gy >= cells_y) continue;  // past the image's edge
                const glm::vec2 jitter = patternsf::interleaved_jitter(static_cast<std::uint32_t>(gx),
                                                                       static_cast<std::uint32_t>(gy), settings.seed);
                const glm::vec2 offset((static_cast<float>(gx % side) + jitter.x) / static_cast<float>(side),
                                       (static_cast<float>(gy % side) + jitter.y) / static_cast<float>(side));
                ndcs[tile] = K::vec2(model.sample_ndc(gx / side, gy / side, glm::min(offset, glm::vec2(0.99999994f))));
            }
        }
        for (std::size_t index = 0; index < plan.triangles.size(); ++index) {
            if (!plan.visible[index]) continue;
            const K::MovingTriangle& tri = plan.triangles[index];
            const PassBox box = method_pass_box(plan, k, index);
            ++local.bounded;
            const CellRect& r = box.rect;
            if (r.empty()) {
                ++local.bounded_empty;
                continue;
            }
            for (int ty = r.y0 / tile_w; ty <= r.y1 / tile_w; ++ty) {
                for (int tx = r.x0 / tile_w; tx <= r.x1 / tile_w; ++tx) {
                    const std::size_t tile = static_cast<std::size_t>(ty) * tiles_x + tx;
                    const int gx = cells[tile].x, gy = cells[tile].y;
                    if (gx < r.x0 || gx > r.x1 || gy < r.y0 || gy > r.y1) continue;
                    const int px = gx / side, py = gy / side, sx = gx % side, sy = gy % side;
                    const K::vec2 ndc = ndcs[tile];
                    if (!K::screen_contains(box.bound, ndc)) continue;
                    ++local.tested;
                    double z = 0.0;
                    if (!K::covers(tri, ndc, uv, t, near, z)) continue;
                    ++local.hit;
                    const std::size_t sample =
                        (static_cast<std::size_t>(py) * width + px) * spp + static_cast<std::size_t>(sy * side + sx);
                    depth_test(z, static_cast<std::uint32_t>(index), depth[sample], hits[sample]);
                }
            }
        }
        progress.advance();
    });
    progress.finish();
    result.stats.ms_per_phase.emplace_back("raster", ms_since(phase));

    finish_render(result, scene, plan, hits, counters, width, height, start, sample_ids);
    return result;
}

RenderResult render_interval(const Scene& scene, const RenderSettings& settings, std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point start = Clock::now();
    Clock::time_point phase = Clock::now();
    RenderSettings interval_settings = settings;
    interval_settings.method = "interval";
    const MethodPlan plan = make_method_plan(scene, interval_settings);
    const CameraModel& model = plan.model;
    const int width = settings.width, height = settings.height, strata = settings.spp;
    const std::size_t sample_count = static_cast<std::size_t>(width) * height * strata;
    std::vector<double> depth(sample_count, std::numeric_limits<double>::infinity());
    std::vector<std::uint32_t> hits(sample_count, no_hit);
    RenderResult result;
    result.stats.triangles = scene.triangles.size();
    result.stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    // One work item per stratum: sample j of every pixel belongs to stratum j.
    phase = Clock::now();
    const double near = model.znear;
    Progress progress(settings.progress, start, strata);
    const Counters counters = run_items(settings, strata, [&](int j, Counters& local) {
        // Sample j of every pixel, computed once per stratum.
        std::vector<Sample> plane(static_cast<std::size_t>(width) * height);
        for (int py = 0; py < height; ++py) {
            for (int px = 0; px < width; ++px) {
                const kernelf::PixelSample s =
                    patternsf::interval_sample(static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py),
                                               static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(strata),
                                               settings.seed);
                plane[static_cast<std::size_t>(py) * width + px] =
                    Sample{K::vec2(model.sample_ndc(px, py, s.offset)), K::vec2(s.lens), double(s.time)};
            }
        }
        for (std::size_t index = 0; index < plan.triangles.size(); ++index) {
            if (!plan.visible[index]) continue;
            const K::MovingTriangle& tri = plan.triangles[index];
            const PassBox box = method_pass_box(plan, j, index);
            ++local.bounded;
            const CellRect& r = box.rect;
            if (r.empty()) {
                ++local.bounded_empty;
                continue;
            }
            for (int py = r.y0; py <= r.y1; ++py) {
                for (int px = r.x0; px <= r.x1; ++px) {
                    const Sample& s = plane[static_cast<std::size_t>(py) * width + px];
                    if (!K::screen_contains(box.bound, s.ndc)) continue;
                    ++local.tested;
                    double z = 0.0;
                    if (!K::covers(tri, s.ndc, s.lens, s.time, near, z)) continue;
                    ++local.hit;
                    const std::size_t sample = (static_cast<std::size_t>(py) * width + px) * strata + static_cast<std::size_t>(j);
                    depth_test(z, static_cast<std::uint32_t>(index), depth[sample], hits[sample]);
                }
            }
        }
        progress.advance();
    });
    progress.finish();
    result.stats.ms_per_phase.emplace_back("raster", ms_since(phase));

    finish_render(result, scene, plan, hits, counters, width, height, start, sample_ids);
    return result;
}

RenderResult render_accum(const Scene& scene, const RenderSettings& settings, std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point start = Clock::now();
    Clock::time_point phase = Clock::now();
    RenderSettings accum_settings = settings;
    accum_settings.method = "accum";
    const MethodPlan plan = make_method_plan(scene, accum_settings);
    const CameraModel& model = plan.model;
    const int width = settings.width, height = settings.height, passes = settings.spp;
    const std::size_t pixel_count = static_cast<std::size_t>(width) * height;
    // hits[pixel * K + k]: what pass k saw, so the passes can run in any
    // order and the resolve still sums them in order 0 .. K-1.
    std::vector<std::uint32_t> hits(pixel_count * static_cast<std::size_t>(passes), no_hit);
    RenderResult result;
    result.stats.triangles = scene.triangles.size();
    result.stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    phase = Clock::now();
    const double near = model.znear;
    Progress progress(settings.progress, start, passes);
    const Counters counters = run_items(settings, passes, [&](int k, Counters& local) {
        const kernelf::PixelSample& pass_sample = plan.pass_samples[static_cast<std::size_t>(k)];
        const K::vec2 uv(pass_sample.lens);
        const double t = pass_sample.time;
        const glm::vec2 offset = pass_sample.offset;
        std::vector<double> depth(pixel_count, std::numeric_limits<double>::infinity());
        std::vector<std::uint32_t> pass(pixel_count, no_hit);
        for (std::size_t index = 0; index < plan.triangles.size(); ++index) {
            if (!plan.visible[index]) continue;
            const K::MovingTriangle& tri = plan.triangles[index];
            const PassBox box = method_pass_box(plan, k, index);
            ++local.bounded;
            const CellRect& r = box.rect;
            if (r.empty()) {
                ++local.bounded_empty;
                continue;
            }
            for (int py = r.y0; py <= r.y1; ++py) {
                for (int px = r.x0; px <= r.x1; ++px) {
                    const K::vec2 ndc(model.sample_ndc(px, py, offset));
                    if (!K::screen_contains(box.bound, ndc)) continue;
                    ++local.tested;
                    double z = 0.0;
                    if (!K::covers(tri, ndc, uv, t, near, z)) continue;
                    ++local.hit;
                    const std::size_t pixel = static_cast<std::size_t>(py) * width + px;
                    depth_test(z, static_cast<std::uint32_t>(index), depth[pixel], pass[pixel]);
                }
            }
        }
        for (std::size_t pixel = 0; pixel < pixel_count; ++pixel) {
            hits[pixel * static_cast<std::size_t>(passes) + static_cast<std::size_t>(k)] = pass[pixel];
        }
        progress.advance();
    });
    progress.finish();
    result.stats.ms_per_phase.emplace_back("raster", ms_since(phase));

    finish_render(result, scene, plan, hits, counters, width, height, start, sample_ids);
    return result;
}

const std::vector<std::string>& render_method_names() {
    static const std::vector<std::string> names = {"stochastic", "interleave", "interval", "accum"};
    return names;
}

void validate_render_method(const std::string& method) {
    const std::vector<std::string>& names = render_method_names();
    if (std::find(names.begin(), names.end(), method) == names.end()) {
        throw std::invalid_argument("unknown render method '" + method +
                                    "' (valid: stochastic, interleave, interval, accum)");
    }
}

RenderResult render_with_method(const Scene& scene, const RenderSettings& settings) {
    validate_render_method(settings.method);
    if (settings.method == "interleave") return render_interleave(scene, settings);
    if (settings.method == "interval") return render_interval(scene, settings);
    if (settings.method == "accum") return render_accum(scene, settings);
    return render_cpu(scene, settings);
}

}  // namespace blurcull::frontend
