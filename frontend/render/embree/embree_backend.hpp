// The reference renderer: Intel Embree 3 ray casting with the shared thin
// lens, linear motion and sample pattern (docs/reference-renderer.md).
#pragma once

#include "render/common/render_types.hpp"
#include "render/embree/embree_options.hpp"
#include "scene/scene.hpp"

namespace blurcull::frontend {

// Traces settings.spp rays per pixel, sample j of pixel (px, py) taken from
// blurcull::patternsf::sampler_sample(sampler_setup(settings.sampler, px, py,
// spp, seed), j), as on every backend. Deterministic: the
// image depends only on the scene and settings (not on the thread count).
// stats.samples_tested = rays traced, stats.samples_hit = rays that hit.
// Throws std::invalid_argument for bad settings (a settings.method other than
// stochastic among them), SceneError for a bad scene
// (validate_scene), std::runtime_error for Embree failures. `options` choose
// how the rays are traced (every choice gives the same image; the defaults
// are the fastest).
RenderResult render_embree(const Scene& scene, const RenderSettings& settings, const EmbreeOptions& options = {});

}  // namespace blurcull::frontend
