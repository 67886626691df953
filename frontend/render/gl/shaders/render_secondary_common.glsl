// What dof-secondary's clip and trace passes share (render_secondary_clip.comp,
// render_secondary_trace.comp): the cluster's view as the host packs it
// (gl_layer_trace.cpp's 18 floats: eye, forward, right, up, tan_half_fov,
// near, far, size, layers, thickness) and a ray's clipped segment as 10
// floats (empty, s0, s1, z0, z1, p0, p1, unused).
layout(std430, binding = BC_GL_TRACE_VIEW_BINDING) readonly buffer View { float view_in[]; };
layout(std430, binding = BC_GL_TRACE_SEGMENTS_BINDING) buffer Segments { float segment_io[]; };

// The invocation's item: dispatches are 2D (gl_layer_trace.cpp,
// dispatch_items) so that more than 65,535 work groups of items fit. Both
// passes declare local_size_x = BC_TRACE_GROUP (gl_WorkGroupSize is not
// declared before their layout line).
#define BC_TRACE_GROUP 64
uint dispatch_item() {
    return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * uint(BC_TRACE_GROUP) + gl_LocalInvocationID.x;
}

LayerView trace_view() {
    LayerView v;
    v.eye = vec3(view_in[0], view_in[1], view_in[2]);
    v.forward = vec3(view_in[3], view_in[4], view_in[5]);
    v.right = vec3(view_in[6], view_in[7], view_in[8]);
    v.up = vec3(view_in[9], view_in[10], view_in[11]);
    v.tan_half_fov = view_in[12];
    v.near = view_in[13];
    v.far = view_in[14];
    v.size = int(view_in[15]);
    return v;
}
int trace_layer_count() { return int(view_in[16]); }
float trace_thickness() { return view_in[17]; }

LayerSegment load_segment(uint ray) {
    uint at = 10u * ray;
    LayerSegment seg;
    seg.empty = segment_io[at] != 0.0;
    seg.s0 = segment_io[at + 1u];
    seg.s1 = segment_io[at + 2u];
    seg.z0 = segment_io[at + 3u];
    seg.z1 = segment_io[at + 4u];
    seg.p0 = vec2(segment_io[at + 5u], segment_io[at + 6u]);
    seg.p1 = vec2(segment_io[at + 7u], segment_io[at + 8u]);
    return seg;
}

void store_segment(uint ray, LayerSegment seg) {
    uint at = 10u * ray;
    segment_io[at] = seg.empty ? 1.0 : 0.0;
    segment_io[at + 1u] = seg.s0;
    segment_io[at + 2u] = seg.s1;
    segment_io[at + 3u] = seg.z0;
    segment_io[at + 4u] = seg.z1;
    segment_io[at + 5u] = seg.p0.x;
    segment_io[at + 6u] = seg.p0.y;
    segment_io[at + 7u] = seg.p1.x;
    segment_io[at + 8u] = seg.p1.y;
    segment_io[at + 9u] = 0.0;
}
