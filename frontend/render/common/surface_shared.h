// The per-hit surface formulas of the shading contract (docs/reference-renderer.md,
// "Shading"): texture wrap and bilinear weights, the sRGB decode, the lights
// (directional, point and spot with their falloffs) and the lit or unlit
// colour, the texture fetch (transform, wrap, bilinear), the interpolation of
// vertex attributes and the alpha test (MASK's cutoff, BLEND's stochastic
// transparency), in float, in one operation order. Written in the C++/GLSL subset of optics_shared.h: the host resolve
// of every backend runs it in C++, the GL backend's alpha mask test
// (shaders/render_mask.glsl) runs the same text in GLSL.
//
// The texel fetch is the includer's: vec4 bc_texel(BC_TEXTURE_IN texture,
// int x, int y), the linear RGBA of an already wrapped texel. In C++ it is
// decode_texel of a Texture (texture_sampling.cpp); in GLSL BC_TEXTURE_IN is
// an ivec4 locating the texture in the includer's buffers, and the includer
// defines bc_texel after this header.
#ifndef BLURCULL_SURFACE_SHARED_H
#define BLURCULL_SURFACE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>

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
using uint = std::uint32_t;
inline float pow(float a, float b) { return std::pow(a, b); }
// GLSL's floatBitsToUint.
inline uint floatBitsToUint(float value) {
    uint bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}
