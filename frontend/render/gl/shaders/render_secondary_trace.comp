// dof-secondary's image-space tracing step on the GPU (docs/secondary-rays.md,
// "The renderer"): one invocation per bounced ray, its segment already
// clipped (frustum, min/max pyramid, lens part: on the host, or by
// render_secondary_clip.comp), stepped through the cluster's layered depth
// images with the kernel's layer_trace_begin / layer_trace_step: the loop of
// include/blurcull/layer_trace.hpp, reading this shader's buffer. Same
// emitted text as the host, so the same hits. With pick_surface, the hit's
// surface is picked from the layers' triangles as the host's hit_triangle
// does (bounce_shared.h), so only it need come back: two words per ray at
// ray hit_offset + r of a render's bounce (the clusters' hits side by side,
// read back once), or with the rays gathered at the batch's ray index.
layout(local_size_x = BC_TRACE_GROUP) in;
layout(std430, binding = BC_GL_TRACE_DEPTHS_BINDING) readonly buffer Depths { float depth_in[]; };  // layer, y, x
layout(std430, binding = BC_GL_TRACE_HITS_BINDING) writeonly buffer Hits { uint hit_out[]; };     // 8 per ray, or 2 with pick_surface
layout(std430, binding = BC_GL_TRACE_TRIANGLE_IDS_BINDING) readonly buffer TriangleIds { uint triangle_in[]; };  // layer, y, x
uniform uint count;
uniform int pick_surface;  // 1: the surface's triangle picked (TriangleIds bound), the hit in two words
uniform uint hit_offset;   // with pick_surface: ray r's hit at hit_offset + r,
uniform int hits_by_index; // or with this at ray_index[r] (the batch's ray it is)
layout(std430, binding = BC_GL_GATHER_INDICES_BINDING) readonly buffer Indices { uint ray_index[]; };

// The triangle stored at (layer, x, y); none (the k-buffer's ~0) reads as 0, the host's default.
uint stored_triangle(int plane, int size, int layer, int x, int y) {
    uint id = triangle_in[layer * plane + y * size + x];
    return id == 0xFFFFFFFFu ? 0u : id;
}

// The host's hit_triangle (dof_secondary.cpp): the nearest in depth of the
// 3 x 3 texels of the hit's layer around it, its own texel on ties.
uint hit_surface(LayerView v, LayerHit h) {
    int plane = v.size * v.size;
    int hx = bc_hit_texel(h.image.x, v.size);
    int hy = bc_hit_texel(h.image.y, v.size);
    float best = uintBitsToFloat(0x7F800000u);
    uint triangle = stored_triangle(plane, v.size, h.layer, hx, hy);
    for (int y = max(0, hy - 1); y <= min(v.size - 1, hy + 1); ++y) {
        for (int x = max(0, hx - 1); x <= min(v.size - 1, hx + 1); ++x) {
            precise float gap = abs(depth_in[h.layer * plane + y * v.size + x] - h.depth);
            if (bc_hit_surface_closer(gap, best, x == hx && y == hy)) {
                best = gap;
                triangle = stored_triangle(plane, v.size, h.layer, x, y);
            }
        }
    }
    return triangle;
}

void main() {
    uint r = dispatch_item();
    if (r >= count) return;
    LayerView v = trace_view();
    int layers = trace_layer_count();
    LayerSegment seg = load_segment(r);
    int plane = v.size * v.size;
    LayerTrace t = bc_layer_trace_begin(v, seg, layers, trace_thickness());
    for (int k = 0; k < t.steps; ++k) {
        if (t.done) break;
        float depths[BC_LAYERS_MAX];
        for (int l = 0; l < BC_LAYERS_MAX; ++l)
            depths[l] = l < t.layers ? depth_in[l * plane + t.y * v.size + t.x] : 0.0;
        t = bc_layer_trace_step(v, seg, t, depths);
    }
    LayerHit h = t.hit;
    if (pick_surface != 0) {
        uint at = 2u * (hits_by_index != 0 ? ray_index[r] : hit_offset + r);
        hit_out[at] = (uint(h.steps) << 1u) | (h.hit ? 1u : 0u);
        hit_out[at + 1u] = h.hit ? hit_surface(v, h) : 0u;
        return;
    }
    uint out_at = 8u * r;
    hit_out[out_at] = h.hit ? 1u : 0u;
    hit_out[out_at + 1u] = uint(h.layer + 1);
    hit_out[out_at + 2u] = uint(h.steps);
    hit_out[out_at + 3u] = floatBitsToUint(h.s);
    hit_out[out_at + 4u] = floatBitsToUint(h.depth);
    hit_out[out_at + 5u] = floatBitsToUint(h.image.x);
    hit_out[out_at + 6u] = floatBitsToUint(h.image.y);
    hit_out[out_at + 7u] = 0u;
}
