#include "render/gl/gl_sampling_methods.hpp"

#include "render/camera_model.hpp"
#include "render/gl/gl_render_targets.hpp"
#include "render/interleaved_backend.hpp"
#include "render/moving_triangle.hpp"
#include "render/progress.hpp"

#include <blurcull/kernel.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

namespace blurcull::frontend {

namespace {

using Clock = std::chrono::steady_clock;
using gl::GlError;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// std430 layouts of render_common.glsl's MovingTriangle and render_method.*'s MethodBox.
struct GpuTriangle {
    float p[6][4];
    float c[6][2];
};
static_assert(sizeof(GpuTriangle) == 144, "std430 MovingTriangle");
struct GpuBox {
    std::int32_t quad[4];
    std::int32_t rect[4];
    float box[4];
    std::int32_t index[4];
};
static_assert(sizeof(GpuBox) == 64, "std430 MethodBox");

// The float nearest a double bound on the side that keeps float comparisons
// exact: for a float s, s >= lo iff s >= up(lo), and s <= hi iff s <= down(hi).
float round_up(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}
float round_down(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
}

int get_integer(const gl::Functions& gl, GLenum name) {
    GLint value = 0;
    gl.GetIntegerv(name, &value);
    return value;
}

GLint location(const gl::Functions& gl, const gl::Program& program, const char* name) {
    return gl.GetUniformLocation(program.id(), name);
}

}  // namespace

struct GlMethodPrograms {
    const gl::Functions* gl;
    gl::Program samples;
    gl::Program draw;
    GLuint vertex_array = 0;

    explicit GlMethodPrograms(const gl::Functions& functions)
        : gl(&functions),
          samples(functions, {kernel_stage(GL_COMPUTE_SHADER, "render_method_samples.comp")}),
          draw(functions, {kernel_stage(GL_VERTEX_SHADER, "render_method.vert"),
                           kernel_stage(GL_FRAGMENT_SHADER, "render_method.frag")}) {
        functions.GenVertexArrays(1, &vertex_array);
    }
    GlMethodPrograms(const GlMethodPrograms&) = delete;
    GlMethodPrograms& operator=(const GlMethodPrograms&) = delete;
    ~GlMethodPrograms() { gl->DeleteVertexArrays(1, &vertex_array); }
};

namespace {

int thread_count(const RenderSettings& settings, std::size_t items) {
    const int threads =
        settings.threads > 0 ? settings.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    return static_cast<int>(std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(threads), items / 1024 + 1)));
}

// Pass `pass`'s boxes of every visible triangle, in index order, with the
// counts the CPU renderers keep (bounded, off screen). Interleave: a triangle
// whose rectangle holds no cell of the pass's tuple gets no quad (the CPU
// tests nothing for it either), and its quad covers tiles, not cells.
struct PassBoxes {
    std::vector<GpuBox> boxes;
    std::uint64_t bounded = 0, empty = 0;
};

void pass_boxes_range(const MethodPlan& plan, int pass, const InterleaveTupleCells* table, int lattice_width,
                      std::size_t begin, std::size_t end, PassBoxes& out) {
    const int tile_w = plan.tiles.width;
    const std::size_t tile_count =
        table == nullptr ? 0 : static_cast<std::size_t>(table->tiles_x) * static_cast<std::size_t>(table->tiles_y);
    for (std::size_t i = begin; i < end; ++i) {
        if (!plan.visible[i]) continue;
        const PassBox box = method_pass_box(plan, pass, i);
        ++out.bounded;
        const CellRect& r = box.rect;
        if (r.empty()) {
            ++out.empty;
            continue;
        }
        GpuBox gpu{{r.x0, r.y0, r.x1, r.y1},
                   {r.x0, r.y0, r.x1, r.y1},
                   {round_up(box.bound.lo.x), round_up(box.bound.lo.y), round_down(box.bound.hi.x),
                    round_down(box.bound.hi.y)},
                   {static_cast<std::int32_t>(i), 0, 0, 0}};
        if (table != nullptr) {
            const int tx0 = r.x0 / tile_w, ty0 = r.y0 / tile_w, tx1 = r.x1 / tile_w, ty1 = r.y1 / tile_w;
            bool any = false;
            for (int ty = ty0; ty <= ty1 && !any; ++ty) {
                for (int tx = tx0; tx <= tx1 && !any; ++tx) {
                    const std::uint32_t cell =
                        table->cells[static_cast<std::size_t>(pass) * tile_count +
                                     static_cast<std::size_t>(ty) * static_cast<std::size_t>(table->tiles_x) +
                                     static_cast<std::size_t>(tx)];
                    if (cell == no_sample_hit) continue;
                    const int gx = static_cast<int>(cell % static_cast<std::uint32_t>(lattice_width));
                    const int gy = static_cast<int>(cell / static_cast<std::uint32_t>(lattice_width));
                    any = gx >= r.x0 && gx <= r.x1 && gy >= r.y0 && gy <= r.y1;
                }
            }
            if (!any) continue;
            gpu.quad[0] = tx0;
            gpu.quad[1] = ty0;
            gpu.quad[2] = tx1;
            gpu.quad[3] = ty1;
        }
        out.boxes.push_back(gpu);
    }
}

