#include "render/gl/gl_backend.hpp"

#include "render/common/motion_segments.hpp"
#include "render/common/camera_model.hpp"
#include "render/common/cull_method.hpp"
#include "render/common/moving_triangle.hpp"
#include "render/common/parallel_items.hpp"
#include "render/common/progress.hpp"
#include "render/common/shading.hpp"
#include "render/common/surface_shading.hpp"
#include "render/gl/gl_alpha_mask.hpp"
#include "render/gl/gl_compute_pipeline.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/gl_frame_common.hpp"
#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gl_sampling_methods.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"
#include "scene/scene_checks.hpp"

#include <blurcull/kernel.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace blurcull::frontend {
namespace {

using Clock = std::chrono::steady_clock;
using gl::GlError;
using gl::shader_stage;
constexpr gl::Prelude masked = gl::Prelude::render_masked;


// MSAA samples per pass: llvmpipe's maximum; spp / 4 passes reach any spp.
constexpr int samples_per_pass = 4;
constexpr std::uint32_t pass_samples = samples_per_pass;

// The shaders' std430 structs (gpu_layout_shared.h, shared with the GLSL).
using gpu::CellBounds;
using gpu::GpuMovingTriangle;
using gpu::TriangleInfo;
constexpr int cells_max = BC_GL_CELLS_MAX;

}  // namespace

namespace {

// `context`, made current: the programs compile on it (with several contexts
// alive, another may be current).
gl::HeadlessContext made_current(gl::HeadlessContext&& context) {
    context.make_current();
    return std::move(context);
}

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
    gl::VertexArray vertex_array;
    // interleave / interval / accum (gl_sampling_methods.cpp), compiled on first use;
    // declared after the context, so destroyed before it.
    std::shared_ptr<GlMethodPrograms> methods;
    // The compute pipeline (gl_compute_pipeline.cpp), compiled on first use.
    std::shared_ptr<GlComputePrograms> compute;

    explicit State(gl::HeadlessContext&& made)
        : context(made_current(std::move(made))),
          setup(context.gl(), {shader_stage(GL_COMPUTE_SHADER, "render_setup.comp")}),
          bounds(context.gl(), {shader_stage(GL_COMPUTE_SHADER, "render_bounds.comp")}),
          samples(context.gl(), {shader_stage(GL_COMPUTE_SHADER, "render_samples.comp")}),
          draw_static(context.gl(), {shader_stage(GL_VERTEX_SHADER, "render_static.vert"),
                                     shader_stage(GL_FRAGMENT_SHADER, "render_static.frag", masked)}),
          draw_static_group(context.gl(), {shader_stage(GL_VERTEX_SHADER, "render_static.vert"),
                                           shader_stage(GL_FRAGMENT_SHADER, "render_static_group.frag", masked)}),
          static_fill(context.gl(), {shader_stage(GL_VERTEX_SHADER, "render_static_fill.vert"),
                                     shader_stage(GL_FRAGMENT_SHADER, "render_static_fill.frag")}),
          draw_moving(context.gl(), {shader_stage(GL_VERTEX_SHADER, "render_moving.vert"),
                                     shader_stage(GL_FRAGMENT_SHADER, "render_moving.frag", masked)}),
          resolve(context.gl(), {shader_stage(GL_COMPUTE_SHADER, "render_resolve.comp")}),
          vertex_array(context.gl()) {}
    State(const State&) = delete;
    State& operator=(const State&) = delete;
    // The members' glDelete* act on the current context: this one's, with
    // several alive.
    ~State() { context.make_current_for_release(); }
};

