// The per-hit surface formulas of the shading contract (docs/reference-renderer.md,
// "Shading"): texture wrap and bilinear weights, the sRGB decode, and the lit
// colour, in float, in one operation order. Written in the C++/GLSL subset of
// optics_shared.h so a GPU resolve can include it; today every backend,
// the GL one included, runs it on the host (the texel fetch is the caller's).
#ifndef BLURCULL_SURFACE_SHARED_H
#define BLURCULL_SURFACE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cmath>

namespace blurcull::frontend::surface {
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::ivec2;
using glm::clamp;
using glm::floor;
using glm::abs;
using glm::min;
using glm::max;
using glm::dot;
using glm::mix;
using glm::sqrt;
inline float pow(float a, float b) { return std::pow(a, b); }
#define BC_SURFACE_FN inline
#else
#define BC_SURFACE_FN
#endif

// TextureWrap (scene.hpp) as ints.
#define BC_WRAP_REPEAT 0
#define BC_WRAP_CLAMP 1
#define BC_WRAP_MIRROR 2

// Texel coordinates are kept within +-2^24 texels (where float still holds
// integers); a NaN coordinate reads texel 0. The loader warns of texture
// coordinates that far out (docs/reference-renderer.md, "Shading").
#define BC_TEXEL_LIMIT 16777216.0

// Integer texel i (any int) folded into [0, n) by wrap mode `mode`.
BC_SURFACE_FN int bc_wrap_texel(int i, int n, int mode) {
    if (mode == BC_WRAP_CLAMP) return clamp(i, 0, n - 1);
    if (mode == BC_WRAP_MIRROR) {
        int period = 2 * n;
        int m = i % period;
        if (m < 0) m = m + period;
        return m < n ? m : period - 1 - m;
    }
    int r = i % n;
    return r < 0 ? r + n : r;
}

// Bilinear filtering along one axis of n texels at texture coordinate c (0
// and 1 are the outer edges of the first and last texel): the left texel's
// index (before wrapping) and the right one's weight.
BC_SURFACE_FN vec2 bc_bilinear_axis(float c, int n) {
    float x = c * float(n) - 0.5f;
    if (!(x == x)) x = 0.0f;  // NaN
    x = clamp(x, -float(BC_TEXEL_LIMIT), float(BC_TEXEL_LIMIT));
    float left = floor(x);
    return vec2(left, x - left);
}

// The four decoded texels (t00 at (left, top), t10 right of it, t01 below,
// t11 diagonal) weighted by the fractions (fx, fy) of bc_bilinear_axis.
BC_SURFACE_FN vec4 bc_bilinear_mix(vec4 t00, vec4 t10, vec4 t01, vec4 t11, float fx, float fy) {
    vec4 top = t00 + (t10 - t00) * fx;
    vec4 bottom = t01 + (t11 - t01) * fx;
    return top + (bottom - top) * fy;
}

// The sRGB transfer function's inverse (IEC 61966-2-1) of an 8-bit value;
// the host tabulates it once (a GPU gets the table, so both decode alike).
BC_SURFACE_FN float bc_srgb_to_linear(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// Texture coordinates transform * (uv, 1) of a 3x3 (KHR_texture_transform).
BC_SURFACE_FN vec2 bc_transform_uv(vec3 row0, vec3 row1, vec2 uv) {
    return vec2(row0.x * uv.x + row0.y * uv.y + row0.z, row1.x * uv.x + row1.y * uv.y + row1.z);
}

// The diffuse term's cosine |n . l| / (|n| |l|) of a normal and the light
// direction (two-sided); 0 for a zero length or a product of lengths that
// is not finite (3.40282347e38 is FLT_MAX).
BC_SURFACE_FN float bc_lambert(vec3 normal, vec3 light) {
    float normal_length = sqrt(dot(normal, normal));
    float light_length = sqrt(dot(light, light));
    float product = normal_length * light_length;
    if (!(normal_length > 0.0f && light_length > 0.0f && product <= 3.40282347e38f)) return 0.0f;
    return min(abs(dot(normal, light)) / product, 1.0f);  // rounding can step past 1
}

// The shaded colour of a hit: base colour lit by ambient plus the diffuse
// term, plus emission.
BC_SURFACE_FN vec3 bc_lit_colour(vec3 base, float lambert, vec3 light_color, vec3 emissive, float ambient,
                                 float diffuse) {
    return base * (vec3(ambient) + (diffuse * lambert) * light_color) + emissive;
}

#ifdef __cplusplus
}  // namespace blurcull::frontend::surface
#endif

#endif  // BLURCULL_SURFACE_SHARED_H
