// dof-secondary's image-space tracing step on the GPU (docs/secondary-rays.md,
// "The renderer"): one invocation per bounced ray, its segment already
// clipped on the host (frustum, min/max pyramid, lens part), stepped through
// the cluster's layered depth images with the kernel's layer_trace_begin /
// layer_trace_step: the loop of include/blurcull/layer_trace.hpp, reading
// this shader's buffer. Same emitted text as the host, so the same hits.
layout(local_size_x = 64) in;
layout(std430, binding = BC_GL_TRACE_DEPTHS_BINDING) readonly buffer Depths { float depth_in[]; };      // layer, y, x
layout(std430, binding = BC_GL_TRACE_SEGMENTS_BINDING) readonly buffer Segments { float segment_in[]; };  // 10 floats per ray
layout(std430, binding = BC_GL_TRACE_VIEW_BINDING) readonly buffer View { float view_in[]; };         // eye, forward, right, up, tan, near, far, size, layers, thickness
layout(std430, binding = BC_GL_TRACE_HITS_BINDING) writeonly buffer Hits { uint hit_out[]; };         // 8 per ray
uniform uint count;

void main() {
    uint r = gl_GlobalInvocationID.x;
    if (r >= count) return;
    LayerView v;
    v.eye = vec3(view_in[0], view_in[1], view_in[2]);
    v.forward = vec3(view_in[3], view_in[4], view_in[5]);
    v.right = vec3(view_in[6], view_in[7], view_in[8]);
    v.up = vec3(view_in[9], view_in[10], view_in[11]);
    v.tan_half_fov = view_in[12];
    v.near = view_in[13];
    v.far = view_in[14];
    v.size = int(view_in[15]);
    int layers = int(view_in[16]);
    float thickness = view_in[17];
    uint at = 10u * r;
    LayerSegment seg;
    seg.empty = segment_in[at] != 0.0;
    seg.s0 = segment_in[at + 1u];
    seg.s1 = segment_in[at + 2u];
    seg.z0 = segment_in[at + 3u];
    seg.z1 = segment_in[at + 4u];
    seg.p0 = vec2(segment_in[at + 5u], segment_in[at + 6u]);
    seg.p1 = vec2(segment_in[at + 7u], segment_in[at + 8u]);
    int plane = v.size * v.size;
    LayerTrace t = bc_layer_trace_begin(v, seg, layers, thickness);
    for (int k = 0; k < t.steps; ++k) {
        if (t.done) break;
        float depths[BC_LAYERS_MAX];
        for (int l = 0; l < BC_LAYERS_MAX; ++l)
            depths[l] = l < t.layers ? depth_in[l * plane + t.y * v.size + t.x] : 0.0;
        t = bc_layer_trace_step(v, seg, t, depths);
    }
    LayerHit h = t.hit;
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