namespace {

// What GlRenderer::render checks before any GL work.
void check_stochastic_request(const Scene& scene, const RenderSettings& settings, const GlOptions& options) {
    validate_settings(settings);
    require_valid_scene(scene);
    if (options.cell_pixels < 1) throw std::invalid_argument("gl: cell_pixels must be >= 1");
    if (options.static_group_samples < 0 || options.static_group_samples % samples_per_pass != 0) {
        throw std::invalid_argument("gl: static_group_samples must be 0 or a positive multiple of 4");
    }
}

void check_triangle_limit(std::size_t count) {
    // 64 cells per work group, at most 65535 groups (GL's minimum limit).
    constexpr std::size_t triangle_limit = 65535 * 64 / cells_max;
    if (count > triangle_limit) {
        throw GlError("gl: " + std::to_string(count) + " triangles exceed the fragment pipeline's limit of " +
                      std::to_string(triangle_limit) + " (--gl-pipeline compute takes any number)");
    }
}

// GlOptions::time_steps: milliseconds per step of the passes, summed over the
// passes; each step ends with a glFinish, so the steps no longer overlap.
class StepTimer {
public:
    enum Step { samples, static_draw, moving, resolve, step_count };
    StepTimer(const gl::Functions& gl, bool enabled) : gl_(&gl), enabled_(enabled), step_start_(Clock::now()) {}

    void end(Step step) {
        if (!enabled_) return;
        gl_->Finish();
        const Clock::time_point now = Clock::now();
        step_ms_[step] += std::chrono::duration<double, std::milli>(now - step_start_).count();
        step_start_ = now;
    }
    // Appends the steps to ms_per_phase when enabled.
    void add_to(RenderStats& stats) const {
        if (!enabled_) return;
        stats.ms_per_phase.emplace_back("samples", step_ms_[samples]);
        stats.ms_per_phase.emplace_back("static", step_ms_[static_draw]);
        stats.ms_per_phase.emplace_back("moving", step_ms_[moving]);
        stats.ms_per_phase.emplace_back("resolve", step_ms_[resolve]);
    }

private:
    const gl::Functions* gl_;
    bool enabled_;
    Clock::time_point step_start_;
    std::array<double, step_count> step_ms_{};
};

// Static triangles are drawn once per group of passes (the whole frame unless
// its samples would exceed group_entries_max): llvmpipe's cost is per
// primitive (docs/gl-backend.md). Each group's winners (per sample) go to
// group ids and start each of its passes (render_static_fill.frag). With one
// pass per group, the static draw per pass is cheaper: the result is
// pass_samples, and no groups are drawn.
std::uint32_t static_group_samples(std::uint32_t passes, std::size_t pixels, const GlOptions& options) {
    constexpr std::size_t group_entries_max = std::size_t{1} << 22;
    std::size_t group_limit =
        std::min<std::size_t>(passes * pass_samples, group_entries_max / pixels / pass_samples * pass_samples);
    if (options.static_group_samples > 0) {
        group_limit = std::min(group_limit, static_cast<std::size_t>(options.static_group_samples));
    }
    return std::max(static_cast<std::uint32_t>(group_limit), pass_samples);
}

// The groups of passes of static_group_samples and their buffers: each
// group's samples (render_samples.comp with stride `samples`) and per sample
// the winning static triangle and its depth key (render_static_group.frag).
struct StaticGroups {
    std::uint32_t samples;  // per group, a multiple of pass_samples
    bool used;              // static triangles and more than one pass per group
    gl::Buffer sample_buffer, time_buffer, id_buffer, depth_buffer;

