#include "render/gl/gl_layer_trace.hpp"

#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace blurcull::frontend {

namespace {

// A compute pass of dof-secondary's (Prelude::secondary).
std::unique_ptr<gl::Program> secondary_program(const gl::Functions& f, std::string_view main_name) {
    return std::make_unique<gl::Program>(
        f, std::vector<gl::ShaderStage>{gl::shader_stage(GL_COMPUTE_SHADER, main_name, gl::Prelude::secondary)});
}

// Dispatches `items` invocations of the bound program's 64-wide work
// groups, as render_secondary_common.glsl's dispatch_item numbers them (in
// rows, so a cluster of more than 4.2 million rays fits). The shaders skip
// items past the count.
void dispatch_items(const gl::Functions& f, std::size_t items) { gl::dispatch_in_rows(f, (items + 63) / 64); }

// `slot`'s buffer with room for `bytes` (gl::reserve_storage; `data` copied
// in), bound at `binding`.
void bind_storage(const gl::Functions& f, std::optional<gl::Buffer>& slot, GLuint binding, std::size_t bytes,
                  const void* data = nullptr) {
    gl::reserve_storage(f, slot, bytes, data).bind_base(binding);
}

// The view as render_secondary_common.glsl reads it.
std::vector<float> view_values(const kernelf::LayerView& view, int layers, float thickness) {
    return {view.eye.x,     view.eye.y,     view.eye.z,        view.forward.x, view.forward.y,   view.forward.z,
            view.right.x,   view.right.y,   view.right.z,      view.up.x,      view.up.y,        view.up.z,
            view.tan_half_fov, view.near,   view.far,          float(view.size), float(layers),  thickness};
}

}  // namespace

std::vector<std::uint32_t> group_words(const std::vector<std::uint32_t>& group_ends) {
    std::vector<std::uint32_t> words{static_cast<std::uint32_t>(group_ends.size())};
    words.reserve(1 + 2 * group_ends.size());
    std::uint32_t begin = 0;
    for (std::uint32_t end : group_ends) {
        words.push_back(begin);
        words.push_back(end);
        begin = end;
    }
    return words;
}

GlLayerTracer::GlLayerTracer(const gl::HeadlessContext& context)
    : context_((context.make_current(), &context)),
      gl_(&context.gl()),
      program_(secondary_program(context.gl(), "render_secondary_trace.comp")),
      clip_program_(secondary_program(context.gl(), "render_secondary_clip.comp")),
      gather_program_(std::make_unique<gl::Program>(
          context.gl(), std::vector<gl::ShaderStage>{gl::shader_stage(
                            GL_COMPUTE_SHADER, "render_secondary_gather.comp", gl::Prelude::clusters)})) {}

// The programs' and buffers' glDelete* act on the current context: this one's, with several alive.
GlLayerTracer::~GlLayerTracer() { context_->make_current_for_release(); }

void GlLayerTracer::run_trace(std::size_t count, bool pick_surface, std::size_t hit_offset,
                              bool hits_by_index) const {
    const gl::Functions& f = *gl_;
    f.UseProgram(program_->id());
    f.Uniform1ui(f.GetUniformLocation(program_->id(), "count"), static_cast<GLuint>(count));
    f.Uniform1i(f.GetUniformLocation(program_->id(), "pick_surface"), pick_surface ? 1 : 0);
    f.Uniform1ui(f.GetUniformLocation(program_->id(), "hit_offset"), static_cast<GLuint>(hit_offset));
    f.Uniform1i(f.GetUniformLocation(program_->id(), "hits_by_index"), hits_by_index ? 1 : 0);
    dispatch_items(f, count);
    // Its hits for the read-back, its reads before the next cluster's layer passes write.
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    f.UseProgram(0);
}

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
    const gl::Buffer& depth_buffer = gl::reserve_storage(f, depths_, depth.size() * sizeof(float), depth.data());
    depth_buffer.bind_base(BC_GL_TRACE_DEPTHS_BINDING);
    depth_buffer.bind_base(BC_GL_TRACE_TRIANGLE_IDS_BINDING);  // never read: no surface picked here
    depth_buffer.bind_base(BC_GL_GATHER_INDICES_BINDING);      // nor hits stored by index
    bind_storage(f, segments_, BC_GL_TRACE_SEGMENTS_BINDING, packed.size() * sizeof(float), packed.data());
    bind_storage(f, view_, BC_GL_TRACE_VIEW_BINDING, view_floats.size() * sizeof(float), view_floats.data());
    bind_storage(f, hits_, BC_GL_TRACE_HITS_BINDING, segments.size() * 8 * sizeof(std::uint32_t));
    run_trace(segments.size(), false, 0);
    gl::check_gl(f, "dof-secondary: the layer trace pass");
    std::vector<std::uint32_t> out(segments.size() * 8);
    hits_->read(out.data(), out.size() * sizeof(std::uint32_t));
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

// A hit's first word before a trace writes it: no trace writes all ones (steps < 2^31).
constexpr std::uint32_t not_traced = 0xFFFFFFFFu;

void GlLayerTracer::begin_bounces(std::size_t rays) const {
    const gl::Functions& f = *gl_;
    const gl::Buffer& hits = gl::reserve_storage(f, bounce_hits_, rays * 2 * sizeof(std::uint32_t));
    f.BindBuffer(GL_SHADER_STORAGE_BUFFER, hits.id());
    f.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &not_traced);
    f.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

