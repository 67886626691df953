// alphaMode MASK and BLEND in the raster decision (docs/reference-renderer.md,
// "Shading"): compiled after surface_shared.h and before the mains that draw
// triangles (render_static.frag, render_static_group.frag, render_moving.frag,
// render_method.frag). A covered sample of a masked triangle stays covered
// only where hit_alpha >= alphaCutoff, one of a BLEND triangle with
// probability hit_alpha (by the hash of the sample and the triangle): the
// host's SurfaceShader::sample_kept with the formulas of surface_shared.h
// (bc_alpha_test), at the barycentrics of the kernel's bc_covers_hit (float,
// the triangle the sample was tested against).
layout(std430, binding = BC_GL_MASK_SLOTS_BINDING) readonly buffer MaskSlots { int mask_slot[]; };
layout(std430, binding = BC_GL_MASK_TRIANGLES_BINDING) readonly buffer MaskTriangles { MaskTriangle mask_triangles[]; };
layout(std430, binding = BC_GL_MASK_TEXELS_BINDING) readonly buffer MaskTexels {
    float alpha_of_code[BC_GL_ALPHA_CODES];
    uint alpha_words[];
};

// surface_shared.h's texel fetch for the mask: only alpha is uploaded, so
// the colour channels read 0. texture = MaskTriangle.texture.
vec4 bc_texel(ivec4 tex, int x, int y) {
    int byte_index = tex.x + y * tex.y + x;
    uint code = (alpha_words[byte_index >> 2] >> (8u * uint(byte_index & 3))) & 0xffu;
    return vec4(0.0, 0.0, 0.0, alpha_of_code[code]);
}

// Whether sample (ndc, lens, time), which bc_sample_test found covered by
// scene triangle `triangle` (at triangles[local]: the compute pipeline's
// batches hold a part of the scene), stays covered: always for an opaque
// triangle.
bool mask_keeps_batch(int triangle, int local, vec2 ndc, vec2 lens, float time) {
    int slot = mask_slot[triangle];
    if (slot < 0) return true;
    MaskTriangle m = mask_triangles[slot];
    float depth;
    vec3 b;
    if (!bc_covers_hit(triangles[local], ndc, lens, time, near_plane, depth, b)) b = vec3(1.0 / 3.0);
    int flags = m.wrap_flags.z;
    float vertex_alpha = 1.0;
    if ((flags & BC_GL_MASK_HAS_COLOR) != 0) {
        vertex_alpha = bc_interpolate(b, vec4(m.vertex_alpha.x), vec4(m.vertex_alpha.y), vec4(m.vertex_alpha.z)).x;
    }
    float texture_alpha = 1.0;
    if (m.texture.x >= 0) {
        vec2 uv = vec2(0.0);
        if ((flags & BC_GL_MASK_HAS_TEXCOORD) != 0) {
            uv = bc_interpolate(b, vec4(m.uv01.xy, 0.0, 0.0), vec4(m.uv01.zw, 0.0, 0.0), vec4(m.uv2_alpha.xy, 0.0, 0.0)).xy;
        }
        texture_alpha = bc_transformed_texture(m.texture, m.texture.y, m.texture.z, m.wrap_flags.x, m.wrap_flags.y,
                                               m.transform_row0.xyz, m.transform_row1.xyz, uv).w;
    }
    return bc_alpha_test(bc_hit_alpha(m.uv2_alpha.z, vertex_alpha, texture_alpha), m.uv2_alpha.w,
                         (flags & BC_GL_MASK_BLEND) != 0, uint(triangle), ndc, time);
}

// The same where triangles[] holds the whole scene (every pass but the
// compute pipeline's raster).
bool mask_keeps(int triangle, vec2 ndc, vec2 lens, float time) {
    return mask_keeps_batch(triangle, triangle, ndc, lens, time);
}
