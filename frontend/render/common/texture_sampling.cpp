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
    const glm::vec2 ax = surface::bc_bilinear_axis(uv.x, texture.width);
    const glm::vec2 ay = surface::bc_bilinear_axis(uv.y, texture.height);
    const int wrap_s = static_cast<int>(texture.wrap_s), wrap_t = static_cast<int>(texture.wrap_t);
    const int left = static_cast<int>(ax.x), top = static_cast<int>(ay.x);
    const int x0 = surface::bc_wrap_texel(left, texture.width, wrap_s);
    const int x1 = surface::bc_wrap_texel(left + 1, texture.width, wrap_s);
    const int y0 = surface::bc_wrap_texel(top, texture.height, wrap_t);
    const int y1 = surface::bc_wrap_texel(top + 1, texture.height, wrap_t);
    return surface::bc_bilinear_mix(decode_texel(texture, x0, y0), decode_texel(texture, x1, y0),
                                    decode_texel(texture, x0, y1), decode_texel(texture, x1, y1), ax.y, ay.y);
}

}  // namespace blurcull::frontend
