#include "render/common/method_plan.hpp"

#include "render/common/motion_segments.hpp"
#include "render/common/moving_triangle.hpp"
#include "render/common/render_method.hpp"
#include "render/common/shading.hpp"
#include "render/common/surface_shading.hpp"
#include "scene/scene_checks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace blurcull::frontend {
namespace {

using K = blurcull::kernel<double>;

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

// The lattice cells (x right, y down, scale x scale per pixel) that can hold
// a sample inside the bound (kernel's box_cell_rect, clamped to the lattice);
// empty (x0 > x1) when the bound is empty or misses the screen.
CellRect cell_rect(const CameraModel& model, const K::ScreenBound& bound, int scale) {
    if (bound.empty) return CellRect{0, 0, -1, -1};
    const K::vec2 cells(double(model.width * scale), double(model.height * scale));
    const glm::ivec4 r = K::box_cell_rect(bound.lo, bound.hi, cells);
    return CellRect{r.x, r.y, r.z, r.w};
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

// The double precision triangles and colours, which triangles some sample may
// see, and whether the scene has motion and defocus at all.
void plan_triangles(const Scene& scene, MethodPlan& plan) {
    plan.shader = std::make_shared<const SurfaceShader>(scene, plan.model);
    plan.colours = plan.shader->flat_colours();
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
        plan.warnings.push_back("skipped " + std::to_string(invalid) +
                                " triangles whose clip coordinates overflow");
    }
}

// Interleave's tiles of (u, v, t) tuples, one pass per tuple.
void plan_interleave_passes(const RenderSettings& settings, const InterleaveOptions& options, MethodPlan& plan) {
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
}

}  // namespace

MethodPlan make_method_plan(const Scene& scene, const RenderSettings& settings, const InterleaveOptions& options) {
    validate_settings(settings);
    if (settings.method == RenderMethod::stochastic || settings.method == RenderMethod::dof_secondary) {
        throw std::invalid_argument(std::string("method plan: '") + to_string(settings.method) +
                                    "' has no fixed passes");
    }
    refuse_motion_segments(scene, std::string("method ") + to_string(settings.method));
    int side = 1;
    if (settings.method == RenderMethod::interleave) {
        side = exact_square_root(settings.spp);
        if (side * side != settings.spp) {
            throw std::invalid_argument("interleave: samples per pixel must be a square (1, 4, 9, 16, ...), got " +
                                        std::to_string(settings.spp));
        }
    }
    require_valid_scene(scene);
    MethodPlan plan;
    plan.method = settings.method;
    plan.seed = settings.seed;
    plan.model = CameraModel(scene.camera, settings.width, settings.height);
    plan_triangles(scene, plan);
    plan.per_pixel = settings.spp;
    switch (settings.method) {
        case RenderMethod::interleave:
            plan.scale = side;
            plan_interleave_passes(settings, options, plan);
            break;
        case RenderMethod::interval:
            plan.passes = settings.spp;
            break;
        case RenderMethod::accum:
        case RenderMethod::stochastic:  // refused above
        case RenderMethod::dof_secondary:
            plan.passes = settings.spp;
            for (int k = 0; k < plan.passes; ++k) {
                plan.pass_samples.push_back(patternsf::accum_sample(static_cast<std::uint32_t>(k), settings.seed));
            }
            break;
    }
    return plan;
}

