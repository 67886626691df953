#include "render/gl/gl_layer_trace.hpp"

#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace blurcull::frontend {

GlLayerTracer::GlLayerTracer(const gl::HeadlessContext& context)
    : context_((context.make_current(), &context)),
      gl_(&context.gl()),
      program_(std::make_unique<gl::Program>(
          context.gl(),
          std::vector<gl::ShaderStage>{gl::shader_stage(GL_COMPUTE_SHADER, "render_secondary_trace.comp", gl::Prelude::secondary)})),
      clip_program_(std::make_unique<gl::Program>(
          context.gl(),
          std::vector<gl::ShaderStage>{gl::shader_stage(GL_COMPUTE_SHADER, "render_secondary_clip.comp", gl::Prelude::secondary)})) {}

// The program's glDeleteProgram acts on the current context: this one's, with several alive.
GlLayerTracer::~GlLayerTracer() { context_->make_current_for_release(); }

namespace {

// Dispatches `items` invocations of the bound program's 64-wide work
// groups, as render_secondary_common.glsl's dispatch_item numbers them:
// rows of at most 65,535 groups (the least GL_MAX_COMPUTE_WORK_GROUP_COUNT
// a GL 4.3 context offers), so a cluster of more than 4.2 million rays
// fits. The shaders skip items past the count.
void dispatch_items(const gl::Functions& f, std::size_t items) {
    constexpr std::size_t row = 65535;
    const std::size_t groups = (items + 63) / 64;
    const auto x = static_cast<GLuint>(std::min(groups, row));
    const auto y = static_cast<GLuint>((groups + row - 1) / row);
    f.DispatchCompute(x, y, 1);
}

// The view as render_secondary_common.glsl reads it.
std::vector<float> view_values(const kernelf::LayerView& view, int layers, float thickness) {
    return {view.eye.x,     view.eye.y,     view.eye.z,        view.forward.x, view.forward.y,   view.forward.z,
            view.right.x,   view.right.y,   view.right.z,      view.up.x,      view.up.y,        view.up.z,
            view.tan_half_fov, view.near,   view.far,          float(view.size), float(layers),  thickness};
}

}  // namespace

std::vector<kernelf::LayerHit> GlLayerTracer::trace(const kernelf::LayerView& view, const std::vector<float>& depth,
                                                    int layers, float thickness,
                                                    const std::vector<kernelf::LayerSegment>& segments) const {
    std::vector<kernelf::LayerHit> hits(segments.size());
    if (segments.empty()) return hits;
    const gl::Functions& f = *gl_;
    std::vector<float> packed(segments.size() * 10, 0.0f);
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const kernelf::LayerSegment& s = segments[i];
        const float values[10] = {s.empty ? 1.0f : 0.0f, s.s0, s.s1, s.z0, s.z1, s.p0.x, s.p0.y, s.p1.x, s.p1.y, 0.0f};
        std::memcpy(&packed[i * 10], values, sizeof values);
    }
    const std::vector<float> view_floats = view_values(view, layers, thickness);
    const gl::Buffer depth_buffer(f, GL_SHADER_STORAGE_BUFFER, depth.size() * sizeof(float), depth.data());
    const gl::Buffer segment_buffer(f, GL_SHADER_STORAGE_BUFFER, packed.size() * sizeof(float), packed.data());
    const gl::Buffer view_buffer(f, GL_SHADER_STORAGE_BUFFER, view_floats.size() * sizeof(float), view_floats.data());
    const gl::Buffer hit_buffer(f, GL_SHADER_STORAGE_BUFFER, segments.size() * 8 * sizeof(std::uint32_t));
    depth_buffer.bind_base(BC_GL_TRACE_DEPTHS_BINDING);
    segment_buffer.bind_base(BC_GL_TRACE_SEGMENTS_BINDING);
    view_buffer.bind_base(BC_GL_TRACE_VIEW_BINDING);
    hit_buffer.bind_base(BC_GL_TRACE_HITS_BINDING);
    depth_buffer.bind_base(BC_GL_TRACE_TRIANGLE_IDS_BINDING);  // never read: no surface picked here
    const auto count = static_cast<GLuint>(segments.size());
    f.UseProgram(program_->id());
    f.Uniform1ui(f.GetUniformLocation(program_->id(), "count"), count);
    f.Uniform1i(f.GetUniformLocation(program_->id(), "pick_surface"), 0);
    dispatch_items(f, count);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::check_gl(f, "dof-secondary: the layer trace pass");
    std::vector<std::uint32_t> out(segments.size() * 8);
    hit_buffer.read(out.data(), out.size() * sizeof(std::uint32_t));
    f.UseProgram(0);
    auto as_float = [](std::uint32_t bits) {
        float value;
        std::memcpy(&value, &bits, sizeof value);
        return value;
    };
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const std::uint32_t* o = &out[i * 8];
        kernelf::LayerHit& h = hits[i];
        h.hit = o[0] != 0u;
        h.layer = static_cast<int>(o[1]) - 1;
        h.steps = static_cast<int>(o[2]);
        h.s = as_float(o[3]);
        h.depth = as_float(o[4]);
        h.image = glm::vec2(as_float(o[5]), as_float(o[6]));
    }
    return hits;
}

