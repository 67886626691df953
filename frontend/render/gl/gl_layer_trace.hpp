// The GL build of dof-secondary's image-space tracing step: a compute pass
// (shaders/render_secondary_trace.comp) that runs the kernel's emitted
// layer_trace_begin / layer_trace_step over a cluster's layered depth images,
// one invocation per ray (docs/secondary-rays.md, "The renderer"); and the
// GPU-resident bounce of a cluster: the groups' interval clipping
// (shaders/render_secondary_clip.comp), the traces and the hits' surfaces on
// the layers where GlLayerBuilder::build_resident left them.
#pragma once

#include "render/common/bounce_shared.h"
#include "render/gl/gl_context.hpp"
#include "render/gl/gl_layer_images.hpp"

#include <blurcull/kernel.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace blurcull::frontend {

// Groups of rays as the clip pass reads them: how many, then each one's
// (begin, end); from the host's group ends (group g: rays
// [g ? group_ends[g - 1] : 0, group_ends[g])).
std::vector<std::uint32_t> group_words(const std::vector<std::uint32_t>& group_ends);

class GlLayerTracer {
public:
    // On `context` (kept alive by the caller; made current here, and by its
    // destructor to delete its program); compiles the pass. trace() runs on
    // the current context: the caller makes `context` current first.
    // Throws gl::GlError with the compiler's log.
    explicit GlLayerTracer(const gl::HeadlessContext& context);
    ~GlLayerTracer();
    GlLayerTracer(const GlLayerTracer&) = delete;
    GlLayerTracer& operator=(const GlLayerTracer&) = delete;

    // The hits of `segments` (clipped by kernelf::layer_segment for `view`) in
    // depth images [layer][y][x] of view.size^2 texels each: what
    // trace_layers gives on the host.
    std::vector<kernelf::LayerHit> trace(const kernelf::LayerView& view, const std::vector<float>& depth, int layers,
                                         float thickness, const std::vector<kernelf::LayerSegment>& segments) const;

    // The GPU-resident bounce of a render's clusters, none waiting for the
    // last: begin_bounces makes room for `rays` hits; queue_bounce takes a
    // cluster's rays in the layers `built` made by its last build_resident
    // for `view` (`layers` per texel): ray i starts at starts[i] along
    // directions[i]; group g, rays [g ? group_ends[g - 1] : 0,
    // group_ends[g]), is clipped together by the pyramid (the host's
    // clip_group), then each ray is traced and its hit's surface picked (the
    // host's hit_triangle), its hit stored at first + i; finish_bounces reads
    // the first `rays` hits back, waiting for the GPU once (a hit no queued
    // ray wrote: LayerBounceHit::traced false). The next
    // build_resident may follow queue_bounce at once: GL runs the passes in
    // order.
    void begin_bounces(std::size_t rays) const;
    void queue_bounce(const kernelf::LayerView& view, int layers, float thickness, const GlLayerBuilder& built,
                      const std::vector<glm::vec3>& starts, const std::vector<glm::vec3>& directions,
                      const std::vector<std::uint32_t>& group_ends, std::size_t first) const;
    // queue_bounce with the `rays` rays gathered on the GPU instead of
    // uploaded: ray i is the point indices[i] of `points` (GlClustering's
    // buffer: position and direction, vec4 each), started at position +
    // offset * direction (render_secondary_gather.comp; the host's start to
    // the bit), and its hit stored at indices[i], the batch's ray it is
    // (finish_bounces then reads one hit per ray of the batch). The groups
    // are in `groups` on the GPU, group_words' layout, at most `max_groups`
    // of them. Only what the caller put in `indices` and `groups` crossed
    // the bus, if anything.
    void queue_bounce_gathered(const kernelf::LayerView& view, int layers, float thickness,
                               const GlLayerBuilder& built, const gl::Buffer& points, const gl::Buffer& indices,
                               std::size_t rays, float offset, const gl::Buffer& groups,
                               std::size_t max_groups) const;
    std::vector<LayerBounceHit> finish_bounces(std::size_t rays) const;

private:
    const gl::HeadlessContext* context_;
    const gl::Functions* gl_;
    std::unique_ptr<gl::Program> program_;
    std::unique_ptr<gl::Program> clip_program_;
    std::unique_ptr<gl::Program> gather_program_;
    // The passes' buffers (trace's depths; view, rays, groups, segments,
    // hits; the bounce's hits, 2 words a ray), kept from one cluster to the
    // next.
    mutable std::optional<gl::Buffer> depths_, view_, rays_, groups_, segments_, hits_, bounce_hits_;

    // The trace pass over `count` segments in the bound buffers: trace()'s
    // (8 words a ray at BC_GL_TRACE_HITS_BINDING, not picking surfaces), or
    // the bounce's (picking them; hits from `hit_offset`).
    void run_trace(std::size_t count, bool pick_surface, std::size_t hit_offset, bool hits_by_index = false) const;
    // Throws unless begin_bounces made room for `rays` hits from `first`.
    void check_room(std::size_t first, std::size_t rays) const;
    // A queued bounce's clipping and traces, its `rays` rays in rays_, its
    // groups in `groups` (at most max_groups); hits from `first`, or by the
    // ray indices bound at BC_GL_GATHER_INDICES_BINDING.
    void clip_and_trace(const kernelf::LayerView& view, int layers, float thickness, const GlLayerBuilder& built,
                        std::size_t rays, const gl::Buffer& groups, std::size_t max_groups, bool hits_by_index,
                        std::size_t first) const;
};

}  // namespace blurcull::frontend