    StaticGroups(const gl::Functions& gl, std::uint32_t group_samples, bool has_static, std::size_t pixels)
        : samples(group_samples),
          used(has_static && group_samples > pass_samples),
          sample_buffer(storage_buffer(gl, entries(pixels) * sizeof(glm::vec4))),
          time_buffer(storage_buffer(gl, entries(pixels) * sizeof(float))),
          id_buffer(storage_buffer(gl, entries(pixels) * sizeof(std::uint32_t))),
          depth_buffer(storage_buffer(gl, entries(pixels) * sizeof(std::uint32_t))) {
        sample_buffer.bind_base(BC_GL_GROUP_SAMPLES_BINDING);
        time_buffer.bind_base(BC_GL_GROUP_TIMES_BINDING);
        id_buffer.bind_base(BC_GL_GROUP_IDS_BINDING);
        depth_buffer.bind_base(BC_GL_GROUP_DEPTHS_BINDING);
    }
    std::size_t entries(std::size_t pixels) const { return used ? pixels * samples : 1; }
};

// One stochastic frame on a renderer's programs: the constructor makes the
// float triangles, the draw lists and the frame's buffers (bound to the
// shaders' bindings); GlRenderer::render then runs the steps in order.
class StochasticFrame {
public:
    // `flat`: each triangle's flat colour (the render's SurfaceShader).
    StochasticFrame(const GlRenderer::State& state, const Scene& scene, const RenderSettings& settings,
                    const GlOptions& options, bool keep_ids, const std::vector<glm::vec3>& flat);

    // Per triangle and per moving cell, once per frame: render_setup.comp
    // (screen bound, path) and render_bounds.comp (cells' sample bounds);
    // then the id/depth target and the state the passes draw with.
    void run_setup();
    // Every pass of four samples: per-sample ids and depths in 4x MSAA
    // targets, folded into the per-pixel sums after each pass.
    void run_passes(RenderStats& stats, StepTimer& timer);
    // The resolved image; the sample ids into *sample_ids when kept.
    Image read_back(std::vector<std::uint32_t>* sample_ids) const;

private:
    // The pattern's samples base .. base + stride - 1 of every pixel, into
    // the buffers bound at 7 and 8.
    void compute_samples(std::uint32_t base, std::uint32_t stride) const;
    // A group's samples and its static winners (render_static_group.frag).
    void draw_static_group(const StaticGroups& groups, std::uint32_t group_base, RenderStats& stats,
                           StepTimer& timer);
    // A pass's samples, its static triangles (or the group's winners) and its
    // moving cells into the MSAA target.
    void draw_pass(std::uint32_t pass_base, const StaticGroups& groups, std::uint32_t group_base, StepTimer& timer);
    // The pass's samples into the per-pixel sums (render_resolve.comp).
    void resolve_pass(std::uint32_t pass_base, RenderStats& stats);

