// What the GL backend's two stochastic pipelines share on the host
// (gl_backend.cpp: the fragment pipeline; gl_compute_pipeline.cpp: the
// compute pipeline): the uniforms of render_common.glsl, storage buffers, the
// frame's float triangles and draw lists, the colours, and the readback of
// render_resolve.comp's sums. docs/gl-backend.md.
#pragma once

#include "render/common/camera_model.hpp"
#include "render/common/render_types.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "scene/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace blurcull::frontend {

void set_int(const gl::Functions& gl, const gl::Program& program, const char* name, int value);
void set_uint(const gl::Functions& gl, const gl::Program& program, const char* name, std::uint32_t value);
void set_float(const gl::Functions& gl, const gl::Program& program, const char* name, float value);

// Uses `program` and sets the uniforms of render_common.glsl (and `sampler`
// where the stage declares it).
void set_common(const gl::Functions& gl, const gl::Program& program, const CameraModel& model,
                const RenderSettings& settings, std::uint32_t pass_base);

// A shader storage buffer of `bytes` bytes, or holding `data`.
gl::Buffer storage_buffer(const gl::Functions& gl, std::size_t bytes);
template <class T>
gl::Buffer storage_buffer(const gl::Functions& gl, const std::vector<T>& data) {
    return gl::Buffer(gl, GL_SHADER_STORAGE_BUFFER, data.size() * sizeof(T), data.data());
}

// The frame's triangles as the shaders see them, and each path's draw list.
struct FrameTriangles {
    // make_moving_triangle<float> of each, as the kernel's GLSL sees them; at
    // least one entry (GL refuses empty buffers).
    std::vector<gpu::GpuMovingTriangle> gpu;
    std::vector<std::int32_t> classes;  // classify() of each (BC_INVALID in the padding)
    // The triangles each path draws, in index order: static_count and
    // moving_count entries, padded to one when empty (GL refuses empty
    // buffers; drawn with count 0).
    std::vector<std::uint32_t> static_list, moving_list;
    std::size_t static_count = 0, moving_count = 0;
};

// classify() here, on the float triangle the GLSL sees (kernel<float> and its
// GLSL twin are bit-identical), so each path draws a list of only its own
// triangles, in index order. With `first` and `count`: the scene's triangles
// first ... first + count - 1 only (the compute pipeline's batches), at
// entries 0 ... count - 1 of gpu and classes; the lists hold scene indices.
// On `threads` threads (render_threads: the settings' --threads); the same
// result on any number.
FrameTriangles frame_triangles(const Scene& scene, const CameraModel& model, bool force_full_path, int threads);
FrameTriangles frame_triangles(const Scene& scene, const CameraModel& model, bool force_full_path,
                               std::size_t first, std::size_t count, int threads);

// Each triangle's flat colour (`flat`: SurfaceShader::flat_colours, the
// render's shade_all), then the scene's background (index = triangle count).
std::vector<glm::vec4> frame_colours(const std::vector<glm::vec3>& flat, const Scene& scene);

// The image from render_resolve.comp's per-pixel sums (rgb, hit count),
// divided by spp as the CPU backend resolves (resolve_box, resolve_coverage).
Image image_from_sums(const gl::Buffer& sums, const RenderSettings& settings);

}  // namespace blurcull::frontend
