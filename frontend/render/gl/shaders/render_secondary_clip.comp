// dof-secondary's interval clipping on the GPU (gl_layer_trace.cpp): one
// invocation per group of rays clipped together (one pixel's samples in one
// lens part; the host's groups, or GlClustering::group's, in any order). Each ray's segment starts clipped to the view only; then, for
// BC_BOUNCE_CLIP_ROUNDS rounds, the union of the group's footprints is
// looked up in the layers' min/max pyramid where GlLayerBuilder made it, and
// every non-empty segment is clipped to that interval again: clip_group in
// render/secondary/dof_secondary.cpp, with the same kernel and
// bounce_shared.h text, so the same segments. The trace pass reads them.
layout(local_size_x = BC_TRACE_GROUP) in;
layout(std430, binding = BC_GL_TRACE_PYRAMID_BINDING) readonly buffer Pyramid { float pyramid[]; };  // levels, finest first, (lo, hi) a cell
layout(std430, binding = BC_GL_TRACE_RAYS_BINDING) readonly buffer Rays { vec4 ray_in[]; };          // start, direction per ray
// How many groups, then per group the (begin, end) of its rays.
layout(std430, binding = BC_GL_TRACE_GROUPS_BINDING) readonly buffer Groups { uint group_word[]; };

// The (min, max) depth of the surfaces in texel box [x0, x1] x [y0, y1]
// (DepthPyramid::interval over GlLayerBuilder's levels); min > max for none.
vec2 pyramid_interval(int x0, int y0, int x1, int y1, int size) {
    int levels = 1;
    for (int s = size; s > 1; s = (s + 1) / 2) ++levels;
    int level = bc_pyramid_level(x0, y0, x1, y1, levels);
    int offset = 0;
    int cells = size;
    for (int k = 0; k < level; ++k) {
        offset += 2 * cells * cells;
        cells = (cells + 1) / 2;
    }
    vec2 range = vec2(uintBitsToFloat(0x7F800000u), -uintBitsToFloat(0x7F800000u));
    for (int y = y0 >> level; y <= (y1 >> level); ++y) {
        for (int x = x0 >> level; x <= (x1 >> level); ++x) {
            int at = offset + 2 * (y * cells + x);
            range.x = min(range.x, pyramid[at]);
            range.y = max(range.y, pyramid[at + 1]);
        }
    }
    return range;
}

void main() {
    uint g = dispatch_item();
    if (g >= group_word[0]) return;
    uint first = group_word[1u + 2u * g];
    uint last = group_word[2u + 2u * g];
    LayerView v = trace_view();
    float huge = float(BC_BOUNCE_HUGE_DEPTH);
    for (uint i = first; i < last; ++i)
        store_segment(i, bc_layer_segment(v, ray_in[2u * i].xyz, ray_in[2u * i + 1u].xyz, huge, vec2(0.0, huge)));
    for (int round = 0; round < BC_BOUNCE_CLIP_ROUNDS; ++round) {
        vec4 box = bc_footprint_none(v.size);
        for (uint i = first; i < last; ++i) box = bc_footprint_union(box, bc_layer_footprint(v, load_segment(i)));
        if (box.x > box.z) break;  // every segment empty: all leave the layers
        vec2 range = pyramid_interval(int(box.x), int(box.y), int(box.z), int(box.w), v.size);
        vec2 clip = bc_bounce_clip(range, trace_thickness(), huge);
        for (uint i = first; i < last; ++i) {
            if (load_segment(i).empty) continue;
            store_segment(i, bc_layer_segment(v, ray_in[2u * i].xyz, ray_in[2u * i + 1u].xyz, huge, clip));
        }
    }
}
