// Static path: triangles that neither move nor defocus. One invocation per
// sample (gl_SampleID; llvmpipe shades a shader that writes gl_SampleMask per
// sample anyway): sample pass_base + gl_SampleID of the pattern
// (render_samples.comp), bc_sample_test() (the screen box, then bc_covers(),
// which for such a triangle is three edge functions). No cells, no hull, no lens/time bounds.
// The exact depth goes to gl_FragDepth (near / w), as on the moving path.
layout(std430, binding = BC_GL_INFOS_BINDING) readonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = BC_GL_COUNTERS_BINDING) buffer Counters { uint tested; uint hit; };
PASS_SAMPLE_BUFFERS

flat in int g_index;
layout(location = 0) out uint out_id;

void main() {
    uint j = pass_base + uint(gl_SampleID);
    if (j >= spp) discard;
    uvec2 pixel = fragment_cell(gl_FragCoord.xy, image_size);
    uint slot = (pixel.y * uint(image_size.x) + pixel.x) * 4u + uint(gl_SampleID);
    vec4 ndc_lens = pass_ndc_lens[slot];
    ScreenBound b;
    b.empty = false;
    b.lo = infos[g_index].box.xy;
    b.hi = infos[g_index].box.zw;
    b.hull_count = 0;
    float depth;
    int verdict = bc_sample_test(triangles[g_index], b, true, bc_no_sample_bounds(), ndc_lens.xy, ndc_lens.zw,
                                 pass_time[slot], near_plane, depth);
    if (verdict == BC_SAMPLE_CULLED) discard;
    atomicAdd(tested, 1u);
    if (verdict != BC_SAMPLE_COVERED) discard;
    if (!mask_keeps(g_index, ndc_lens.xy, ndc_lens.zw, pass_time[slot])) discard;  // alphaMode MASK, before the depth test
    atomicAdd(hit, 1u);
    gl_FragDepth = bc_depth_key(near_plane, depth);
    gl_SampleMask[0] = 1 << gl_SampleID;
    out_id = uint(g_index);
}
