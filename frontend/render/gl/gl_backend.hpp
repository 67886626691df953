// The OpenGL backend: the same stochastic rasterization as render_cpu (same
// samples, same shading, same per-sample depth test) on a headless OpenGL 4.5
// context, with the kernel's GLSL emitted from the C++ headers. Design and
// numbers: docs/gl-backend.md.
#pragma once

#include "render/common/render_types.hpp"
#include "scene/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace blurcull::gl {
class HeadlessContext;
}

namespace blurcull::frontend {

// How --backend gl rasterizes the stochastic method: the fragment pipeline
// (MSAA passes of four samples, gl_SampleMask; docs/gl-backend.md, "Design")
// or the compute pipeline (setup, binning to screen tiles, a work group per
// tile; gl_compute_pipeline.hpp and docs/gl-backend.md, "The compute pipeline").
// Same samples, same decisions, same image.
enum class GlPipeline { fragment, compute };
inline const char* to_string(GlPipeline pipeline) {
    return pipeline == GlPipeline::compute ? "compute" : "fragment";
}
// "fragment" or "compute"; throws std::invalid_argument naming the valid ones.
inline GlPipeline parse_gl_pipeline(const std::string& name) {
    if (name == "fragment") return GlPipeline::fragment;
    if (name == "compute") return GlPipeline::compute;
    throw std::invalid_argument("unknown gl pipeline '" + name + "' (valid: fragment, compute)");
}

struct GlOptions {
    GlPipeline pipeline = GlPipeline::fragment;
    // Compute pipeline: entries the tile lists start with (0: what the
    // renderer last needed, at least 4 per triangle). A frame whose lists need
    // more is detected on the GPU and binned again with room for all (counter
    // tile_list_retries); a tiny value forces that path (the tests do).
    std::size_t tile_list_capacity = 0;
    // Compute pipeline: hierarchical occlusion per tile and shutter slice
    // (an entry's samples in a slice where its kernel depth floor is behind
    // every sample its tile holds are skipped; hidden in all, it is dropped).
    // The same image; fewer samples tested, and fewer counted in
    // samples_hit, as the cpu backend's CpuOptions::occlusion.
    bool occlusion = true;
    // Compute pipeline: triangles set up, binned and rasterized at a time
    // (0: 2^20; at most 4,194,240, and as many as a storage block holds of
    // their 464-byte records). The per-triangle buffers hold one batch, so
    // GPU memory is bounded whatever the scene's size (counter
    // gpu_buffer_bytes); the same image for any size.
    std::size_t triangle_batch = 0;
    // Compute pipeline: a moving or defocused triangle's samples tested only
    // inside the screen box of their shutter slice (BC_GL_TIME_STRATA of
    // them, the kernel's stratum_screen_box). The same image, fewer samples
    // tested.
    bool time_strata = true;
    // Every triangle through the moving path (per-sample kernel test), even
    // static in-focus ones: to measure what the static path saves.
    bool force_full_path = false;
    // Fill GlRenderer::render's sample_ids.
    bool keep_sample_ids = false;
    // Smallest side, in pixels, of the cells a moving triangle's sample bounds
    // are computed for (each triangle gets at most 4 x 4 cells).
    int cell_pixels = 8;
    // Time each step of the passes (samples, static, moving, resolve; summed
    // over passes, added to ms_per_phase) with a glFinish after each: the
    // frame gets slightly slower, since the steps no longer overlap.
    bool time_steps = false;
    // Samples per pixel each static draw covers (a multiple of 4): 0 for as
    // many as fit (the whole frame unless pixels x spp exceeds 4M), 4 for a
    // draw per pass of four samples. The image is the same either way.
    int static_group_samples = 0;
};

// Sample j of pixel (px, py) is at sample_ids[(py * width + px) * spp + j]:
// the index of the triangle it shows, or no_triangle for the background.
constexpr std::uint32_t no_triangle = 0xffffffffu;

// A headless context with the backend's programs compiled; renders any number
// of frames. Throws gl::GlError (a std::runtime_error) when no context can be
// made or a shader does not compile.
class GlRenderer {
public:
    GlRenderer();
    // On a given context (made current here and by render(); its objects are
    // deleted on it), e.g. HeadlessContext::from_current for a window's:
    // render() leaves its program, vertex array and texture bound and the
    // viewport, depth test, depth clamp and clip control changed (the caller
    // resets what it needs).
    explicit GlRenderer(gl::HeadlessContext&& context);
    GlRenderer(GlRenderer&&) noexcept;
    GlRenderer& operator=(GlRenderer&&) noexcept;
    ~GlRenderer();

    // settings.method stochastic renders as described above (options.pipeline
    // compute: the compute pipeline, which refuses other methods); interleave,
    // interval and accum as the CPU renderers of render/cpu/methods.hpp
    // (gl_sampling_methods.hpp; their sample_ids are in that layout, spp per pixel).
    // Throws std::invalid_argument for bad settings, SceneError for a bad
    // scene, gl::GlError when the image does not fit the context's limits.
    RenderResult render(const Scene& scene, const RenderSettings& settings, const GlOptions& options = {},
                        std::vector<std::uint32_t>* sample_ids = nullptr);

    // E.g. "egl_surfaceless, llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
    std::string description() const;
    // The context it renders on: other passes may share it (GlDofSecondary's
    // layer and trace passes), making it current before they run.
    const gl::HeadlessContext& context() const;

    struct State;

private:
    std::unique_ptr<State> state_;
};

// One frame, like render_cpu: a context and programs are made for the call
// (their compile time is the "compile" phase of ms_per_phase, included in
// ms_total), then render_gl_frame. settings.threads is used only by the host
// side of the interleave / interval / accum methods (their per-pass boxes).
RenderResult render_gl(const Scene& scene, const RenderSettings& settings, const GlOptions& options = {});

// One frame on `renderer`, as render_gl: the request checked, a 1x1 warm-up
// frame (llvmpipe compiles a program's code on its first draw, so that
// "raster+resolve" is the frame alone), then the frame. The "compile" phase
// of ms_per_phase is `made_ms` (what making the renderer took, when the
// caller just made it for this frame) plus the warm-up; ms_total includes it.
RenderResult render_gl_frame(GlRenderer& renderer, const Scene& scene, const RenderSettings& settings,
                             const GlOptions& options = {}, double made_ms = 0.0);

// A headless OpenGL 4.5 context that runs on hardware (its GL_RENDERER is
// not Mesa's llvmpipe, softpipe or swrast), for the caller to render on; null
// when there is none, and then `reason` (when given) says why. No context is
// made where the machine has no GPU device. `blurcull render --backend auto`
// renders on it (one context: the probe's).
std::unique_ptr<gl::HeadlessContext> hardware_gl_context(std::string* reason = nullptr);

}  // namespace blurcull::frontend