    const GlRenderer::State& state_;
    const gl::Functions& gl_;
    const RenderSettings& settings_;
    const GlOptions options_;
    const CameraModel model_;
    const std::size_t count_, pixels_;
    const std::uint32_t spp_;
    const bool keep_ids_;
    const int cull_;                // the cull method, BC_CULL_*
    const int cells_per_triangle_;  // 1, or cells_max when the method bounds lens and time
    const FrameTriangles triangles_;
    const std::size_t cell_count_;
    gl::Buffer triangle_buffer_, info_buffer_;
    SampleCounters counters_;
    gl::Buffer colour_buffer_, sum_buffer_, id_buffer_, cell_buffer_, pass_sample_buffer_, pass_time_buffer_,
        class_buffer_, static_list_buffer_, moving_list_buffer_;
    const GlAlphaMask mask_;  // alphaMode MASK, tested by the fragment shaders (render_mask.glsl)
    std::optional<IdDepthTarget> id_depth_;  // made by run_setup
};

// Cells per moving triangle: the cull methods that bound lens and time
// (the registry's bounds_samples) get their bounds per cell (at most 4 x 4);
// the others one cell, the rectangle. The cells carry the two-stage part of
// BC_CULL_EDGES, not its edge planes.
int cells_per_triangle_for(CullMethod cull) {
    return cull_method_info(cull).bounds_samples ? cells_max : 1;
}

StochasticFrame::StochasticFrame(const GlRenderer::State& state, const Scene& scene, const RenderSettings& settings,
                                 const GlOptions& options, bool keep_ids, const std::vector<glm::vec3>& flat)
    : state_(state),
      gl_(state.context.gl()),
      settings_(settings),
      options_(options),
      model_(scene.camera, settings.width, settings.height),
      count_(scene.triangles.size()),
      pixels_(static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height)),
      spp_(static_cast<std::uint32_t>(settings.spp)),
      keep_ids_(keep_ids),
      cull_(kernel_cull_method(settings.cull)),
      cells_per_triangle_(cells_per_triangle_for(settings.cull)),
      triangles_(frame_triangles(scene, model_, options.force_full_path, render_threads(settings))),
      cell_count_(triangles_.moving_count * static_cast<std::size_t>(cells_per_triangle_)),
      triangle_buffer_(storage_buffer(gl_, triangles_.gpu)),
      info_buffer_(storage_buffer(gl_, std::max<std::size_t>(count_, 1) * sizeof(TriangleInfo))),
      counters_(gl_),
      colour_buffer_(storage_buffer(gl_, frame_colours(flat, scene))),
      sum_buffer_(storage_buffer(gl_, pixels_ * sizeof(glm::vec4))),
      id_buffer_(storage_buffer(gl_, keep_ids ? pixels_ * spp_ * sizeof(std::uint32_t) : 4)),
      cell_buffer_(storage_buffer(gl_, std::max<std::size_t>(cell_count_, 1) * sizeof(CellBounds))),
      pass_sample_buffer_(storage_buffer(gl_, pixels_ * samples_per_pass * sizeof(glm::vec4))),
      pass_time_buffer_(storage_buffer(gl_, pixels_ * samples_per_pass * sizeof(float))),
      class_buffer_(storage_buffer(gl_, triangles_.classes)),
      static_list_buffer_(storage_buffer(gl_, triangles_.static_list)),
      moving_list_buffer_(storage_buffer(gl_, triangles_.moving_list)),
      mask_(gl_, scene) {
    mask_.bind();
    triangle_buffer_.bind_base(BC_GL_TRIANGLES_BINDING);
    info_buffer_.bind_base(BC_GL_INFOS_BINDING);
    counters_.bind_base(BC_GL_COUNTERS_BINDING);
    colour_buffer_.bind_base(BC_GL_COLOURS_BINDING);
    sum_buffer_.bind_base(BC_GL_SUMS_BINDING);
    id_buffer_.bind_base(BC_GL_SAMPLE_IDS_BINDING);
    cell_buffer_.bind_base(BC_GL_CELLS_BINDING);
    pass_sample_buffer_.bind_base(BC_GL_PASS_SAMPLES_BINDING);
    pass_time_buffer_.bind_base(BC_GL_PASS_TIMES_BINDING);
    class_buffer_.bind_base(BC_GL_CLASSES_BINDING);
    static_list_buffer_.bind_base(BC_GL_STATIC_LIST_BINDING);
    moving_list_buffer_.bind_base(BC_GL_MOVING_LIST_BINDING);
}

