#include "render/gl_backend.hpp"

#include "render/camera_model.hpp"
#include "render/gl_methods.hpp"
#include "render/gl_render_targets.hpp"
#include "render/moving_triangle.hpp"
#include "render/shading.hpp"
#include "scene/scene_checks.hpp"

#include <gl/gl_context.hpp>

#include <blurcull/kernel.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
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

// MSAA samples per pass: llvmpipe's maximum; spp / 4 passes reach any spp.
constexpr int samples_per_pass = 4;

// std430 layouts of the shaders' structs (shaders/glsl/render_common.glsl).
struct GpuTriangle {           // MovingTriangle: vec3 p[6] (stride 16), vec2 c[6]
    float p[6][4];
    float c[6][2];
};
static_assert(sizeof(GpuTriangle) == 144, "std430 MovingTriangle");
constexpr std::size_t triangle_info_bytes = (4 + 4 + 4 + 4 + 4 + 4 * BC_HULL_MAX) * 4;
constexpr std::size_t cell_bounds_bytes = 6 * 4 * 4;  // CellBounds: ivec4 + 5 vec4
constexpr int cells_max = 16;                         // CELLS_MAX

}  // namespace

struct GlRenderer::State {
    gl::HeadlessContext context;
    gl::Program setup;
    gl::Program bounds;
    gl::Program samples;
    gl::Program draw_static;
    gl::Program draw_static_group;
    gl::Program static_fill;
    gl::Program draw_moving;
    gl::Program resolve;
    GLuint vertex_array = 0;
    // interleave / interval / accum (gl_methods.cpp), compiled on first use;
    // declared after the context, so destroyed before it.
    std::shared_ptr<GlMethodPrograms> methods;

    explicit State(gl::HeadlessContext&& made)
        : context(std::move(made)),
          setup(context.gl(), {kernel_stage(GL_COMPUTE_SHADER, "render_setup.comp")}),
          bounds(context.gl(), {kernel_stage(GL_COMPUTE_SHADER, "render_bounds.comp")}),
          samples(context.gl(), {kernel_stage(GL_COMPUTE_SHADER, "render_samples.comp")}),
          draw_static(context.gl(), {kernel_stage(GL_VERTEX_SHADER, "render_static.vert"),
                                     kernel_stage(GL_FRAGMENT_SHADER, "render_static.frag")}),
          draw_static_group(context.gl(), {kernel_stage(GL_VERTEX_SHADER, "render_static.vert"),
                                           kernel_stage(GL_FRAGMENT_SHADER, "render_static_group.frag")}),
          static_fill(context.gl(), {kernel_stage(GL_VERTEX_SHADER, "render_static_fill.vert"),
                                     kernel_stage(GL_FRAGMENT_SHADER, "render_static_fill.frag")}),
          draw_moving(context.gl(), {kernel_stage(GL_VERTEX_SHADER, "render_moving.vert"),
                                     kernel_stage(GL_FRAGMENT_SHADER, "render_moving.frag")}),
          resolve(context.gl(), {kernel_stage(GL_COMPUTE_SHADER, "render_resolve.comp")}) {
        context.gl().GenVertexArrays(1, &vertex_array);
    }
    State(const State&) = delete;
    State& operator=(const State&) = delete;
    ~State() { context.gl().DeleteVertexArrays(1, &vertex_array); }
};

namespace {

void set_int(const gl::Functions& gl, const gl::Program& program, const char* name, int value) {
    gl.Uniform1i(gl.GetUniformLocation(program.id(), name), value);
}
void set_uint(const gl::Functions& gl, const gl::Program& program, const char* name, std::uint32_t value) {
    gl.Uniform1ui(gl.GetUniformLocation(program.id(), name), value);
}
void set_float(const gl::Functions& gl, const gl::Program& program, const char* name, float value) {
    gl.Uniform1f(gl.GetUniformLocation(program.id(), name), value);
}

// The uniforms of render_common.glsl.
void set_common(const gl::Functions& gl, const gl::Program& program, const CameraModel& model,
                const RenderSettings& settings, std::uint32_t pass_base) {
    gl.UseProgram(program.id());
    gl.Uniform2f(gl.GetUniformLocation(program.id(), "image_size"), static_cast<float>(settings.width),
                 static_cast<float>(settings.height));
    set_float(gl, program, "near_plane", model.znear);
    set_uint(gl, program, "spp", static_cast<std::uint32_t>(settings.spp));
    set_uint(gl, program, "seed", settings.seed);
    set_uint(gl, program, "pass_base", pass_base);
}

int get_integer(const gl::Functions& gl, GLenum name) {
    GLint value = 0;
    gl.GetIntegerv(name, &value);
    return value;
}

}  // namespace

