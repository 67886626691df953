// --method dof-secondary on the gl backend: the GL rasterizer's per-sample
// winners as the primary pass and the image-space traces in a compute pass
// (GlLayerTracer), handed to render_dof_secondary (the rest of the method on
// the host). `blurcull render --backend gl` and `blurcull view` both render
// through it (docs/secondary-rays.md, "The renderer").
#pragma once

#include "render/common/render_types.hpp"
#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/gl_layer_trace.hpp"
#include "render/secondary/dof_secondary.hpp"
#include "render/secondary/secondary_options.hpp"
#include "scene/scene.hpp"

namespace blurcull::frontend {

class GlDofSecondary {
public:
    // `rasterizer` renders the primary samples on its own context (made
    // current by its render), `trace_context` runs the trace pass (made
    // current here, compiling it); both may be one window's context, and the
    // caller keeps both alive while this object is used.
    GlDofSecondary(GlRenderer& rasterizer, const gl::HeadlessContext& trace_context);

    // render_dof_secondary of `scene` with the GL passes; `gl_options` are
    // the rasterizer's (sample ids are kept whatever they say). Throws as
    // render_dof_secondary and GlRenderer::render do.
    RenderResult render(const Scene& scene, const RenderSettings& settings, const GlOptions& gl_options,
                        const SecondaryOptions& options, SecondaryStats* stats = nullptr) const;

private:
    GlRenderer* rasterizer_;
    const gl::HeadlessContext* trace_context_;
    GlLayerTracer tracer_;
};

}  // namespace blurcull::frontend