void StochasticFrame::run_setup() {
    if (count_ > 0) {
        set_common(gl_, state_.setup, model_, settings_, 0);
        set_int(gl_, state_.setup, "triangle_count", static_cast<int>(count_));
        set_int(gl_, state_.setup, "method", cull_);
        set_int(gl_, state_.setup, "force_full", options_.force_full_path ? 1 : 0);
        gl_.DispatchCompute(static_cast<GLuint>((count_ + 63) / 64), 1, 1);
        gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        set_common(gl_, state_.bounds, model_, settings_, 0);
        set_int(gl_, state_.bounds, "moving_count", static_cast<int>(triangles_.moving_count));
        set_int(gl_, state_.bounds, "cells_per_triangle", cells_per_triangle_);
        set_int(gl_, state_.bounds, "method", cull_);
        set_int(gl_, state_.bounds, "cell_pixels", options_.cell_pixels);
        gl_.DispatchCompute(static_cast<GLuint>((cell_count_ + 63) / 64), 1, 1);
        gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    id_depth_.emplace(gl_, settings_.width, settings_.height, samples_per_pass, "the multisample id/depth framebuffer");
    id_depth_->bind_with_depth_rule();
    gl_.Enable(GL_MULTISAMPLE);
    gl_.BindVertexArray(state_.vertex_array.id());
    gl_.ActiveTexture(GL_TEXTURE0 + BC_GL_PASS_IDS_UNIT);
    gl_.BindTexture(GL_TEXTURE_2D_MULTISAMPLE, id_depth_->id_texture());
    gl_.Finish();
    gl::check_gl(gl_, "gl: setup");
}

void StochasticFrame::compute_samples(std::uint32_t base, std::uint32_t stride) const {
    set_common(gl_, state_.samples, model_, settings_, base);
    set_uint(gl_, state_.samples, "stride", stride);
    gl_.DispatchCompute(static_cast<GLuint>((settings_.width + 7) / 8), static_cast<GLuint>((settings_.height + 7) / 8),
                        1);
    gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void StochasticFrame::run_passes(RenderStats& stats, StepTimer& timer) {
    const std::uint32_t passes = (spp_ + samples_per_pass - 1) / samples_per_pass;
    const StaticGroups groups(gl_, static_group_samples(passes, pixels_, options_), triangles_.static_count > 0,
                              pixels_);
    std::uint32_t group_base = 0;
    for (std::uint32_t pass = 0; pass < passes; ++pass) {
        const std::uint32_t pass_base = pass * samples_per_pass;
        if (groups.used && pass_base % groups.samples == 0) {
            group_base = pass_base;
            draw_static_group(groups, group_base, stats, timer);
        }
        draw_pass(pass_base, groups, group_base, timer);
        resolve_pass(pass_base, stats);
        timer.end(StepTimer::resolve);
    }
    gl_.Finish();
}

void StochasticFrame::draw_static_group(const StaticGroups& groups, std::uint32_t group_base, RenderStats& stats,
                                        StepTimer& timer) {
    // render_samples.comp writes at the pass's bindings: the group's buffers
    // there for this dispatch, the pass's back after.
    groups.sample_buffer.bind_base(BC_GL_PASS_SAMPLES_BINDING);
    groups.time_buffer.bind_base(BC_GL_PASS_TIMES_BINDING);
    compute_samples(group_base, groups.samples);
    pass_sample_buffer_.bind_base(BC_GL_PASS_SAMPLES_BINDING);
    pass_time_buffer_.bind_base(BC_GL_PASS_TIMES_BINDING);
    const GLuint no_id = no_triangle;
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, groups.id_buffer.id());
    gl_.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &no_id);
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, groups.depth_buffer.id());
    gl_.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    timer.end(StepTimer::samples);
    // One fragment per pixel at its centre (inside the grown outline wherever
    // a sample can be covered); nothing is written to the framebuffer.
    gl_.Disable(GL_DEPTH_TEST);
    gl_.Disable(GL_MULTISAMPLE);
    gl_.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl_.DepthMask(GL_FALSE);
    set_common(gl_, state_.draw_static_group, model_, settings_, group_base);
    set_uint(gl_, state_.draw_static_group, "group_samples", groups.samples);
    gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles_.static_count * 3));
    gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.Enable(GL_MULTISAMPLE);
    gl_.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.DepthMask(GL_TRUE);
    counters_.add_to(stats);
    timer.end(StepTimer::static_draw);
}