GlRenderer::GlRenderer() : GlRenderer(gl::HeadlessContext::create()) {}

GlRenderer::GlRenderer(gl::HeadlessContext&& context) : state_(std::make_unique<State>(std::move(context))) {
    const gl::Functions& gl = state_->context.gl();
    for (GLenum limit : {GL_MAX_INTEGER_SAMPLES, GL_MAX_DEPTH_TEXTURE_SAMPLES}) {
        if (get_integer(gl, limit) < samples_per_pass) {
            throw GlError("gl: the context has fewer than 4 samples for integer or depth multisample textures");
        }
    }
}

GlRenderer::GlRenderer(GlRenderer&&) noexcept = default;
GlRenderer& GlRenderer::operator=(GlRenderer&&) noexcept = default;
GlRenderer::~GlRenderer() = default;

std::string GlRenderer::description() const {
    return std::string(gl::context_kind_name(state_->context.kind())) + ", " + state_->context.renderer() + ", " +
           state_->context.version();
}

RenderResult GlRenderer::render(const Scene& scene, const RenderSettings& settings, const GlOptions& options,
                                std::vector<std::uint32_t>* sample_ids) {
    if (settings.method != "stochastic") {
        state_->context.make_current();
        return render_gl_method(state_->context, state_->methods, scene, settings,
                                options.keep_sample_ids ? sample_ids : nullptr);
    }
    const Clock::time_point start = Clock::now();
    validate_settings(settings);
    validate_scene(scene);
    if (options.cell_pixels < 1) throw std::invalid_argument("gl: cell_pixels must be >= 1");
    if (options.static_group_samples < 0 || options.static_group_samples % samples_per_pass != 0) {
        throw std::invalid_argument("gl: static_group_samples must be 0 or a positive multiple of 4");
    }
    state_->context.make_current();
    const gl::Functions& gl = state_->context.gl();
    const int width = settings.width, height = settings.height;
    const int max_size = std::min({get_integer(gl, GL_MAX_TEXTURE_SIZE), get_integer(gl, GL_MAX_FRAMEBUFFER_WIDTH),
                                   get_integer(gl, GL_MAX_FRAMEBUFFER_HEIGHT)});
    if (width > max_size || height > max_size) {
        throw GlError("gl: image size " + std::to_string(width) + "x" + std::to_string(height) +
                      " exceeds the context's limit of " + std::to_string(max_size) + " pixels per side");
    }
    const std::size_t count = scene.triangles.size();
    // 64 cells per work group, at most 65535 groups (GL's minimum limit).
    constexpr std::size_t triangle_limit = 65535 * 64 / cells_max;
    if (count > triangle_limit) {
        throw GlError("gl: " + std::to_string(count) + " triangles exceed the backend's limit of " +
                      std::to_string(triangle_limit));
    }
    const CameraModel model(scene.camera, width, height);
    const auto spp = static_cast<std::uint32_t>(settings.spp);

    RenderResult result;
    RenderStats& stats = result.stats;
    stats.triangles = count;

    // Setup: float clip-space triangles (make_moving_triangle<float>, as the
    // kernel's GLSL sees them), colours, buffers, then per triangle on the GPU:
    // screen bound, path.
    Clock::time_point phase = Clock::now();
    std::vector<GpuTriangle> triangles(std::max<std::size_t>(count, 1));
    // classify() here, on the float triangle the GLSL sees (kernel<float> and
    // its GLSL twin are bit-identical), so each path draws a list of only its
    // own triangles, in index order: no vertex, cell or bounds work for the
    // other path's triangles.
    std::vector<std::int32_t> classes(std::max<std::size_t>(count, 1), BC_INVALID);
    std::vector<std::uint32_t> static_list, moving_list;
    for (std::size_t i = 0; i < count; ++i) {
        const kernelf::MovingTriangle tri = make_moving_triangle<float>(scene, model, i);
        classes[i] = kernelf::classify(tri);
        if (classes[i] == 0 && !options.force_full_path) {
            static_list.push_back(static_cast<std::uint32_t>(i));
        } else if (classes[i] != BC_INVALID) {
            moving_list.push_back(static_cast<std::uint32_t>(i));
        }
        for (int j = 0; j < 6; ++j) {
            triangles[i].p[j][0] = tri.p[j].x;
            triangles[i].p[j][1] = tri.p[j].y;
            triangles[i].p[j][2] = tri.p[j].z;
            triangles[i].p[j][3] = 0.0f;
            triangles[i].c[j][0] = tri.c[j].x;
            triangles[i].c[j][1] = tri.c[j].y;
        }
    }
    const std::vector<glm::vec3> shaded = shade_all(scene);
    std::vector<glm::vec4> colours;
    colours.reserve(count + 1);
    for (const glm::vec3& colour : shaded) colours.emplace_back(colour, 1.0f);
    colours.emplace_back(scene.background, 1.0f);
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);

    gl::Buffer triangle_buffer(gl, GL_SHADER_STORAGE_BUFFER, triangles.size() * sizeof(GpuTriangle), triangles.data());
    gl::Buffer info_buffer(gl, GL_SHADER_STORAGE_BUFFER, std::max<std::size_t>(count, 1) * triangle_info_bytes);
    SampleCounters counters(gl);
    gl::Buffer colour_buffer(gl, GL_SHADER_STORAGE_BUFFER, colours.size() * sizeof(glm::vec4), colours.data());
    gl::Buffer sum_buffer(gl, GL_SHADER_STORAGE_BUFFER, pixels * sizeof(glm::vec4));
    const bool keep_ids = options.keep_sample_ids && sample_ids != nullptr;
    gl::Buffer id_buffer(gl, GL_SHADER_STORAGE_BUFFER, keep_ids ? pixels * spp * sizeof(std::uint32_t) : 4);
    triangle_buffer.bind_base(0);
    info_buffer.bind_base(1);
    counters.bind_base(2);
    colour_buffer.bind_base(3);
    sum_buffer.bind_base(4);
    id_buffer.bind_base(5);
    const int method = kernel_cull_method(settings.cull);
    // The per-cell bounds carry the two-stage part of BC_CULL_EDGES, not its edge planes.
    const bool bounds_samples = method == BC_CULL_DUALSPACE || method == BC_CULL_CLIP2 || method == BC_CULL_EDGES;
    const int cells_per_triangle = bounds_samples ? cells_max : 1;
    const std::size_t cell_count = moving_list.size() * static_cast<std::size_t>(cells_per_triangle);
    gl::Buffer cell_buffer(gl, GL_SHADER_STORAGE_BUFFER, std::max<std::size_t>(cell_count, 1) * cell_bounds_bytes);
    cell_buffer.bind_base(6);
    gl::Buffer pass_sample_buffer(gl, GL_SHADER_STORAGE_BUFFER, pixels * samples_per_pass * sizeof(glm::vec4));
    gl::Buffer pass_time_buffer(gl, GL_SHADER_STORAGE_BUFFER, pixels * samples_per_pass * sizeof(float));
    pass_sample_buffer.bind_base(7);
    pass_time_buffer.bind_base(8);
    gl::Buffer class_buffer(gl, GL_SHADER_STORAGE_BUFFER, classes.size() * sizeof(std::int32_t), classes.data());
    class_buffer.bind_base(9);
    const std::size_t static_count = static_list.size(), moving_count = moving_list.size();
    if (static_list.empty()) static_list.push_back(0);  // GL refuses empty buffers; drawn with count 0
    if (moving_list.empty()) moving_list.push_back(0);
    gl::Buffer static_list_buffer(gl, GL_SHADER_STORAGE_BUFFER, static_list.size() * sizeof(std::uint32_t),
                                  static_list.data());
    gl::Buffer moving_list_buffer(gl, GL_SHADER_STORAGE_BUFFER, moving_list.size() * sizeof(std::uint32_t),
                                  moving_list.data());
    static_list_buffer.bind_base(10);
    moving_list_buffer.bind_base(11);

    if (count > 0) {
        set_common(gl, state_->setup, model, settings, 0);
        set_int(gl, state_->setup, "triangle_count", static_cast<int>(count));
        set_int(gl, state_->setup, "method", method);
        set_int(gl, state_->setup, "force_full", options.force_full_path ? 1 : 0);
        gl.DispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
        gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        set_common(gl, state_->bounds, model, settings, 0);
        set_int(gl, state_->bounds, "moving_count", static_cast<int>(moving_count));
        set_int(gl, state_->bounds, "cells_per_triangle", cells_per_triangle);
        set_int(gl, state_->bounds, "method", method);
        set_int(gl, state_->bounds, "cell_pixels", options.cell_pixels);
        gl.DispatchCompute(static_cast<GLuint>((cell_count + 63) / 64), 1, 1);
        gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }

    const IdDepthTarget id_depth(gl, width, height, samples_per_pass, "the multisample id/depth framebuffer");
    id_depth.bind_with_depth_rule();
    gl.Enable(GL_MULTISAMPLE);
    gl.BindVertexArray(state_->vertex_array);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D_MULTISAMPLE, id_depth.id_texture());
    gl.Finish();
    gl::check_gl(gl, "gl: setup");
    stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    // Passes of four samples: per-sample ids and depths in 4x MSAA targets,
    // folded into the per-pixel sums after each pass.
    phase = Clock::now();
    const std::uint32_t passes = (spp + samples_per_pass - 1) / samples_per_pass;
    const GLuint clear_id[4] = {no_triangle, 0, 0, 0};
    const GLfloat clear_depth = 0.0f;
    // options.time_steps: milliseconds per step, summed over the passes.
    enum Step { step_samples, step_static, step_moving, step_resolve, step_count };
    std::array<double, step_count> step_ms{};
    Clock::time_point step_start = Clock::now();
    auto end_step = [&](Step step) {
        if (!options.time_steps) return;
        gl.Finish();
        const Clock::time_point now = Clock::now();
        step_ms[step] += std::chrono::duration<double, std::milli>(now - step_start).count();
        step_start = now;
    };
    // Static triangles are drawn once per group of passes (the whole frame
    // unless its samples would exceed group_entries_max): llvmpipe's cost is
    // per primitive (docs/gl-backend.md). Each group's winners (per sample)
    // go to group_ids and start each of its passes (render_static_fill.frag).
    // With one pass per group, the static draw per pass is cheaper.
    constexpr std::size_t group_entries_max = std::size_t{1} << 22;
    constexpr std::uint32_t pass_samples = samples_per_pass;
    std::size_t group_limit = std::min<std::size_t>(passes * pass_samples,
                                                    group_entries_max / pixels / pass_samples * pass_samples);
    if (options.static_group_samples > 0) {
        group_limit = std::min(group_limit, static_cast<std::size_t>(options.static_group_samples));
    }
    const std::uint32_t group_samples = std::max(static_cast<std::uint32_t>(group_limit), pass_samples);
    const bool static_groups = static_count > 0 && group_samples > pass_samples;
    const std::size_t group_entries = static_groups ? pixels * group_samples : 1;
    gl::Buffer group_sample_buffer(gl, GL_SHADER_STORAGE_BUFFER, group_entries * sizeof(glm::vec4));
    gl::Buffer group_time_buffer(gl, GL_SHADER_STORAGE_BUFFER, group_entries * sizeof(float));
    gl::Buffer group_id_buffer(gl, GL_SHADER_STORAGE_BUFFER, group_entries * sizeof(std::uint32_t));
    group_sample_buffer.bind_base(12);
    group_time_buffer.bind_base(13);
    gl::Buffer group_depth_buffer(gl, GL_SHADER_STORAGE_BUFFER, group_entries * sizeof(std::uint32_t));
    group_id_buffer.bind_base(14);
    group_depth_buffer.bind_base(15);
    std::uint32_t group_base = 0;
    auto compute_samples = [&](std::uint32_t base, std::uint32_t stride) {
        set_common(gl, state_->samples, model, settings, base);
        set_uint(gl, state_->samples, "stride", stride);
        gl.DispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
        gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    };
    for (std::uint32_t pass = 0; pass < passes; ++pass) {
        const std::uint32_t pass_base = pass * samples_per_pass;
        if (static_groups && pass_base % group_samples == 0) {
            group_base = pass_base;
            group_sample_buffer.bind_base(7);
            group_time_buffer.bind_base(8);
            compute_samples(group_base, group_samples);
            pass_sample_buffer.bind_base(7);
            pass_time_buffer.bind_base(8);
            const GLuint no_id = no_triangle;
            gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, group_id_buffer.id());
            gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &no_id);
            gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, group_depth_buffer.id());
            gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
            gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            end_step(step_samples);
            // One fragment per pixel at its centre (inside the grown outline
            // wherever a sample can be covered); nothing is written to the
            // framebuffer.
            gl.Disable(GL_DEPTH_TEST);
            gl.Disable(GL_MULTISAMPLE);
            gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            gl.DepthMask(GL_FALSE);
            set_common(gl, state_->draw_static_group, model, settings, group_base);
            set_uint(gl, state_->draw_static_group, "group_samples", group_samples);
            gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(static_count * 3));
            gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            gl.Enable(GL_DEPTH_TEST);
            gl.Enable(GL_MULTISAMPLE);
            gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            gl.DepthMask(GL_TRUE);
            counters.add_to(stats);
            end_step(step_static);
        }
        compute_samples(pass_base, pass_samples);
        gl.ClearBufferuiv(GL_COLOR, 0, clear_id);
        gl.ClearBufferfv(GL_DEPTH, 0, &clear_depth);
        end_step(step_samples);
        if (count > 0) {
            // Three vertices per static triangle, six (a quad) per moving triangle's cell.
            if (static_groups) {
                set_common(gl, state_->static_fill, model, settings, pass_base);
                set_uint(gl, state_->static_fill, "group_samples", group_samples);
                set_uint(gl, state_->static_fill, "group_base", group_base);
                gl.DrawArrays(GL_TRIANGLES, 0, 3);
            } else {
                set_common(gl, state_->draw_static, model, settings, pass_base);
                gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(static_count * 3));
            }
            end_step(step_static);
            set_common(gl, state_->draw_moving, model, settings, pass_base);
            set_int(gl, state_->draw_moving, "cells_per_triangle", cells_per_triangle);
            gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(cell_count * 6));
            end_step(step_moving);
        }
        gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        set_common(gl, state_->resolve, model, settings, pass_base);
        set_uint(gl, state_->resolve, "background", static_cast<std::uint32_t>(count));
        set_int(gl, state_->resolve, "keep_ids", keep_ids ? 1 : 0);
        set_int(gl, state_->resolve, "pass_ids", 0);
        gl.DispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
        gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        counters.add_to(stats);
        gl::check_gl(gl, "gl: raster pass");
        end_step(step_resolve);
    }
    gl.Finish();
    stats.ms_per_phase.emplace_back("raster+resolve", ms_since(phase));
    if (options.time_steps) {
        stats.ms_per_phase.emplace_back("samples", step_ms[step_samples]);
        stats.ms_per_phase.emplace_back("static", step_ms[step_static]);
        stats.ms_per_phase.emplace_back("moving", step_ms[step_moving]);
        stats.ms_per_phase.emplace_back("resolve", step_ms[step_resolve]);
    }

    phase = Clock::now();
    std::vector<glm::vec4> sums(pixels);
    sum_buffer.read(sums.data(), pixels * sizeof(glm::vec4));
    result.image = Image(width, height);
    for (std::size_t i = 0; i < pixels; ++i) result.image.pixels[i] = resolve_box(glm::vec3(sums[i]), settings.spp);
    if (keep_ids) {
        sample_ids->assign(pixels * spp, no_triangle);
        id_buffer.read(sample_ids->data(), sample_ids->size() * sizeof(std::uint32_t));
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::check_gl(gl, "gl: readback");
    stats.ms_per_phase.emplace_back("readback", ms_since(phase));
    stats.ms_total = ms_since(start);
    return result;
}