// The same, on the settings' threads over contiguous ranges, joined in order.
void pass_boxes(const MethodPlan& plan, int pass, const InterleaveTupleCells* table, int lattice_width,
                const RenderSettings& settings, std::vector<PassBoxes>& parts, std::vector<GpuBox>& boxes,
                RenderStats& stats) {
    const std::size_t count = plan.triangles.size();
    const int threads = thread_count(settings, count);
    parts.resize(static_cast<std::size_t>(threads));
    std::vector<std::thread> helpers;
    auto range = [&](int part) {
        PassBoxes& out = parts[static_cast<std::size_t>(part)];
        out.boxes.clear();
        out.bounded = out.empty = 0;
        const std::size_t begin = count * static_cast<std::size_t>(part) / static_cast<std::size_t>(threads);
        const std::size_t end = count * static_cast<std::size_t>(part + 1) / static_cast<std::size_t>(threads);
        pass_boxes_range(plan, pass, table, lattice_width, begin, end, out);
    };
    for (int part = 1; part < threads; ++part) helpers.emplace_back(range, part);
    range(0);
    for (std::thread& helper : helpers) helper.join();
    boxes.clear();
    for (const PassBoxes& part : parts) {
        boxes.insert(boxes.end(), part.boxes.begin(), part.boxes.end());
        stats.bounds_computed += part.bounded;
        stats.bounds_empty += part.empty;
    }
}

}  // namespace

