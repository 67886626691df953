// The CPU renderers (interleave.cpp, interval.cpp, accum.cpp) of the other
// published ways to sample motion and defocus blur (docs/sampling.md), next
// to render_cpu's stochastic rasterizer:
//  * interleave — interleaved sampling, Fatahalian et al. 2009's InterleaveUVT
//    with Aqsis 2.0's colour-cornered tiles of (u, v, t) tuples;
//  * interval   — Pixar's INTERVAL: one sample per shutter stratum per pixel,
//    a screen box per stratum;
//  * accum      — the accumulation buffer (Haeberli and Akeley 1990).
// Same scene, camera model, shading, coverage test (kernel<double>::covers),
// z-buffer rule (strict, triangles in index order), resolve and statistics as
// render_cpu; deterministic whatever the thread count. Each throws
// std::invalid_argument for bad settings and SceneError for a bad scene.
#pragma once

#include "render/common/render_types.hpp"
#include "render/common/method_plan.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <vector>

namespace blurcull::frontend {

// settings.spp must be a square s^2: pixel (px, py) holds the s x s lattice
// cells (px s + i, py s + j), sample j s + i, each jittered inside its cell
// and taking the (u, v, t) tuple its tile slot holds. For each tuple k the
// triangle is placed at (u, v, t)_k (a static, sharp 2D triangle) and only the
// lattice cells holding tuple k inside its screen box are tested. The tuples
// are rounded to float, like every other pattern's samples.
// stats.bounds_computed counts the placements, bounds_empty those off screen.
// With sample_ids, sample j of pixel p's triangle (or no_sample_hit) goes to
// (*sample_ids)[p * spp + j], p = py * width + px (all three methods).
RenderResult render_interleave(const Scene& scene, const RenderSettings& settings, const InterleaveOptions& options = {},
                               std::vector<std::uint32_t>* sample_ids = nullptr);

// N = settings.spp shutter strata; sample j of a pixel (patternsf::interval_sample)
// has its time in stratum j. Per stratum, each triangle's screen box over that
// sub-interval and the whole lens bounds the pixels whose sample j is tested.
// stats.bounds_computed counts the boxes, bounds_empty those off screen.
RenderResult render_interval(const Scene& scene, const RenderSettings& settings,
                             std::vector<std::uint32_t>* sample_ids = nullptr);

// K = settings.spp pinhole passes; pass k renders the triangles placed at
// (u, v, t)_k with one sample per pixel at one sub-pixel offset, both
// patternsf::accum_sample(k, settings.seed) (Halton points, Cranley-Patterson
// rotated by the seed), z-buffered; a pixel is the mean of its K passes.
// stats.bounds_computed counts the placements, bounds_empty those off screen.
RenderResult render_accum(const Scene& scene, const RenderSettings& settings,
                          std::vector<std::uint32_t>* sample_ids = nullptr);

// Renders with the renderer settings.method names: render_cpu (with default
// CpuOptions) for stochastic, else one of the above with default options.
RenderResult render_with_method(const Scene& scene, const RenderSettings& settings);

}  // namespace blurcull::frontend
