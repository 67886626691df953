// The GL backend's compute pipeline for the stochastic method
// (GlOptions::pipeline = GlPipeline::compute, `blurcull render --backend gl
// --gl-pipeline compute`): the CPU backend's tiled design as compute passes,
// for GPUs whose graphics stages run on a few of their multiprocessors (an
// H200: 4 of 132). Per frame: render_setup.comp (the kernel's screen bound
// per triangle), binning to 8x8-pixel tiles (render_compute_bin.comp count,
// render_compute_scan.comp prefix sum, render_compute_bin.comp fill),
// render_compute_raster.comp (a work group per tile: the kernel's sample
// bounds per tile, bc_sample_test, the depth rule), render_resolve.comp (the
// fragment pipeline's resolve, reading the ids from a buffer). Same samples
// and decisions as the fragment pipeline and the CPU float path.
// docs/gl-backend.md, "The compute pipeline".
#pragma once

#include "render/common/render_types.hpp"
#include "render/gl/gl_context.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace blurcull::frontend {

struct GlOptions;

// The compute pipeline's programs, compiled on first use and kept with the
// renderer, with the tile-list capacity the last frame needed.
struct GlComputePrograms;

// One stochastic frame through the compute pipeline on `context` (current).
// sample_ids as GlRenderer::render's (filled when options.keep_sample_ids).
// ms_per_phase: setup, raster+resolve, readback (wall), then gpu_setup,
// gpu_binning, gpu_raster, gpu_resolve (GL timer queries, summed over a
// retried binning; ~0 on llvmpipe, whose queries do not time compute work)
// and wall_setup ... wall_resolve (the host's clock over each); counters: tile_list_entries, tile_list_capacity,
// tile_list_retries. Throws std::invalid_argument for bad settings or a
// method other than stochastic, gl::GlError when the scene or the tile lists
// exceed the GL's limits.
RenderResult render_gl_compute(const gl::HeadlessContext& context, std::shared_ptr<GlComputePrograms>& programs,
                               const Scene& scene, const RenderSettings& settings, const GlOptions& options,
                               std::vector<std::uint32_t>* sample_ids);

}  // namespace blurcull::frontend