void StochasticFrame::draw_pass(std::uint32_t pass_base, const StaticGroups& groups, std::uint32_t group_base,
                                StepTimer& timer) {
    const GLuint clear_id[4] = {no_triangle, 0, 0, 0};
    const GLfloat clear_depth = 0.0f;
    compute_samples(pass_base, pass_samples);
    gl_.ClearBufferuiv(GL_COLOR, 0, clear_id);
    gl_.ClearBufferfv(GL_DEPTH, 0, &clear_depth);
    timer.end(StepTimer::samples);
    if (count_ == 0) return;
    // Three vertices per static triangle, six (a quad) per moving triangle's cell.
    if (groups.used) {
        set_common(gl_, state_.static_fill, model_, settings_, pass_base);
        set_uint(gl_, state_.static_fill, "group_samples", groups.samples);
        set_uint(gl_, state_.static_fill, "group_base", group_base);
        gl_.DrawArrays(GL_TRIANGLES, 0, 3);
    } else {
        set_common(gl_, state_.draw_static, model_, settings_, pass_base);
        gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles_.static_count * 3));
    }
    timer.end(StepTimer::static_draw);
    set_common(gl_, state_.draw_moving, model_, settings_, pass_base);
    set_int(gl_, state_.draw_moving, "cells_per_triangle", cells_per_triangle_);
    gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(cell_count_ * 6));
    timer.end(StepTimer::moving);
}

void StochasticFrame::resolve_pass(std::uint32_t pass_base, RenderStats& stats) {
    gl_.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    set_common(gl_, state_.resolve, model_, settings_, pass_base);
    set_uint(gl_, state_.resolve, "background", static_cast<std::uint32_t>(count_));
    set_int(gl_, state_.resolve, "keep_ids", keep_ids_ ? 1 : 0);
    set_int(gl_, state_.resolve, "pass_ids", 0);
    set_int(gl_, state_.resolve, "ids_in_buffer", 0);
    gl_.DispatchCompute(static_cast<GLuint>((settings_.width + 7) / 8), static_cast<GLuint>((settings_.height + 7) / 8),
                        1);
    gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    counters_.add_to(stats);
    gl::check_gl(gl_, "gl: raster pass");
}