#define BC_SURFACE_FN inline
}  // namespace blurcull::frontend::surface
namespace blurcull::frontend {
struct Texture;
}
namespace blurcull::frontend::surface {
#define BC_TEXTURE_IN const ::blurcull::frontend::Texture&
// texture_sampling.cpp: decode_texel.
vec4 bc_texel(BC_TEXTURE_IN tex, int x, int y);
#else
#define BC_SURFACE_FN
#define BC_TEXTURE_IN ivec4
vec4 bc_texel(BC_TEXTURE_IN tex, int x, int y);  // the includer's (render_mask.glsl)
#endif

// TextureWrap (scene.hpp) as ints.
#define BC_WRAP_REPEAT 0
#define BC_WRAP_CLAMP 1
#define BC_WRAP_MIRROR 2

// Texel coordinates are kept within +-2^24 texels (where float still holds
// integers); a NaN coordinate reads texel 0. The loader warns of texture
// coordinates that far out (docs/reference-renderer.md, "Shading").
#define BC_TEXEL_LIMIT 16777216.0

// i mod n in [0, n) for any int i and n > 0, with % of non-negative
// operands only (GLSL leaves % of a negative operand undefined): for i < 0,
// i mod n = n - 1 - ((-1 - i) mod n).
BC_SURFACE_FN int bc_floor_mod(int i, int n) {
    return i >= 0 ? i % n : n - 1 - (-1 - i) % n;
}

// Integer texel i (any int) folded into [0, n) by wrap mode `mode`.
BC_SURFACE_FN int bc_wrap_texel(int i, int n, int mode) {
    if (mode == BC_WRAP_CLAMP) return clamp(i, 0, n - 1);
    if (mode == BC_WRAP_MIRROR) {
        int period = 2 * n;
        int m = bc_floor_mod(i, period);
        return m < n ? m : period - 1 - m;
    }
    return bc_floor_mod(i, n);
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

// The texture's linear RGBA at texture coordinate uv (glTF convention: (0, 0)
// the top-left corner of the image), bilinearly filtered between the four
// texels around it, each wrapped by wrap_s / wrap_t (BC_WRAP_*) and fetched
// with bc_texel; texture is width x height texels.
BC_SURFACE_FN vec4 bc_sample_texture(BC_TEXTURE_IN tex, int width, int height, int wrap_s, int wrap_t, vec2 uv) {
    vec2 ax = bc_bilinear_axis(uv.x, width);
    vec2 ay = bc_bilinear_axis(uv.y, height);
    int left = int(ax.x);
    int top = int(ay.x);
    int x0 = bc_wrap_texel(left, width, wrap_s);
    int x1 = bc_wrap_texel(left + 1, width, wrap_s);
    int y0 = bc_wrap_texel(top, height, wrap_t);
    int y1 = bc_wrap_texel(top + 1, height, wrap_t);
    return bc_bilinear_mix(bc_texel(tex, x0, y0), bc_texel(tex, x1, y0), bc_texel(tex, x0, y1),
                           bc_texel(tex, x1, y1), ax.y, ay.y);
}

// bc_sample_texture at the texture coordinates uv after the texture's
// transform (rows row0, row1 of its 3x3; KHR_texture_transform).
BC_SURFACE_FN vec4 bc_transformed_texture(BC_TEXTURE_IN tex, int width, int height, int wrap_s, int wrap_t,
                                          vec3 row0, vec3 row1, vec2 uv) {
    return bc_sample_texture(tex, width, height, wrap_s, wrap_t, bc_transform_uv(row0, row1, uv));
}

// A vertex attribute at barycentric coordinates b (weights of vertices 0, 1,
// 2); narrower attributes go through it padded, each component alike.
BC_SURFACE_FN vec4 bc_interpolate(vec3 b, vec4 a0, vec4 a1, vec4 a2) {
    return b.x * a0 + b.y * a1 + b.z * a2;
}

// The alpha of a hit: baseColorFactor's alpha x COLOR_0's alpha x the base
// colour texture's alpha (1 for a part the triangle does not have).
BC_SURFACE_FN float bc_hit_alpha(float base_alpha, float vertex_alpha, float texture_alpha) {
    return base_alpha * vertex_alpha * texture_alpha;
}

// alphaMode MASK: whether a covered sample of alpha `alpha` stays covered.
BC_SURFACE_FN bool bc_alpha_kept(float alpha, float cutoff) {
    return alpha >= cutoff;
}

// alphaMode BLEND as stochastic transparency (Enderton et al., I3D 2010): a
// covered sample stays covered with probability alpha, decided by a hash of
// the sample (its ndc and time, the floats every backend tests it at) and the
// triangle, so that every backend keeps the same samples and the depth rule
// then picks the nearest kept one. uint32 arithmetic only: host and GPU hash
// alike bit for bit. The lens position is left out: for a pinhole camera the
// CPU and Embree backends skip drawing it (0, 0) where the GL backend draws
// it, and a frame's samples differ in ndc and time already.

// lowbias32 (C. Wellons, hash-prospector): a bijective 32-bit mixer.
BC_SURFACE_FN uint bc_mix32(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// A float's bits with -0 read as +0 (a compare, which no compiler folds away).
BC_SURFACE_FN uint bc_sample_bits(float value) {
    return value == 0.0f ? 0u : floatBitsToUint(value);
}

// The hash of (sample, triangle) that decides a BLEND sample.
BC_SURFACE_FN uint bc_blend_hash(uint triangle, vec2 ndc, float time) {
    uint h = bc_mix32(triangle ^ 0x9e3779b9u);
    h = bc_mix32(h ^ bc_sample_bits(ndc.x));
    h = bc_mix32(h ^ bc_sample_bits(ndc.y));
    return bc_mix32(h ^ bc_sample_bits(time));
}

// alphaMode BLEND: whether a covered sample of alpha `alpha` stays covered,
// for `hash` = bc_blend_hash: its top 24 bits as a uniform value in [0, 1)
// (exact in float), below alpha. Alpha 1 keeps every sample, 0 none.
BC_SURFACE_FN bool bc_blend_kept(float alpha, uint hash) {
    return float(hash >> 8u) * (1.0f / 16777216.0f) < alpha;
}

// The raster decision of an alpha-tested triangle (MASK, or BLEND where
// `blend`) for a covered sample (ndc, time) of alpha `alpha`.
BC_SURFACE_FN bool bc_alpha_test(float alpha, float cutoff, bool blend, uint triangle, vec2 ndc, float time) {
    if (blend) return bc_blend_kept(alpha, bc_blend_hash(triangle, ndc, time));
    return bc_alpha_kept(alpha, cutoff);
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

// Light types (LightType, scene.hpp) as ints: the scene's own directional
// light and KHR_lights_punctual's (Scene::lights).
#define BC_LIGHT_DIRECTIONAL 0
#define BC_LIGHT_POINT 1
#define BC_LIGHT_SPOT 2

// The distance falloff of a point or spot light at squared distance
// distance_squared: the inverse square, windowed to 0 at `range` as the
// KHR_lights_punctual README recommends, max(min(1 - (d / range)^4, 1), 0) / d^2;
// range <= 0 (undefined in the file): the inverse square alone. 0 at d = 0.
BC_SURFACE_FN float bc_range_attenuation(float distance_squared, float range) {
    if (!(distance_squared > 0.0f)) return 0.0f;
    float falloff = 1.0f / distance_squared;
    if (range <= 0.0f) return falloff;
    float ratio_squared = distance_squared / (range * range);
    return max(min(1.0f - ratio_squared * ratio_squared, 1.0f), 0.0f) * falloff;
}

// A spot light's smooth falloff between its cones (the README's sample):
// t = clamp((cos_angle - cos_outer) / (cos_inner - cos_outer), 0, 1), then t^2,
// cos_angle the cosine between the spot's axis and the direction from the
// light to the point; the cones' gap at least 0.001 in cosine.
BC_SURFACE_FN float bc_spot_attenuation(float cos_angle, float cos_inner, float cos_outer) {
    float scale = 1.0f / max(0.001f, cos_inner - cos_outer);
    float t = clamp((cos_angle - cos_outer) * scale, 0.0f, 1.0f);
    return t * t;
}

// The diffuse light a punctual light of type `type` (BC_LIGHT_*) gives a
// point `p` with normal `normal` (two-sided, bc_lambert): `colour` (colour x
// intensity) x the cosine x the falloffs, x the diffuse weight. `position`:
// the light's (point, spot); `direction`: where it shines (spot), towards the
// light (directional).
BC_SURFACE_FN vec3 bc_punctual_light(int type, vec3 position, vec3 direction, vec3 colour, float range,
                                     float cos_inner, float cos_outer, vec3 p, vec3 normal, float diffuse) {
    if (type == BC_LIGHT_DIRECTIONAL) return (diffuse * bc_lambert(normal, direction)) * colour;
    vec3 to_light = position - p;
    float distance_squared = dot(to_light, to_light);
    float attenuation = bc_range_attenuation(distance_squared, range);
    if (type == BC_LIGHT_SPOT && attenuation > 0.0f) {
        float axis_length = sqrt(dot(direction, direction));
        float cos_angle = axis_length > 0.0f ? -dot(to_light, direction) / (sqrt(distance_squared) * axis_length) : -1.0f;
        attenuation *= bc_spot_attenuation(cos_angle, cos_inner, cos_outer);
    }
    return (diffuse * bc_lambert(normal, to_light) * attenuation) * colour;
}

// The shaded colour of a hit whose lights (bc_punctual_light of each) sum to
// `light`: base colour lit by ambient plus that diffuse light, plus
// emission; KHR_materials_unlit: the base colour as it is.
BC_SURFACE_FN vec3 bc_material_colour(bool unlit, vec3 base, vec3 light, vec3 emissive, float ambient) {
    if (unlit) return base;
    return base * (vec3(ambient) + light) + emissive;
}

#ifdef __cplusplus
}  // namespace blurcull::frontend::surface
#endif

#endif  // BLURCULL_SURFACE_SHARED_H