std::vector<LayerBounceHit> GlLayerTracer::bounce(const kernelf::LayerView& view, int layers, float thickness,
                                                const GlLayerBuilder& built, const std::vector<glm::vec3>& starts,
                                                const std::vector<glm::vec3>& directions,
                                                const std::vector<std::uint32_t>& group_ends) const {
    std::vector<LayerBounceHit> hits(starts.size());
    if (starts.empty() || group_ends.empty()) return hits;
    const gl::Functions& f = *gl_;
    std::vector<glm::vec4> rays(2 * starts.size());
    for (std::size_t i = 0; i < starts.size(); ++i) {
        rays[2 * i] = glm::vec4(starts[i], 0.0f);
        rays[2 * i + 1] = glm::vec4(directions[i], 0.0f);
    }
    const std::vector<float> view_floats = view_values(view, layers, thickness);
    const gl::Buffer& view_buffer = gl::reserve_storage(f, view_, view_floats.size() * sizeof(float), view_floats.data());
    const gl::Buffer& ray_buffer = gl::reserve_storage(f, rays_, rays.size() * sizeof(glm::vec4), rays.data());
    const gl::Buffer& group_buffer =
        gl::reserve_storage(f, groups_, group_ends.size() * sizeof(std::uint32_t), group_ends.data());
    const gl::Buffer& segment_buffer = gl::reserve_storage(f, segments_, starts.size() * 10 * sizeof(float));
    const gl::Buffer& hit_buffer = gl::reserve_storage(f, hits_, starts.size() * 8 * sizeof(std::uint32_t));
    view_buffer.bind_base(BC_GL_TRACE_VIEW_BINDING);
    ray_buffer.bind_base(BC_GL_TRACE_RAYS_BINDING);
    group_buffer.bind_base(BC_GL_TRACE_GROUPS_BINDING);
    segment_buffer.bind_base(BC_GL_TRACE_SEGMENTS_BINDING);
    hit_buffer.bind_base(BC_GL_TRACE_HITS_BINDING);
    built.depth_buffer().bind_base(BC_GL_TRACE_DEPTHS_BINDING);
    built.triangle_buffer().bind_base(BC_GL_TRACE_TRIANGLE_IDS_BINDING);
    built.pyramid_buffer().bind_base(BC_GL_TRACE_PYRAMID_BINDING);
    const auto groups = static_cast<GLuint>(group_ends.size());
    f.UseProgram(clip_program_->id());
    f.Uniform1ui(f.GetUniformLocation(clip_program_->id(), "groups"), groups);
    dispatch_items(f, groups);
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const auto count = static_cast<GLuint>(starts.size());
    f.UseProgram(program_->id());
    f.Uniform1ui(f.GetUniformLocation(program_->id(), "count"), count);
    f.Uniform1i(f.GetUniformLocation(program_->id(), "pick_surface"), 1);
    dispatch_items(f, count);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::check_gl(f, "dof-secondary: the clip and trace passes");
    std::vector<std::uint32_t> out(starts.size() * 8);
    hit_buffer.read(out.data(), out.size() * sizeof(std::uint32_t));
    f.UseProgram(0);
    for (std::size_t i = 0; i < hits.size(); ++i) {
        hits[i].hit = out[i * 8] != 0u;
        hits[i].steps = static_cast<int>(out[i * 8 + 2]);
        hits[i].triangle = out[i * 8 + 7];
    }
    return hits;
}

}  // namespace blurcull::frontend
