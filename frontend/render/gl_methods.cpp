#include "render/gl_methods.hpp"

#include "render/camera_model.hpp"
#include "render/interleaved_backend.hpp"
#include "render/moving_triangle.hpp"
#include "render/progress.hpp"

#include <blurcull/glsl/kernel_glsl.hpp>
#include <blurcull/glsl/render_glsl.hpp>
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
#include <utility>
#include <vector>

namespace blurcull::frontend {

namespace {

using Clock = std::chrono::steady_clock;
using gl::GlError;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string_view shader_text(std::string_view name) {
    std::string_view text = glsl::render_shader_source(name);
    if (text.empty()) throw GlError("gl: shader '" + std::string(name) + "' was not embedded at build time");
    return text;
}

gl::ShaderStage kernel_stage(GLenum type, std::string_view main_name) {
    return gl::ShaderStage{type, {glsl::kernel_source(), shader_text("render_common.glsl"), shader_text(main_name)}};
}

// std430 layouts of render_common.glsl's MovingTriangle and render_method.*'s MethodBox.
struct GpuTriangle {
    float p[6][4];
    float c[6][2];
};
static_assert(sizeof(GpuTriangle) == 144, "std430 MovingTriangle");
struct GpuBox {
    std::int32_t rect[4];
    float box[4];
    std::int32_t index[4];
};
static_assert(sizeof(GpuBox) == 48, "std430 MethodBox");

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

class Texture2D {
public:
    Texture2D(const gl::Functions& functions, GLenum format, int width, int height) : gl_(&functions) {
        gl_->GenTextures(1, &id_);
        gl_->BindTexture(GL_TEXTURE_2D, id_);
        gl_->TexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
        gl_->BindTexture(GL_TEXTURE_2D, 0);
        gl::check_gl(*gl_, "gl: method texture");
    }
    Texture2D(const Texture2D&) = delete;
    Texture2D& operator=(const Texture2D&) = delete;
    ~Texture2D() { gl_->DeleteTextures(1, &id_); }
    GLuint id() const { return id_; }

private:
    const gl::Functions* gl_;
    GLuint id_ = 0;
};

class Framebuffer {
public:
    explicit Framebuffer(const gl::Functions& functions) : gl_(&functions) { gl_->GenFramebuffers(1, &id_); }
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;
    ~Framebuffer() { gl_->DeleteFramebuffers(1, &id_); }
    GLuint id() const { return id_; }

private:
    const gl::Functions* gl_;
    GLuint id_ = 0;
};

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
    // Interleave renders the sample lattice, one cell per sample.
    const int target_w = width * plan.scale, target_h = height * plan.scale;
    const int max_size = std::min({get_integer(gl, GL_MAX_TEXTURE_SIZE), get_integer(gl, GL_MAX_FRAMEBUFFER_WIDTH),
                                   get_integer(gl, GL_MAX_FRAMEBUFFER_HEIGHT)});
    if (target_w > max_size || target_h > max_size) {
        throw GlError("gl: " + plan.method + " needs a " + std::to_string(target_w) + "x" + std::to_string(target_h) +
                      " framebuffer, over the context's limit of " + std::to_string(max_size) + " per side");
    }
    const std::size_t count = scene.triangles.size();
    if (count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 6)) {
        throw GlError("gl: " + std::to_string(count) + " triangles exceed the backend's limit");
    }
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const std::size_t cells = static_cast<std::size_t>(target_w) * static_cast<std::size_t>(target_h);
    const auto per_pixel = static_cast<std::size_t>(plan.per_pixel);

    RenderResult result;
    RenderStats& stats = result.stats;
    stats.triangles = count;

    // The kernel's float triangles (as the stochastic path), the boxes' buffer,
    // and per method the lattice's tuples or the interval samples.
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
    const std::uint32_t zero_counters[2] = {0, 0};
    gl::Buffer counter_buffer(gl, GL_SHADER_STORAGE_BUFFER, sizeof zero_counters, zero_counters);
    gl::Buffer box_buffer(gl, GL_SHADER_STORAGE_BUFFER, std::max<std::size_t>(count, 1) * sizeof(GpuBox));
    std::vector<std::uint32_t> cell_tuples;
    if (interleave) cell_tuples = interleave_cell_tuples(plan, width, height);
    gl::Buffer tuple_buffer(gl, GL_SHADER_STORAGE_BUFFER, interleave ? cells * sizeof(std::uint32_t) : 4,
                            interleave ? cell_tuples.data() : nullptr);
    cell_tuples = {};
    gl::Buffer sample_buffer(gl, GL_SHADER_STORAGE_BUFFER, interval ? pixels * 4 * sizeof(float) : 16);
    gl::Buffer time_buffer(gl, GL_SHADER_STORAGE_BUFFER, interval ? pixels * sizeof(float) : 4);
    triangle_buffer.bind_base(0);
    counter_buffer.bind_base(2);
    sample_buffer.bind_base(7);
    time_buffer.bind_base(8);
    box_buffer.bind_base(9);
    tuple_buffer.bind_base(10);

