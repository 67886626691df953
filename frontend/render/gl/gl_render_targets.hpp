// What the GL stochastic path (gl_backend.cpp) and the GL interleave /
// interval / accum passes (gl_sampling_methods.cpp) share: the
// triangle-id + depth framebuffer with blurcull's depth rule, its size check,
// and the tested/hit sample counters.
#pragma once

#include "render/common/render_types.hpp"
#include "render/gl/gl_context.hpp"


namespace blurcull::frontend {

// glGetIntegerv of one value.
int get_integer(const gl::Functions& gl, GLenum name);

// Throws gl::GlError when a target_width x target_height framebuffer exceeds
// the context's texture or framebuffer size limits; the message names the
// image, width x height, that it is for.
void require_target_fits(const gl::Functions& gl, int target_width, int target_height, int width, int height);

// An R32UI triangle-id colour attachment and a DEPTH_COMPONENT32F depth
// attachment of width x height, 2D or (samples > 0) multisample, in one
// framebuffer. Throws gl::GlError naming `what` when it is incomplete.
class IdDepthTarget {
public:
    IdDepthTarget(const gl::Functions& gl, int width, int height, int samples, const char* what);
    GLuint id_texture() const { return id_texture_.id(); }

    // Binds it as the draw target with the depth rule both paths test by:
    // depth is near / w written from covers() (larger is nearer, 0 empty), a
    // strict GREATER test so that ties keep the triangle drawn first (the
    // lower index), and depth clamping so that quads are never clipped by
    // depth.
    void bind_with_depth_rule() const;

private:
    const gl::Functions* gl_;
    int width_, height_;
    gl::Texture id_texture_;
    gl::Texture depth_texture_;
    gl::Framebuffer framebuffer_;
};

// SSBO counters of samples tested and samples hit: two 32-bit words the
// fragment shaders atomicAdd to, reset after each pass (so no pass
// overflows them), and after them a carry word each, which the compute
// pipeline's raster adds to where a frame's count wraps (BC_COUNTER_ADD in
// render_common.glsl); added to RenderStats in 64 bits. bind_base binds the
// buffer for a pass; the test of the carry writes words with preset.
class SampleCounters {
public:
    explicit SampleCounters(const gl::Functions& gl);
    void bind_base(GLuint index) const { buffer_.bind_base(index); }
    void add_to(RenderStats& stats);
    // Sets the four words (tested, hit, and their carries): for tests.
    void preset(const std::uint32_t (&words)[4]);

private:
    const gl::Functions* gl_;
    gl::Buffer buffer_;
};

}  // namespace blurcull::frontend
