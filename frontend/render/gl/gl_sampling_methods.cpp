#include "render/gl/gl_sampling_methods.hpp"

#include "render/common/camera_model.hpp"
#include "render/common/method_plan.hpp"
#include "render/common/moving_triangle.hpp"
#include "render/common/progress.hpp"
#include "render/gl/gl_alpha_mask.hpp"
#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"

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


// The shaders' std430 structs (gpu_layout_shared.h, shared with the GLSL).
using gpu::GpuMovingTriangle;
using GpuBox = gpu::MethodBox;

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

GLint location(const gl::Functions& gl, const gl::Program& program, const char* name) {
    return gl.GetUniformLocation(program.id(), name);
}

}  // namespace

struct GlMethodPrograms {
    const gl::Functions* gl;
    gl::Program samples;
    gl::Program draw;
    gl::VertexArray vertex_array;

    explicit GlMethodPrograms(const gl::Functions& functions)
        : gl(&functions),
          samples(functions, {gl::shader_stage(GL_COMPUTE_SHADER, "render_method_samples.comp")}),
          draw(functions, {gl::shader_stage(GL_VERTEX_SHADER, "render_method.vert"),
                           gl::shader_stage(GL_FRAGMENT_SHADER, "render_method.frag", gl::Prelude::render_masked)}),
          vertex_array(functions) {}
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
        GpuBox gpu{glm::ivec4(r.x0, r.y0, r.x1, r.y1), glm::ivec4(r.x0, r.y0, r.x1, r.y1),
                   glm::vec4(round_up(box.bound.lo.x), round_up(box.bound.lo.y), round_down(box.bound.hi.x),
                             round_down(box.bound.hi.y)),
                   glm::ivec4(static_cast<std::int32_t>(i), 0, 0, 0)};
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

// The framebuffer a method draws into: interleave, one cell per tile of the
// width*s x height*s lattice; else one per pixel.
struct MethodTarget {
    int lattice_width;  // lattice cells per row (width * plan.scale)
    int tile_width;     // lattice cells per framebuffer cell side (1 but for interleave)
    int width, height;  // framebuffer cells
    std::size_t cells;  // width * height
};

MethodTarget method_target(const MethodPlan& plan, int width, int height) {
    const bool interleave = plan.method == RenderMethod::interleave;
    MethodTarget target{};
    target.lattice_width = width * plan.scale;
    target.tile_width = interleave ? plan.tiles.width : 1;
    target.width = interleave ? (target.lattice_width + target.tile_width - 1) / target.tile_width : width;
    target.height = interleave ? (height * plan.scale + target.tile_width - 1) / target.tile_width : height;
    target.cells = static_cast<std::size_t>(target.width) * static_cast<std::size_t>(target.height);
    return target;
}

// The kernel's float triangles, as the stochastic path uploads them; at least
// one entry (GL refuses empty buffers).
std::vector<GpuMovingTriangle> gpu_triangles(const Scene& scene, const CameraModel& model) {
    const std::size_t count = scene.triangles.size();
    std::vector<GpuMovingTriangle> triangles(std::max<std::size_t>(count, 1));
    for (std::size_t i = 0; i < count; ++i) triangles[i] = gpu::to_gpu(make_moving_triangle<float>(scene, model, i));
    return triangles;
}

// One interleave / interval / accum frame: the constructor uploads the
// triangles and per method the tuples' cells or makes the interval samples'
// buffers, makes the single-sampled id/depth target and sets the uniforms;
// run_pass then draws each pass and keeps its ids.
class MethodFrame {
public:
    MethodFrame(const gl::Functions& gl, const GlMethodPrograms& programs, const Scene& scene,
                const RenderSettings& settings, const MethodPlan& plan, const MethodTarget& target);

    // Pass `pass`: its boxes (host, double, as the CPU renderers), its samples
    // (interval), a quad per triangle that may hold a sample, in index order,
    // then its ids into the hits. Returns the milliseconds spent on the boxes.
    double run_pass(int pass, RenderStats& stats);
    // Every pass's ids, (p * spp + j), no_sample_hit for the background.
    std::vector<std::uint32_t> take_hits() { return std::move(hits_); }

private:
    void set_uniforms() const;
    void draw_boxes(int pass);
    // The pass's ids (GL's rows are bottom-up) to their samples.
    void read_pass_ids(int pass);

