#include "render/gl/gl_alpha_mask.hpp"

#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gpu_layout_shared.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace blurcull::frontend {

namespace gl_mask_detail {
// The three buffers' contents; each at least one entry (GL refuses empty buffers).
struct MaskData {
    std::vector<std::int32_t> slots;
    std::vector<gpu::MaskTriangle> triangles;
    std::vector<std::uint32_t> texels;  // BC_GL_ALPHA_CODES float bits, then the alpha bytes
    std::size_t alpha_bytes = 0;
    std::size_t masked = 0;
};
}  // namespace gl_mask_detail

namespace {

using gl_mask_detail::MaskData;

glm::vec2 texcoord_of(const Scene& scene, std::uint32_t vertex) {
    return scene.texcoord.empty() ? glm::vec2(0.0f) : scene.texcoord[vertex];
}

// Appends texture's alpha bytes (texel k at byte base + k, four per word).
std::int32_t append_alpha(const Texture& texture, MaskData& data) {
    const std::size_t base = data.alpha_bytes;
    const std::size_t count = texture.texels.size();
    data.alpha_bytes += count;
    data.texels.resize(BC_GL_ALPHA_CODES + (data.alpha_bytes + 3) / 4, 0u);
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t byte = base + k;
        data.texels[BC_GL_ALPHA_CODES + byte / 4] |= (texture.texels[k] >> 24) << (8 * (byte % 4));
    }
    return static_cast<std::int32_t>(base);
}

gpu::MaskTriangle mask_triangle(const Scene& scene, std::size_t t, std::map<int, std::int32_t>& uploaded,
                                MaskData& data) {
    const Material& material = scene.materials[scene.triangle_material[t]];
    const glm::uvec3& tri = scene.triangles[t];
    gpu::MaskTriangle m{};
    const glm::vec2 uv0 = texcoord_of(scene, tri.x), uv1 = texcoord_of(scene, tri.y), uv2 = texcoord_of(scene, tri.z);
    m.uv01 = glm::vec4(uv0, uv1);
    m.uv2_alpha = glm::vec4(uv2, material.base_alpha, material.alpha_cutoff);
    int flags = scene.texcoord.empty() ? 0 : BC_GL_MASK_HAS_TEXCOORD;
    if (material.alpha_mode == AlphaMode::blend) flags |= BC_GL_MASK_BLEND;
    if (!scene.vertex_color.empty()) {
        flags |= BC_GL_MASK_HAS_COLOR;
        m.vertex_alpha = glm::vec4(scene.vertex_color[tri.x].w, scene.vertex_color[tri.y].w,
                                   scene.vertex_color[tri.z].w, 0.0f);
    }
    const TextureRef& ref = material.base_color_texture;
    m.texture = glm::ivec4(-1, 0, 0, 0);
    if (ref.texture >= 0) {
        const Texture& texture = scene.textures[static_cast<std::size_t>(ref.texture)];
        auto found = uploaded.find(ref.texture);
        if (found == uploaded.end()) found = uploaded.emplace(ref.texture, append_alpha(texture, data)).first;
        m.texture = glm::ivec4(found->second, texture.width, texture.height, 0);
        // glm::mat3 is column-major: row r is (m[0][r], m[1][r], m[2][r]) (surface_shading.cpp).
        const glm::mat3& x = ref.transform;
        m.transform_row0 = glm::vec4(x[0][0], x[1][0], x[2][0], 0.0f);
        m.transform_row1 = glm::vec4(x[0][1], x[1][1], x[2][1], 0.0f);
        m.wrap_flags = glm::ivec4(static_cast<int>(texture.wrap_s), static_cast<int>(texture.wrap_t), 0, 0);
    }
    m.wrap_flags.z = flags;
    return m;
}

MaskData mask_data(const Scene& scene) {
    MaskData data;
    data.slots.assign(std::max<std::size_t>(scene.triangles.size(), 1), -1);
    data.texels.resize(BC_GL_ALPHA_CODES);
    for (std::uint32_t code = 0; code < BC_GL_ALPHA_CODES; ++code) {
        // The host's decode_texel: alpha = code / 255.
        const float alpha = static_cast<float>(code) / 255.0f;
        std::memcpy(&data.texels[code], &alpha, sizeof alpha);
    }
    std::map<int, std::int32_t> uploaded;  // texture -> its first alpha byte
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        if (scene.materials[scene.triangle_material[t]].alpha_mode == AlphaMode::opaque) continue;
        data.slots[t] = static_cast<std::int32_t>(data.triangles.size());
        data.triangles.push_back(mask_triangle(scene, t, uploaded, data));
    }
    data.masked = data.triangles.size();
    if (data.triangles.empty()) data.triangles.emplace_back();
    return data;
}

template <class T>
gl::Buffer upload(const gl::Functions& gl, const std::vector<T>& values) {
    return gl::Buffer(gl, GL_SHADER_STORAGE_BUFFER, values.size() * sizeof(T), values.data());
}

MaskData checked_mask_data(const gl::Functions& gl, const Scene& scene) {
    MaskData data = mask_data(scene);
    const auto limit = static_cast<std::size_t>(get_integer(gl, GL_MAX_SHADER_STORAGE_BLOCK_SIZE));
    if (data.texels.size() * sizeof(std::uint32_t) > limit) {
        throw gl::GlError("gl: the alpha-masked textures' " + std::to_string(data.alpha_bytes) +
                          " alpha bytes exceed the context's storage block limit of " + std::to_string(limit) +
                          " bytes");
    }
    return data;
}

}  // namespace

GlAlphaMask::GlAlphaMask(const gl::Functions& gl, const Scene& scene)
    : GlAlphaMask(gl, checked_mask_data(gl, scene)) {}

GlAlphaMask::GlAlphaMask(const gl::Functions& gl, const MaskData& data)
    : masked_(data.masked), slots_(upload(gl, data.slots)), triangles_(upload(gl, data.triangles)),
      texels_(upload(gl, data.texels)) {}

void GlAlphaMask::bind() const {
    slots_.bind_base(BC_GL_MASK_SLOTS_BINDING);
    triangles_.bind_base(BC_GL_MASK_TRIANGLES_BINDING);
    texels_.bind_base(BC_GL_MASK_TEXELS_BINDING);
}

}  // namespace blurcull::frontend
