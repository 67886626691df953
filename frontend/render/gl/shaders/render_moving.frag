// Moving path, one invocation per sample (gl_SampleID makes it run at sample
// rate): sample pass_base + gl_SampleID of the pattern (render_samples.comp), culled by the cell's
// bounds and the screen bound, then the exact bc_covers() (bc_sample_test); its depth goes to
// gl_FragDepth (near / w), so the depth test is per sample.
layout(std430, binding = BC_GL_INFOS_BINDING) readonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = BC_GL_COUNTERS_BINDING) buffer Counters { uint tested; uint hit; };
PASS_SAMPLE_BUFFERS

flat in int g_index;
flat in vec4 g_lens;
flat in vec4 g_time_lines_u_a;
flat in vec4 g_time_lines_u_b;
flat in vec4 g_time_lines_v_a;
flat in vec4 g_time_lines_v_b;
layout(location = 0) out uint out_id;

void main() {
    uint j = pass_base + uint(gl_SampleID);
    if (j >= spp) discard;
    uvec2 pixel = fragment_cell(gl_FragCoord.xy, image_size);
    uint slot = (pixel.y * uint(image_size.x) + pixel.x) * 4u + uint(gl_SampleID);
    vec4 ndc_lens = pass_ndc_lens[slot];
    PixelSample s;
    s.offset = vec2(0.0);
    s.lens = ndc_lens.zw;
    s.time = pass_time[slot];
    SampleBounds sb =
        carried_sample_bounds(g_lens, g_time_lines_u_a, g_time_lines_u_b, g_time_lines_v_a, g_time_lines_v_b);
    vec2 ndc = ndc_lens.xy;
    ScreenBound b;
    b.empty = false;
    b.lo = infos[g_index].box.xy;
    b.hi = infos[g_index].box.zw;
    b.hull_count = infos[g_index].hull_count;
    for (int k = 0; k < BC_HULL_MAX; ++k) {
        b.hull_edge[k] = k < b.hull_count ? infos[g_index].hull[k].xyz : vec3(0.0);
    }
    float depth;
    int verdict = bc_sample_test(triangles[g_index], b, true, sb, ndc, s.lens, s.time, near_plane, depth);
    if (verdict == BC_SAMPLE_CULLED) discard;
    atomicAdd(tested, 1u);
    if (verdict != BC_SAMPLE_COVERED) discard;
    if (!mask_keeps(g_index, ndc_lens.xy, ndc_lens.zw, pass_time[slot])) discard;  // alphaMode MASK, before the depth test
    atomicAdd(hit, 1u);
    gl_FragDepth = bc_depth_key(near_plane, depth);
    gl_SampleMask[0] = 1 << gl_SampleID;
    out_id = uint(g_index);
}