RenderResult render_gl_method(const gl::HeadlessContext& context, std::shared_ptr<GlMethodPrograms>& programs,
                              const Scene& scene, const RenderSettings& settings,
                              std::vector<std::uint32_t>* sample_ids) {
    const Clock::time_point start = Clock::now();
    Clock::time_point phase = start;
    const MethodPlan plan = make_method_plan(scene, settings);  // validates settings, method and scene
    const gl::Functions& gl = context.gl();
    if (!programs) programs = std::make_shared<GlMethodPrograms>(gl);
    const int width = settings.width, height = settings.height;
    const bool interleave = plan.method == "interleave", interval = plan.method == "interval";
    const int lattice_w = width * plan.scale;
    // Interleave: one framebuffer cell per tile of the lattice; else one per pixel.
    const int tile_w = interleave ? plan.tiles.width : 1;
    const int target_w = interleave ? (lattice_w + tile_w - 1) / tile_w : width;
    const int target_h = interleave ? (height * plan.scale + tile_w - 1) / tile_w : height;
    const int max_size = std::min({get_integer(gl, GL_MAX_TEXTURE_SIZE), get_integer(gl, GL_MAX_FRAMEBUFFER_WIDTH),
                                   get_integer(gl, GL_MAX_FRAMEBUFFER_HEIGHT)});
    if (target_w > max_size || target_h > max_size) {
        throw GlError("gl: image size " + std::to_string(width) + "x" + std::to_string(height) +
                      " exceeds the context's limit of " + std::to_string(max_size) + " pixels per side");
    }
    const std::size_t count = scene.triangles.size();
    if (count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 6)) {
        throw GlError("gl: " + std::to_string(count) + " triangles exceed the backend's limit");
    }
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const std::size_t targets = static_cast<std::size_t>(target_w) * static_cast<std::size_t>(target_h);
    const auto per_pixel = static_cast<std::size_t>(plan.per_pixel);
    InterleaveTupleCells table;
    if (interleave) table = interleave_tuple_cells(plan, width, height);

    RenderResult result;
    RenderStats& stats = result.stats;
    stats.triangles = count;

    // The kernel's float triangles (as the stochastic path), the boxes' buffer,
    // and per method the tuples' cells or the interval samples.
    std::vector<GpuTriangle> triangles(std::max<std::size_t>(count, 1));
    for (std::size_t i = 0; i < count; ++i) {
        const kernelf::MovingTriangle tri = make_moving_triangle<float>(scene, plan.model, i);
        for (int j = 0; j < 6; ++j) {
            triangles[i].p[j][0] = tri.p[j].x;
            triangles[i].p[j][1] = tri.p[j].y;
            triangles[i].p[j][2] = tri.p[j].z;
            triangles[i].p[j][3] = 0.0f;
            triangles[i].c[j][0] = tri.c[j].x;
            triangles[i].c[j][1] = tri.c[j].y;
        }
    }
    gl::Buffer triangle_buffer(gl, GL_SHADER_STORAGE_BUFFER, triangles.size() * sizeof(GpuTriangle), triangles.data());
    SampleCounters counters(gl);
    gl::Buffer box_buffer(gl, GL_SHADER_STORAGE_BUFFER, std::max<std::size_t>(count, 1) * sizeof(GpuBox));
    gl::Buffer tuple_buffer(gl, GL_SHADER_STORAGE_BUFFER, interleave ? table.cells.size() * sizeof(std::uint32_t) : 4,
                            interleave ? table.cells.data() : nullptr);
    gl::Buffer sample_buffer(gl, GL_SHADER_STORAGE_BUFFER, interval ? pixels * 4 * sizeof(float) : 16);
    gl::Buffer time_buffer(gl, GL_SHADER_STORAGE_BUFFER, interval ? pixels * sizeof(float) : 4);
    triangle_buffer.bind_base(0);
    counters.bind_base(2);
    sample_buffer.bind_base(7);
    time_buffer.bind_base(8);
    box_buffer.bind_base(9);
    tuple_buffer.bind_base(10);

    // The stochastic path's framebuffer and depth rule, single-sampled.
    const IdDepthTarget id_depth(gl, target_w, target_h, 0, "the method's id/depth framebuffer");
    id_depth.bind_with_depth_rule();
    gl.BindVertexArray(programs->vertex_array);

    const gl::Program& draw = programs->draw;
    gl.UseProgram(draw.id());
    gl.Uniform2f(location(gl, draw, "image_size"), static_cast<float>(width), static_cast<float>(height));
    gl.Uniform2f(location(gl, draw, "target_size"), static_cast<float>(target_w), static_cast<float>(target_h));
    gl.Uniform1f(location(gl, draw, "near_plane"), plan.model.znear);
    gl.Uniform1ui(location(gl, draw, "seed"), settings.seed);
    gl.Uniform1ui(location(gl, draw, "scale"), static_cast<std::uint32_t>(plan.scale));
    gl.Uniform1ui(location(gl, draw, "lattice_width"), static_cast<std::uint32_t>(lattice_w));
    gl.Uniform1ui(location(gl, draw, "tile_count"), static_cast<std::uint32_t>(targets));
    gl.Uniform1i(location(gl, draw, "method_kind"), interleave ? 0 : (interval ? 1 : 2));
    const gl::Program& samples = programs->samples;
    gl.UseProgram(samples.id());
    gl.Uniform2f(location(gl, samples, "image_size"), static_cast<float>(width), static_cast<float>(height));
    gl.Uniform1ui(location(gl, samples, "spp"), static_cast<std::uint32_t>(plan.per_pixel));
    gl.Uniform1ui(location(gl, samples, "seed"), settings.seed);
    gl::check_gl(gl, "gl: method setup");
    stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    // Per pass: the boxes (host, double, as the CPU renderers), a quad per
    // triangle that may hold a sample, in index order, then the pass's ids.
    std::vector<std::uint32_t> hits(pixels * per_pixel, no_sample_hit);
    std::vector<std::uint32_t> pass_ids(targets);
    std::vector<PassBoxes> parts;
    std::vector<GpuBox> boxes;
    boxes.reserve(count);
    const GLuint clear_id[4] = {no_sample_hit, 0, 0, 0};
    const GLfloat clear_depth = 0.0f;
    double boxes_ms = 0.0;
    phase = Clock::now();
    Progress progress(settings.progress, start, plan.passes, "gl");
    for (int pass = 0; pass < plan.passes; ++pass) {
        const Clock::time_point boxes_start = Clock::now();
        pass_boxes(plan, pass, interleave ? &table : nullptr, lattice_w, settings, parts, boxes, stats);
        boxes_ms += ms_since(boxes_start);
        if (interval) {
            gl.UseProgram(samples.id());
            gl.Uniform1ui(location(gl, samples, "pass_index"), static_cast<std::uint32_t>(pass));
            gl.DispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
            gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        gl.ClearBufferuiv(GL_COLOR, 0, clear_id);
        gl.ClearBufferfv(GL_DEPTH, 0, &clear_depth);
        if (!boxes.empty()) {
            gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, box_buffer.id());
            gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(boxes.size() * sizeof(GpuBox)),
                             boxes.data());
            gl.UseProgram(draw.id());
            gl.Uniform1ui(location(gl, draw, "pass_index"), static_cast<std::uint32_t>(pass));
            if (!interval) {
                const kernelf::PixelSample& s = plan.pass_samples[static_cast<std::size_t>(pass)];
                gl.Uniform2f(location(gl, draw, "pass_lens"), s.lens.x, s.lens.y);
                gl.Uniform1f(location(gl, draw, "pass_t"), s.time);
                gl.Uniform2f(location(gl, draw, "pass_offset"), s.offset.x, s.offset.y);
            }
            gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(boxes.size() * 6));
        }
        gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        counters.add_to(stats);
        // The pass's ids (GL's rows are bottom-up) to their samples: pass k
        // is sample k of every pixel (interval, accum); interleave's tile t
        // is tuple k's cell (gx, gy) of t, sample (gy % s) s + gx % s of
        // pixel (gx / s, gy / s).
        gl.ReadPixels(0, 0, target_w, target_h, GL_RED_INTEGER, GL_UNSIGNED_INT, pass_ids.data());
        for (int row = 0; row < target_h; ++row) {
            const std::size_t y = static_cast<std::size_t>(target_h - 1 - row);
            for (int x = 0; x < target_w; ++x) {
                const std::uint32_t id = pass_ids[static_cast<std::size_t>(row) * target_w + static_cast<std::size_t>(x)];
                const std::size_t target = y * static_cast<std::size_t>(target_w) + static_cast<std::size_t>(x);
                if (!interleave) {
                    hits[target * per_pixel + static_cast<std::size_t>(pass)] = id;
                    continue;
                }
                const std::uint32_t cell = table.cells[static_cast<std::size_t>(pass) * targets + target];
                if (cell == no_sample_hit) continue;
                const int gx = static_cast<int>(cell % static_cast<std::uint32_t>(lattice_w));
                const int gy = static_cast<int>(cell / static_cast<std::uint32_t>(lattice_w));
                const int side = plan.scale;
                const std::size_t pixel = static_cast<std::size_t>(gy / side) * width + static_cast<std::size_t>(gx / side);
                hits[pixel * per_pixel + static_cast<std::size_t>((gy % side) * side + gx % side)] = id;
            }
        }
        gl::check_gl(gl, "gl: method pass");
        progress.advance();
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    progress.finish();
    stats.ms_per_phase.emplace_back("boxes", boxes_ms);
    stats.ms_per_phase.emplace_back("raster", ms_since(phase) - boxes_ms);

    phase = Clock::now();
    result.image = resolve_method_samples(scene, plan, hits, width, height);
    if (sample_ids != nullptr) *sample_ids = std::move(hits);
    stats.ms_per_phase.emplace_back("resolve", ms_since(phase));
    stats.ms_total = ms_since(start);
    return result;
}

}  // namespace blurcull::frontend