void GlLayerTracer::check_room(std::size_t first, std::size_t rays) const {
    if (!bounce_hits_ || bounce_hits_->size() < (first + rays) * 2 * sizeof(std::uint32_t))
        throw gl::GlError("gl: queue_bounce past the " + std::to_string(bounce_hits_ ? bounce_hits_->size() / 8 : 0) +
                          " hits begin_bounces made room for");
}

void GlLayerTracer::queue_bounce(const kernelf::LayerView& view, int layers, float thickness,
                                 const GlLayerBuilder& built, const std::vector<glm::vec3>& starts,
                                 const std::vector<glm::vec3>& directions,
                                 const std::vector<std::uint32_t>& group_ends, std::size_t first) const {
    if (starts.empty() || group_ends.empty()) return;
    check_room(first, starts.size());
    std::vector<glm::vec4> rays(2 * starts.size());
    for (std::size_t i = 0; i < starts.size(); ++i) {
        rays[2 * i] = glm::vec4(starts[i], 0.0f);
        rays[2 * i + 1] = glm::vec4(directions[i], 0.0f);
    }
    bind_storage(*gl_, rays_, BC_GL_TRACE_RAYS_BINDING, rays.size() * sizeof(glm::vec4), rays.data());
    const std::vector<std::uint32_t> words = group_words(group_ends);
    const gl::Buffer& groups = gl::reserve_storage(*gl_, groups_, words.size() * sizeof(std::uint32_t), words.data());
    rays_->bind_base(BC_GL_GATHER_INDICES_BINDING);  // never read: hits stored from `first`
    clip_and_trace(view, layers, thickness, built, starts.size(), groups, group_ends.size(), false, first);
}

void GlLayerTracer::queue_bounce_gathered(const kernelf::LayerView& view, int layers, float thickness,
                                          const GlLayerBuilder& built, const gl::Buffer& points,
                                          const gl::Buffer& indices, std::size_t rays, float offset,
                                          const gl::Buffer& groups, std::size_t max_groups) const {
    if (rays == 0 || max_groups == 0) return;
    check_room(0, rays);  // the indices are the batch's rays, fewer than begin_bounces made room for
    const gl::Functions& f = *gl_;
    points.bind_base(BC_GL_CLUSTER_POINTS_BINDING);
    indices.bind_base(BC_GL_GATHER_INDICES_BINDING);
    bind_storage(f, rays_, BC_GL_TRACE_RAYS_BINDING, rays * 2 * sizeof(glm::vec4));
    f.UseProgram(gather_program_->id());
    f.Uniform1ui(f.GetUniformLocation(gather_program_->id(), "count"), static_cast<GLuint>(rays));
    f.Uniform1f(f.GetUniformLocation(gather_program_->id(), "offset"), offset);
    dispatch_items(f, rays);
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    clip_and_trace(view, layers, thickness, built, rays, groups, max_groups, true, 0);
}

void GlLayerTracer::clip_and_trace(const kernelf::LayerView& view, int layers, float thickness,
                                   const GlLayerBuilder& built, std::size_t rays, const gl::Buffer& groups,
                                   std::size_t max_groups, bool hits_by_index, std::size_t first) const {
    const gl::Functions& f = *gl_;
    const std::vector<float> view_floats = view_values(view, layers, thickness);
    bind_storage(f, view_, BC_GL_TRACE_VIEW_BINDING, view_floats.size() * sizeof(float), view_floats.data());
    rays_->bind_base(BC_GL_TRACE_RAYS_BINDING);
    groups.bind_base(BC_GL_TRACE_GROUPS_BINDING);
    bind_storage(f, segments_, BC_GL_TRACE_SEGMENTS_BINDING, rays * 10 * sizeof(float));
    bounce_hits_->bind_base(BC_GL_TRACE_HITS_BINDING);
    built.depth_buffer().bind_base(BC_GL_TRACE_DEPTHS_BINDING);
    built.triangle_buffer().bind_base(BC_GL_TRACE_TRIANGLE_IDS_BINDING);
    built.pyramid_buffer().bind_base(BC_GL_TRACE_PYRAMID_BINDING);
    f.UseProgram(clip_program_->id());
    dispatch_items(f, max_groups);  // those past the groups' count return at once
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    run_trace(rays, true, first, hits_by_index);
}

std::vector<LayerBounceHit> GlLayerTracer::finish_bounces(std::size_t rays) const {
    std::vector<LayerBounceHit> hits(rays);
    if (rays == 0) return hits;
    gl::check_gl(*gl_, "dof-secondary: the clip and trace passes");
    std::vector<std::uint32_t> out(rays * 2);
    bounce_hits_->read(out.data(), out.size() * sizeof(std::uint32_t));
    for (std::size_t i = 0; i < rays; ++i) {
        hits[i].traced = out[2 * i] != not_traced;
        if (!hits[i].traced) continue;
        hits[i].hit = (out[2 * i] & 1u) != 0u;
        hits[i].steps = static_cast<int>(out[2 * i] >> 1u);
        hits[i].triangle = out[2 * i + 1];
    }
    return hits;
}

}  // namespace blurcull::frontend