RenderResult render_gl(const Scene& scene, const RenderSettings& settings) {
    const Clock::time_point start = Clock::now();
    validate_settings(settings);
    validate_scene(scene);
    GlRenderer renderer;
    // llvmpipe compiles a program's code on its first draw: one 1x1 frame
    // makes that happen here, so "raster+resolve" is the frame alone.
    RenderSettings warm_up = settings;
    warm_up.width = 1;
    warm_up.height = 1;
    warm_up.spp = 4;
    warm_up.progress = false;
    renderer.render(scene, warm_up);
    const double compile_ms = ms_since(start);
    RenderResult result = renderer.render(scene, settings);
    result.stats.ms_per_phase.insert(result.stats.ms_per_phase.begin(), {"compile", compile_ms});
    result.stats.ms_total = ms_since(start);
    return result;
}

bool gl_available(std::string* reason) {
    try {
        gl::HeadlessContext::create();
        return true;
    } catch (const std::exception& e) {
        if (reason != nullptr) *reason = e.what();
        return false;
    }
}

bool gl_hardware_available(std::string* reason) {
    try {
        const gl::HeadlessContext context = gl::HeadlessContext::create();
        const std::string renderer = context.renderer();
        for (const char* software : {"llvmpipe", "softpipe", "swrast"}) {
            if (renderer.find(software) != std::string::npos) {
                if (reason != nullptr) *reason = "only a software renderer, " + renderer + ", slower than the cpu backend";
                return false;
            }
        }
        return true;
    } catch (const std::exception& e) {
        if (reason != nullptr) *reason = e.what();
        return false;
    }
}

}  // namespace blurcull::frontend