PassBox method_pass_box(const MethodPlan& plan, int pass, std::size_t triangle) {
    const K::MovingTriangle& tri = plan.triangles[triangle];
    const double near = plan.model.znear;
    PassBox box;
    if (plan.method == RenderMethod::interval) {
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
    table.cells.assign(n * tile_count, no_sample_hit);
    for (int ty = 0; ty < table.tiles_y; ++ty) {
        for (int tx = 0; tx < table.tiles_x; ++tx) {
            const std::size_t tile = static_cast<std::size_t>(ty) * static_cast<std::size_t>(table.tiles_x) + static_cast<std::size_t>(tx);
            const std::size_t prototype =
                tiles.prototype_of_tile(static_cast<std::uint32_t>(tx), static_cast<std::uint32_t>(ty));
            for (std::size_t k = 0; k < n; ++k) {
                const int slot = tiles.tuple_slot[prototype * n + k];
                const glm::ivec2 cell = K::interleaved_cell(glm::ivec2(tx, ty), slot, tile_w);
                const int gx = cell.x, gy = cell.y;
                if (gx >= cells_x || gy >= cells_y) continue;  // past the image's edge
                table.cells[k * tile_count + tile] =
                    static_cast<std::uint32_t>(gy) * static_cast<std::uint32_t>(cells_x) + static_cast<std::uint32_t>(gx);
            }
        }
    }
    return table;
}

std::vector<std::int32_t> method_tuple_of_cell(const MethodPlan& plan, int width, int height) {
    if (plan.method != RenderMethod::interleave) return {};
    const InterleaveTupleCells table = interleave_tuple_cells(plan, width, height);
    const std::size_t tile_count = static_cast<std::size_t>(table.tiles_x) * static_cast<std::size_t>(table.tiles_y);
    std::vector<std::int32_t> tuple_of_cell(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                                                static_cast<std::size_t>(plan.per_pixel),
                                            -1);
    for (std::size_t entry = 0; entry < table.cells.size(); ++entry) {
        const std::uint32_t cell = table.cells[entry];
        if (cell != no_sample_hit) tuple_of_cell[cell] = static_cast<std::int32_t>(entry / tile_count);
    }
    return tuple_of_cell;
}

MethodSample method_sample(const MethodPlan& plan, const std::vector<std::int32_t>& tuple_of_cell, int px, int py,
                           int j) {
    const CameraModel& model = plan.model;
    if (plan.method == RenderMethod::interval) {
        const kernelf::PixelSample s = patternsf::interval_sample(
            static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py), static_cast<std::uint32_t>(j),
            static_cast<std::uint32_t>(plan.passes), plan.seed);
        return MethodSample{model.sample_ndc(px, py, s.offset), s.lens, s.time};
    }
    if (plan.method != RenderMethod::interleave) {  // accum: pass j
        const kernelf::PixelSample& s = plan.pass_samples[static_cast<std::size_t>(j)];
        return MethodSample{model.sample_ndc(px, py, s.offset), s.lens, s.time};
    }
    const int side = plan.scale;
    const glm::ivec2 cell(px * side + j % side, py * side + j / side);
    const std::size_t cell_index =
        static_cast<std::size_t>(cell.y) * static_cast<std::size_t>(model.width * side) + static_cast<std::size_t>(cell.x);
    const kernelf::PixelSample& tuple = plan.pass_samples[static_cast<std::size_t>(tuple_of_cell[cell_index])];
    const glm::vec2 jitter =
        patternsf::interleaved_jitter(static_cast<std::uint32_t>(cell.x), static_cast<std::uint32_t>(cell.y), plan.seed);
    return MethodSample{kernelf::interleaved_sample_ndc(cell, side, jitter, model.image_size()), tuple.lens, tuple.time};
}

Image resolve_method_samples(const Scene& scene, const MethodPlan& plan, const std::vector<std::uint32_t>& ids,
                             int width, int height) {
    const SurfaceShader& shader = *plan.shader;
    const std::vector<std::int32_t> tuple_of_cell =
        shader.any_per_hit() ? method_tuple_of_cell(plan, width, height) : std::vector<std::int32_t>{};
    Image image(width, height);
    image.coverage.resize(image.pixels.size());
    const int per_pixel = plan.per_pixel;
    for (int py = 0; py < image.height; ++py) {
        for (int px = 0; px < image.width; ++px) {
            const std::size_t base = image.index(px, py) * static_cast<std::size_t>(per_pixel);
            glm::vec3 sum(0.0f);
            std::uint32_t covered = 0;
            for (int j = 0; j < per_pixel; ++j) {
                const std::uint32_t id = ids[base + static_cast<std::size_t>(j)];
                if (id == no_sample_hit) {
                    sum += scene.background;
                    continue;
                }
                ++covered;
                if (!shader.per_hit(id)) {
                    sum += plan.colours[id];
                    continue;
                }
                const MethodSample s = method_sample(plan, tuple_of_cell, px, py, j);
                sum += shader.sample_colour(id, s.ndc, s.lens, s.time);
            }
            image.at(px, py) = resolve_box(sum, per_pixel);
            image.coverage[image.index(px, py)] = resolve_coverage(covered, per_pixel);
        }
    }
    return image;
}

}  // namespace blurcull::frontend