    const gl::Functions& gl_;
    const GlMethodPrograms& programs_;
    const RenderSettings& settings_;
    const MethodPlan& plan_;
    const MethodTarget target_;
    const bool interleave_, interval_;
    const std::size_t pixels_, per_pixel_;
    const InterleaveTupleCells table_;  // interleave only
    gl::Buffer triangle_buffer_;
    SampleCounters counters_;
    gl::Buffer box_buffer_, tuple_buffer_, sample_buffer_, time_buffer_;
    const GlAlphaMask mask_;  // alphaMode MASK, tested by render_method.frag (render_mask.glsl)
    // The stochastic path's framebuffer and depth rule, single-sampled.
    const IdDepthTarget id_depth_;
    std::vector<std::uint32_t> hits_, pass_ids_;
    std::vector<PassBoxes> parts_;
    std::vector<GpuBox> boxes_;
};

MethodFrame::MethodFrame(const gl::Functions& gl, const GlMethodPrograms& programs, const Scene& scene,
                         const RenderSettings& settings, const MethodPlan& plan, const MethodTarget& target)
    : gl_(gl),
      programs_(programs),
      settings_(settings),
      plan_(plan),
      target_(target),
      interleave_(plan.method == RenderMethod::interleave),
      interval_(plan.method == RenderMethod::interval),
      pixels_(static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height)),
      per_pixel_(static_cast<std::size_t>(plan.per_pixel)),
      table_(interleave_ ? interleave_tuple_cells(plan, settings.width, settings.height) : InterleaveTupleCells{}),
      triangle_buffer_([&] {
          const std::vector<GpuMovingTriangle> triangles = gpu_triangles(scene, plan.model);
          return gl::Buffer(gl, GL_SHADER_STORAGE_BUFFER, triangles.size() * sizeof(GpuMovingTriangle),
                            triangles.data());
      }()),
      counters_(gl),
      box_buffer_(gl, GL_SHADER_STORAGE_BUFFER, std::max<std::size_t>(scene.triangles.size(), 1) * sizeof(GpuBox)),
      tuple_buffer_(gl, GL_SHADER_STORAGE_BUFFER, interleave_ ? table_.cells.size() * sizeof(std::uint32_t) : 4,
                    interleave_ ? table_.cells.data() : nullptr),
      sample_buffer_(gl, GL_SHADER_STORAGE_BUFFER, interval_ ? pixels_ * 4 * sizeof(float) : 16),
      time_buffer_(gl, GL_SHADER_STORAGE_BUFFER, interval_ ? pixels_ * sizeof(float) : 4),
      mask_(gl, scene),
      id_depth_(gl, target.width, target.height, 0, "the method's id/depth framebuffer"),
      hits_(pixels_ * per_pixel_, no_sample_hit),
      pass_ids_(target.cells) {
    triangle_buffer_.bind_base(BC_GL_TRIANGLES_BINDING);
    counters_.bind_base(BC_GL_COUNTERS_BINDING);
    sample_buffer_.bind_base(BC_GL_PASS_SAMPLES_BINDING);
    time_buffer_.bind_base(BC_GL_PASS_TIMES_BINDING);
    box_buffer_.bind_base(BC_GL_METHOD_BOXES_BINDING);
    tuple_buffer_.bind_base(BC_GL_METHOD_TUPLE_CELLS_BINDING);
    mask_.bind();
    id_depth_.bind_with_depth_rule();
    gl.BindVertexArray(programs.vertex_array.id());
    set_uniforms();
    gl::check_gl(gl, "gl: method setup");
    boxes_.reserve(scene.triangles.size());
}

void MethodFrame::set_uniforms() const {
    const gl::Program& draw = programs_.draw;
    const auto width = static_cast<float>(settings_.width), height = static_cast<float>(settings_.height);
    gl_.UseProgram(draw.id());
    gl_.Uniform2f(location(gl_, draw, "image_size"), width, height);
    gl_.Uniform2f(location(gl_, draw, "target_size"), static_cast<float>(target_.width),
                  static_cast<float>(target_.height));
    gl_.Uniform1f(location(gl_, draw, "near_plane"), plan_.model.znear);
    gl_.Uniform1ui(location(gl_, draw, "seed"), settings_.seed);
    gl_.Uniform1ui(location(gl_, draw, "scale"), static_cast<std::uint32_t>(plan_.scale));
    gl_.Uniform1ui(location(gl_, draw, "lattice_width"), static_cast<std::uint32_t>(target_.lattice_width));
    gl_.Uniform1ui(location(gl_, draw, "tile_count"), static_cast<std::uint32_t>(target_.cells));
    gl_.Uniform1i(location(gl_, draw, "method_kind"), interleave_ ? 0 : (interval_ ? 1 : 2));
    const gl::Program& samples = programs_.samples;
    gl_.UseProgram(samples.id());
    gl_.Uniform2f(location(gl_, samples, "image_size"), width, height);
    gl_.Uniform1ui(location(gl_, samples, "spp"), static_cast<std::uint32_t>(plan_.per_pixel));
    gl_.Uniform1ui(location(gl_, samples, "seed"), settings_.seed);
}

