// The GL backend's alphaMode MASK test (shaders/render_mask.glsl): the
// buffers it reads, made from the scene once per frame (the stages whose
// mains call it are built with gl::Prelude::render_masked, shader_stages.hpp).
// docs/gl-backend.md, "Alpha mask".
#pragma once

#include "render/gl/gl_context.hpp"
#include "scene/scene.hpp"

#include <cstddef>

namespace blurcull::frontend {

namespace gl_mask_detail {
struct MaskData;  // gl_alpha_mask.cpp: the buffers' contents
}

// The MaskSlots, MaskTriangles and MaskTexels buffers (gpu_layout_shared.h)
// of a scene: every triangle's slot (-1 unless alphaMode MASK or BLEND), the masked
// triangles' texture coordinates, COLOR_0 alphas, factors and texture, and
// the alpha bytes of their base colour textures. Throws gl::GlError when
// those bytes exceed the context's largest storage block.
class GlAlphaMask {
public:
    GlAlphaMask(const gl::Functions& gl, const Scene& scene);

    // Binds the buffers at BC_GL_MASK_*_BINDING.
    void bind() const;
    // Triangles whose material is alphaMode MASK or BLEND.
    std::size_t masked_triangles() const { return masked_; }
    // Their buffers' bytes (GPU memory).
    std::size_t buffer_bytes() const { return slots_.size() + triangles_.size() + texels_.size(); }

private:
    GlAlphaMask(const gl::Functions& gl, const gl_mask_detail::MaskData& data);

    std::size_t masked_ = 0;
    gl::Buffer slots_, triangles_, texels_;
};

}  // namespace blurcull::frontend
