// Texture lookup of the shading contract (docs/reference-renderer.md,
// "Shading"): bilinear filtering of the four texels around a texture
// coordinate, each wrapped by the texture's modes and sRGB-decoded first.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>

namespace blurcull::frontend {

// The 256 linear values of the 8-bit sRGB codes (bc_srgb_to_linear of
// code / 255), computed once; the GL backend uploads the same table.
const std::array<float, 256>& srgb_decode_table();

// The texel (x, y), both already wrapped, as linear RGBA: colour channels
// sRGB-decoded, alpha code / 255.
glm::vec4 decode_texel(const Texture& texture, int x, int y);

// Linear RGBA of `texture` at texture coordinate uv (glTF convention: (0, 0)
// the top-left corner of the image), bilinearly filtered, wrapped by
// texture.wrap_s / wrap_t. The caller guarantees a valid texture (validate_scene);
// any uv is allowed (NaN reads texel 0, far coordinates are clamped).
glm::vec4 sample_texture(const Texture& texture, glm::vec2 uv);

}  // namespace blurcull::frontend
