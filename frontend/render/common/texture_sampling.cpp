#include "render/common/texture_sampling.hpp"

#include "render/common/surface_shared.h"

namespace blurcull::frontend {

const std::array<float, 256>& srgb_decode_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int code = 0; code < 256; ++code) t[static_cast<std::size_t>(code)] = surface::bc_srgb_to_linear(static_cast<float>(code) / 255.0f);
        return t;
    }();
    return table;
}

glm::vec4 decode_texel(const Texture& texture, int x, int y) {
    const std::uint32_t texel =
        texture.texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(texture.width) + static_cast<std::size_t>(x)];
    const std::array<float, 256>& table = srgb_decode_table();
    return glm::vec4(table[texel & 0xffu], table[(texel >> 8) & 0xffu], table[(texel >> 16) & 0xffu],
                     static_cast<float>(texel >> 24) / 255.0f);
}

glm::vec4 sample_texture(const Texture& texture, glm::vec2 uv) {
    return surface::bc_sample_texture(texture, texture.width, texture.height, static_cast<int>(texture.wrap_s),
                                      static_cast<int>(texture.wrap_t), uv);
}

}  // namespace blurcull::frontend

namespace blurcull::frontend::surface {

vec4 bc_texel(BC_TEXTURE_IN tex, int x, int y) { return decode_texel(tex, x, y); }

}  // namespace blurcull::frontend::surface
