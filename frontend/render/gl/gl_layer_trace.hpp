// The GL build of dof-secondary's image-space tracing step: a compute pass
// (shaders/render_secondary_trace.comp) that runs the kernel's emitted
// layer_trace_begin / layer_trace_step over a cluster's layered depth images,
// one invocation per ray (docs/secondary-rays.md, "The renderer").
#pragma once

#include "render/gl/gl_context.hpp"

#include <blurcull/kernel.hpp>

#include <memory>
#include <vector>

namespace blurcull::frontend {

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

private:
    const gl::HeadlessContext* context_;
    const gl::Functions* gl_;
    std::unique_ptr<gl::Program> program_;
};

}  // namespace blurcull::frontend