double MethodFrame::run_pass(int pass, RenderStats& stats) {
    static const GLuint clear_id[4] = {no_sample_hit, 0, 0, 0};
    static const GLfloat clear_depth = 0.0f;
    const Clock::time_point boxes_start = Clock::now();
    pass_boxes(plan_, pass, interleave_ ? &table_ : nullptr, target_.lattice_width, settings_, parts_, boxes_, stats);
    const double boxes_ms = ms_since(boxes_start);
    if (interval_) {
        const gl::Program& samples = programs_.samples;
        gl_.UseProgram(samples.id());
        gl_.Uniform1ui(location(gl_, samples, "pass_index"), static_cast<std::uint32_t>(pass));
        gl_.DispatchCompute(static_cast<GLuint>((settings_.width + 7) / 8),
                            static_cast<GLuint>((settings_.height + 7) / 8), 1);
        gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    gl_.ClearBufferuiv(GL_COLOR, 0, clear_id);
    gl_.ClearBufferfv(GL_DEPTH, 0, &clear_depth);
    if (!boxes_.empty()) draw_boxes(pass);
    gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    counters_.add_to(stats);
    read_pass_ids(pass);
    gl::check_gl(gl_, "gl: method pass");
    return boxes_ms;
}

void MethodFrame::draw_boxes(int pass) {
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, box_buffer_.id());
    gl_.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(boxes_.size() * sizeof(GpuBox)),
                      boxes_.data());
    const gl::Program& draw = programs_.draw;
    gl_.UseProgram(draw.id());
    gl_.Uniform1ui(location(gl_, draw, "pass_index"), static_cast<std::uint32_t>(pass));
    if (!interval_) {
        const kernelf::PixelSample& s = plan_.pass_samples[static_cast<std::size_t>(pass)];
        gl_.Uniform2f(location(gl_, draw, "pass_lens"), s.lens.x, s.lens.y);
        gl_.Uniform1f(location(gl_, draw, "pass_t"), s.time);
        gl_.Uniform2f(location(gl_, draw, "pass_offset"), s.offset.x, s.offset.y);
    }
    gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(boxes_.size() * 6));
}

// Pass k is sample k of every pixel (interval, accum); interleave's tile t
// is tuple k's cell (gx, gy) of t, sample (gy % s) s + gx % s of pixel
// (gx / s, gy / s).
void MethodFrame::read_pass_ids(int pass) {
    const int target_w = target_.width, target_h = target_.height;
    gl_.ReadPixels(0, 0, target_w, target_h, GL_RED_INTEGER, GL_UNSIGNED_INT, pass_ids_.data());
    const auto lattice_w = static_cast<std::uint32_t>(target_.lattice_width);
    for (int row = 0; row < target_h; ++row) {
        const std::size_t y = static_cast<std::size_t>(target_h - 1 - row);
        for (int x = 0; x < target_w; ++x) {
            const std::uint32_t id = pass_ids_[static_cast<std::size_t>(row) * target_w + static_cast<std::size_t>(x)];
            const std::size_t target = y * static_cast<std::size_t>(target_w) + static_cast<std::size_t>(x);
            if (!interleave_) {
                hits_[target * per_pixel_ + static_cast<std::size_t>(pass)] = id;
                continue;
            }
            const std::uint32_t cell = table_.cells[static_cast<std::size_t>(pass) * target_.cells + target];
            if (cell == no_sample_hit) continue;
            const int gx = static_cast<int>(cell % lattice_w);
            const int gy = static_cast<int>(cell / lattice_w);
            const int side = plan_.scale;
            const std::size_t pixel =
                static_cast<std::size_t>(gy / side) * static_cast<std::size_t>(settings_.width) +
                static_cast<std::size_t>(gx / side);
            hits_[pixel * per_pixel_ + static_cast<std::size_t>((gy % side) * side + gx % side)] = id;
        }
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
    const MethodTarget target = method_target(plan, settings.width, settings.height);
    require_target_fits(gl, target.width, target.height, settings.width, settings.height);
    const std::size_t count = scene.triangles.size();
    if (count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 6)) {
        throw GlError("gl: " + std::to_string(count) + " triangles exceed the backend's limit");
    }

    RenderResult result;
    RenderStats& stats = result.stats;
    stats.triangles = count;
    MethodFrame frame(gl, *programs, scene, settings, plan, target);
    stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    double boxes_ms = 0.0;
    phase = Clock::now();
    Progress progress(settings.progress, start, plan.passes, "gl");
    for (int pass = 0; pass < plan.passes; ++pass) {
        boxes_ms += frame.run_pass(pass, stats);
        progress.advance();
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    progress.finish();
    stats.ms_per_phase.emplace_back("boxes", boxes_ms);
    stats.ms_per_phase.emplace_back("raster", ms_since(phase) - boxes_ms);

    phase = Clock::now();
    std::vector<std::uint32_t> hits = frame.take_hits();
    result.image = resolve_method_samples(scene, plan, hits, settings.width, settings.height);
    result.warnings = plan.warnings;
    if (sample_ids != nullptr) *sample_ids = std::move(hits);
    stats.ms_per_phase.emplace_back("resolve", ms_since(phase));
    stats.ms_total = ms_since(start);
    return result;
}

}  // namespace blurcull::frontend
