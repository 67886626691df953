// Static path, once per group of samples (usually the whole frame) instead of
// once per 4-sample pass: llvmpipe's cost is per primitive, so each static
// triangle is set up once and its fragment (one per pixel, no gl_SampleID)
// loops over the group's samples of the pixel (render_samples.comp, same
// values as the passes see). Per covered sample, the winner is what the
// per-pass draw in index order with the GREATER depth test kept
// (bc_depth_key_wins): the larger depth key bc_depth_key (near / w, clamped to
// [0, 1] as the depth buffer clamps gl_FragDepth), on equal keys the lower index. group_depths takes the
// largest key (atomicMax: positive floats order as their bits); a triangle
// below it has lost. Otherwise a compare-and-swap loop on group_ids against
// the current holder's key, recomputed (bc_covers() is deterministic): lock-free
// (a failed swap means another triangle progressed), and the holder only
// ever improves, so it ends as the nearest, lowest-index triangle.
layout(std430, binding = BC_GL_INFOS_BINDING) readonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = BC_GL_COUNTERS_BINDING) buffer Counters { uint tested; uint hit; };
GROUP_SAMPLE_BUFFERS
layout(std430, binding = BC_GL_GROUP_IDS_BINDING) buffer GroupIds { uint group_ids[]; };
layout(std430, binding = BC_GL_GROUP_DEPTHS_BINDING) buffer GroupDepths { uint group_depths[]; };

flat in int g_index;

void main() {
    uvec2 pixel = fragment_cell(gl_FragCoord.xy, image_size);
    // The rect holds every sample in the box: none outside it can be covered.
    ivec4 rect = infos[g_index].rect;
    if (int(pixel.x) < rect.x || int(pixel.x) > rect.z || int(pixel.y) < rect.y || int(pixel.y) > rect.w) return;
    uint first = (pixel.y * uint(image_size.x) + pixel.x) * group_samples;
    ScreenBound b;
    b.empty = false;
    b.lo = infos[g_index].box.xy;
    b.hi = infos[g_index].box.zw;
    b.hull_count = 0;
    uint tested_here = 0u, hit_here = 0u;
    for (uint k = 0u; k < group_samples; ++k) {
        if (pass_base + k >= spp) break;
        uint slot = first + k;
        vec4 ndc_lens = group_ndc_lens[slot];
        float depth;
        int verdict = bc_sample_test(triangles[g_index], b, true, bc_no_sample_bounds(), ndc_lens.xy, ndc_lens.zw,
                                     group_time[slot], near_plane, depth);
        if (verdict == BC_SAMPLE_CULLED) continue;
        ++tested_here;
        if (verdict != BC_SAMPLE_COVERED) continue;
        if (!mask_keeps(g_index, ndc_lens.xy, ndc_lens.zw, group_time[slot])) continue;  // alphaMode MASK
        ++hit_here;
        float key = bc_depth_key(near_plane, depth);
        if (!(key > 0.0)) continue;  // the depth test against the cleared 0 would drop it
        uint bits = floatBitsToUint(key);
        if (atomicMax(group_depths[slot], bits) > bits) continue;
        uint mine = uint(g_index);
        uint current = group_ids[slot];
        while (true) {
            if (current != 0xffffffffu) {
                float other = static_depth_key(int(current), slot);
                if (!bc_depth_key_wins(key, mine, other, current)) break;
            }
            uint seen = atomicCompSwap(group_ids[slot], current, mine);
            if (seen == current) break;
            current = seen;
        }
    }
    if (tested_here > 0u) atomicAdd(tested, tested_here);
    if (hit_here > 0u) atomicAdd(hit, hit_here);
}