    Texture2D id_texture(gl, GL_R32UI, target_w, target_h);
    Texture2D depth_texture(gl, GL_DEPTH_COMPONENT32F, target_w, target_h);
    Framebuffer framebuffer(gl);
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, id_texture.id(), 0);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_texture.id(), 0);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw GlError("gl: the method's id/depth framebuffer is incomplete");
    }
    gl.Viewport(0, 0, target_w, target_h);
    // The stochastic path's depth rule: near / w from covers(), larger is
    // nearer, cleared to 0, strict, so ties keep the lower triangle index.
    gl.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_GREATER);
    gl.Enable(GL_DEPTH_CLAMP);
    gl.BindVertexArray(programs->vertex_array);

    const gl::Program& draw = programs->draw;
    gl.UseProgram(draw.id());
    gl.Uniform2f(location(gl, draw, "image_size"), static_cast<float>(width), static_cast<float>(height));
    gl.Uniform2f(location(gl, draw, "target_size"), static_cast<float>(target_w), static_cast<float>(target_h));
    gl.Uniform1f(location(gl, draw, "near_plane"), plan.model.znear);
    gl.Uniform1ui(location(gl, draw, "seed"), settings.seed);
    gl.Uniform1ui(location(gl, draw, "scale"), static_cast<std::uint32_t>(plan.scale));
    gl.Uniform1i(location(gl, draw, "method_kind"), interleave ? 0 : (interval ? 1 : 2));
    const gl::Program& samples = programs->samples;
    gl.UseProgram(samples.id());
    gl.Uniform2f(location(gl, samples, "image_size"), static_cast<float>(width), static_cast<float>(height));
    gl.Uniform1ui(location(gl, samples, "spp"), static_cast<std::uint32_t>(plan.per_pixel));
    gl.Uniform1ui(location(gl, samples, "seed"), settings.seed);
    gl::check_gl(gl, "gl: method setup");
    stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    // Per pass: the boxes (host, double, as the CPU renderers), then a quad per
    // triangle whose box is on screen, in index order.
    std::vector<std::uint32_t> hits(pixels * per_pixel, no_sample_hit);
    std::vector<std::uint32_t> pass_ids(interleave ? 0 : pixels);
    std::vector<GpuBox> boxes;
    boxes.reserve(count);
    const GLuint clear_id[4] = {no_sample_hit, 0, 0, 0};
    const GLfloat clear_depth = 0.0f;
    double boxes_ms = 0.0;
    phase = Clock::now();
    Progress progress(settings.progress, start, plan.passes, "gl");
    for (int pass = 0; pass < plan.passes; ++pass) {
        const Clock::time_point boxes_start = Clock::now();
        boxes.clear();
        for (std::size_t i = 0; i < count; ++i) {
            if (!plan.visible[i]) continue;
            const PassBox box = method_pass_box(plan, pass, i);
            ++stats.bounds_computed;
            if (box.rect.empty()) {
                ++stats.bounds_empty;
                continue;
            }
            boxes.push_back(GpuBox{{box.rect.x0, box.rect.y0, box.rect.x1, box.rect.y1},
                                   {round_up(box.bound.lo.x), round_up(box.bound.lo.y), round_down(box.bound.hi.x),
                                    round_down(box.bound.hi.y)},
                                   {static_cast<std::int32_t>(i), 0, 0, 0}});
        }
        boxes_ms += ms_since(boxes_start);
        if (interval) {
            gl.UseProgram(samples.id());
            gl.Uniform1ui(location(gl, samples, "pass_index"), static_cast<std::uint32_t>(pass));
            gl.DispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
            gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        // Interleave's passes write disjoint cells of one lattice; the others
        // each fill a fresh image.
        if (pass == 0 || !interleave) {
            gl.ClearBufferuiv(GL_COLOR, 0, clear_id);
            gl.ClearBufferfv(GL_DEPTH, 0, &clear_depth);
        }
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
        // 32-bit counters per pass, summed in 64 bits here.
        std::uint32_t counters[2] = {0, 0};
        counter_buffer.read(counters, sizeof counters);
        stats.samples_tested += counters[0];
        stats.samples_hit += counters[1];
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, counter_buffer.id());
        gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero_counters, zero_counters);
        if (!interleave) {
            // Pass k's image is sample k of every pixel; GL's rows are bottom-up.
            gl.ReadPixels(0, 0, width, height, GL_RED_INTEGER, GL_UNSIGNED_INT, pass_ids.data());
            for (int row = 0; row < height; ++row) {
                const std::size_t py = static_cast<std::size_t>(height - 1 - row);
                for (int px = 0; px < width; ++px) {
                    const std::uint32_t id = pass_ids[static_cast<std::size_t>(row) * width + px];
                    hits[(py * width + static_cast<std::size_t>(px)) * per_pixel + static_cast<std::size_t>(pass)] = id;
                }
            }
        }
        gl::check_gl(gl, "gl: method pass");
        progress.advance();
    }
    if (interleave) {
        // Lattice cell (gx, gy) is sample (gy % s) s + gx % s of pixel (gx / s, gy / s).
        std::vector<std::uint32_t> lattice(cells);
        gl.ReadPixels(0, 0, target_w, target_h, GL_RED_INTEGER, GL_UNSIGNED_INT, lattice.data());
        const int side = plan.scale;
        for (int row = 0; row < target_h; ++row) {
            const int gy = target_h - 1 - row;
            for (int gx = 0; gx < target_w; ++gx) {
                const std::size_t pixel = static_cast<std::size_t>(gy / side) * width + static_cast<std::size_t>(gx / side);
                hits[pixel * per_pixel + static_cast<std::size_t>((gy % side) * side + gx % side)] =
                    lattice[static_cast<std::size_t>(row) * target_w + static_cast<std::size_t>(gx)];
            }
        }
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::check_gl(gl, "gl: method readback");
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
