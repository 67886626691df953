// The GL backend's alphaMode MASK test (shaders/render_mask.glsl): the
// buffers it reads, made from the scene once per frame, and the stages whose
// mains call it. docs/gl-backend.md, "Alpha mask".
#pragma once

#include "render/gl/gl_context.hpp"
#include "scene/scene.hpp"

#include <cstddef>
#include <string_view>

namespace blurcull::frontend {

namespace gl_mask_detail {
struct MaskData;  // gl_alpha_mask.cpp: the buffers' contents
}

// A stage whose main calls mask_keeps: kernel_stage's pieces with
// surface_shared.h and render_mask.glsl before `main_name`. Throws
// gl::GlError when a shader was not embedded at build time.
gl::ShaderStage masked_kernel_stage(GLenum type, std::string_view main_name);

// The MaskSlots, MaskTriangles and MaskTexels buffers (gpu_layout_shared.h)
// of a scene: every triangle's slot (-1 unless alphaMode MASK), the masked
// triangles' texture coordinates, COLOR_0 alphas, factors and texture, and
// the alpha bytes of their base colour textures. Throws gl::GlError when
// those bytes exceed the context's largest storage block.
class GlAlphaMask {
public:
    GlAlphaMask(const gl::Functions& gl, const Scene& scene);

    // Binds the buffers at BC_GL_MASK_*_BINDING.
    void bind() const;
    // Triangles whose material is alphaMode MASK.
    std::size_t masked_triangles() const { return masked_; }

private:
    GlAlphaMask(const gl::Functions& gl, const gl_mask_detail::MaskData& data);

    std::size_t masked_ = 0;
    gl::Buffer slots_, triangles_, texels_;
};

}  // namespace blurcull::frontend
