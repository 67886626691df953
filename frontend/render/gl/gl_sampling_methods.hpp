// The interleave, interval and accum methods on the GL backend
// (GlRenderer::render with settings.method other than "stochastic"): the same
// passes, samples and per-pass boxes as the CPU renderers
// (interleaved_backend.hpp, shared through MethodPlan), each sample tested with
// the kernel's GLSL covers() and a per-sample depth test. docs/gl-backend.md.
#pragma once

#include "render/common/render_types.hpp"
#include "render/gl/gl_context.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace blurcull::frontend {

// The methods' programs, compiled on first use and kept with the renderer.
struct GlMethodPrograms;

// Renders settings.method ("interleave", "interval" or "accum") on `context`
// (current on the calling thread). With sample_ids, fills it as the CPU
// renderers do: (*sample_ids)[p * spp + j], no_sample_hit for the background.
// Throws std::invalid_argument for bad settings or an unknown method,
// SceneError for a bad scene, gl::GlError when the framebuffer (the image;
// interleave: one cell per tile of the width*s x height*s lattice) exceeds
// the context's limits.
RenderResult render_gl_method(const gl::HeadlessContext& context, std::shared_ptr<GlMethodPrograms>& programs,
                              const Scene& scene, const RenderSettings& settings,
                              std::vector<std::uint32_t>* sample_ids = nullptr);

}  // namespace blurcull::frontend