Image StochasticFrame::read_back(std::vector<std::uint32_t>* sample_ids) const {
    Image image = image_from_sums(sum_buffer_, settings_);
    if (keep_ids_) {
        sample_ids->assign(pixels_ * spp_, no_triangle);
        id_buffer_.read(sample_ids->data(), sample_ids->size() * sizeof(std::uint32_t));
    }
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::check_gl(gl_, "gl: readback");
    return image;
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

const gl::HeadlessContext& GlRenderer::context() const { return state_->context; }

std::string GlRenderer::description() const {
    return std::string(gl::context_kind_name(state_->context.kind())) + ", " + state_->context.renderer() + ", " +
           state_->context.version();
}

RenderResult GlRenderer::render(const Scene& scene, const RenderSettings& settings, const GlOptions& options,
                                std::vector<std::uint32_t>* sample_ids) {
    if (options.pipeline == GlPipeline::compute) {
        state_->context.make_current();
        return render_gl_compute(state_->context, state_->compute, scene, settings, options, sample_ids);
    }
    if (settings.method != RenderMethod::stochastic) {
        state_->context.make_current();
        return render_gl_method(state_->context, state_->methods, scene, settings,
                                options.keep_sample_ids ? sample_ids : nullptr);
    }
    const Clock::time_point start = Clock::now();
    check_stochastic_request(scene, settings, options);
    state_->context.make_current();
    require_target_fits(state_->context.gl(), settings.width, settings.height, settings.width, settings.height);
    check_triangle_limit(scene.triangles.size());

    RenderResult result;
    RenderStats& stats = result.stats;
    stats.triangles = scene.triangles.size();
    Clock::time_point phase = Clock::now();
    // Per-hit shading (textures, vertex colours, normals) is resolved on the
    // host from the winners the GPU read back, with the CPU backend's
    // function: the shading contract's resolve step (docs/gl-backend.md).
    const SurfaceShader shader(scene, CameraModel(scene.camera, settings.width, settings.height),
                               render_threads(settings));
    std::vector<std::uint32_t> winners;
    std::vector<std::uint32_t>* kept_ids = shader.any_per_hit() && sample_ids == nullptr ? &winners : sample_ids;
    const bool keep_ids = (options.keep_sample_ids && sample_ids != nullptr) || shader.any_per_hit();
    StochasticFrame frame(*state_, scene, settings, options, keep_ids, shader.flat_colours());
    frame.run_setup();
    stats.ms_per_phase.emplace_back("setup", ms_since(phase));

    phase = Clock::now();
    StepTimer timer(state_->context.gl(), options.time_steps);
    frame.run_passes(stats, timer);
    stats.ms_per_phase.emplace_back("raster+resolve", ms_since(phase));
    timer.add_to(stats);

    phase = Clock::now();
    result.image = frame.read_back(keep_ids ? kept_ids : nullptr);
    if (shader.any_per_hit()) {
        result.image = resolve_sample_ids(shader, CameraModel(scene.camera, settings.width, settings.height), settings,
                                          *kept_ids);
    }
    stats.ms_per_phase.emplace_back("readback", ms_since(phase));
    stats.ms_total = ms_since(start);
    return result;
}

namespace {

// What render_gl and render_gl_frame refuse before any GL work.
void check_gl_request(const Scene& scene, const RenderSettings& settings) {
    validate_settings(settings);
    require_valid_scene(scene);
    refuse_motion_segments(scene, "gl");
}

}  // namespace

RenderResult render_gl(const Scene& scene, const RenderSettings& settings, const GlOptions& options) {
    const Clock::time_point start = Clock::now();
    check_gl_request(scene, settings);
    GlRenderer renderer;
    return render_gl_frame(renderer, scene, settings, options, ms_since(start));
}

RenderResult render_gl_frame(GlRenderer& renderer, const Scene& scene, const RenderSettings& settings,
                             const GlOptions& options, double made_ms) {
    const Clock::time_point start = Clock::now();
    check_gl_request(scene, settings);
    RenderSettings warm_up = settings;
    warm_up.width = 1;
    warm_up.height = 1;
    warm_up.spp = 4;
    warm_up.progress = false;
    renderer.render(scene, warm_up, options);
    const double compile_ms = made_ms + ms_since(start);
    RenderResult result = renderer.render(scene, settings, options);
    result.stats.ms_per_phase.insert(result.stats.ms_per_phase.begin(), {"compile", compile_ms});
    result.stats.ms_total = made_ms + ms_since(start);
    return result;
}

// Whether the machine has a device a hardware OpenGL driver could drive: a
// DRM node (/dev/dri/renderD*, /dev/dri/card*: Mesa's drivers) or an NVIDIA
// device (/dev/nvidia*). Without one every context is software, and making
// one to ask costs tens of milliseconds (loading and initialising the driver).
static bool gpu_device_present() {
#if defined(__linux__)
    namespace fs = std::filesystem;
    std::error_code error;
    for (const char* folder : {"/dev/dri", "/dev"}) {
        for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
            const std::string name = it->path().filename().string();
            const bool drm = std::string(folder) == "/dev/dri" &&
                             (name.rfind("renderD", 0) == 0 || name.rfind("card", 0) == 0);
            if (drm || (std::string(folder) == "/dev" && name.rfind("nvidia", 0) == 0)) return true;
        }
        error.clear();
    }
    return false;
#else
    return true;  // elsewhere: ask a context
#endif
}

std::unique_ptr<gl::HeadlessContext> hardware_gl_context(std::string* reason) {
    if (!gpu_device_present()) {
        if (reason != nullptr) *reason = "no GPU device (/dev/dri, /dev/nvidia*), only software OpenGL";
        return nullptr;
    }
    try {
        auto context = std::make_unique<gl::HeadlessContext>(gl::HeadlessContext::create());
        if (context->software()) {
            if (reason != nullptr)
                *reason = "only a software renderer, " + context->renderer() + ", slower than the cpu backend";
            return nullptr;
        }
        return context;
    } catch (const std::exception& e) {
        if (reason != nullptr) *reason = e.what();
        return nullptr;
    }
}

}  // namespace blurcull::frontend
