// The interleave, interval and accum methods: one invocation per framebuffer
// cell (one sample each; no MSAA), the pass's sample of that cell, the
// triangle's box for the pass, then bc_sample_test(), the alpha mask
// (mask_keeps) and gl_FragDepth = near / w with a strict GREATER depth test,
// as the stochastic path.
//  * interleave (method_kind 0): one framebuffer cell per tile of the
//    width*s x height*s lattice; in the pass of tuple k, tile t's cell is
//    the one lattice cell of t holding tuple k (tuple_cell, from the tile
//    set), sampled at its jittered position (interleaved_jitter);
//  * interval (1): pixel p's sample of stratum pass_index, computed by
//    render_method_samples.comp;
//  * accum (2): every pixel at the pass's offset, lens and time.
layout(std430, binding = BC_GL_METHOD_BOXES_BINDING) readonly buffer Boxes { MethodBox boxes[]; };
layout(std430, binding = BC_GL_COUNTERS_BINDING) buffer Counters { uint tested; uint hit; };
// tuple_cell[k * tile_count + t]: gy * lattice_width + gx of tuple k's cell in
// tile t, or 0xffffffff when that cell is past the image's edge.
layout(std430, binding = BC_GL_METHOD_TUPLE_CELLS_BINDING) readonly buffer TupleCells { uint tuple_cell[]; };
layout(std430, binding = BC_GL_PASS_SAMPLES_BINDING) readonly buffer PassSamples { vec4 pass_ndc_lens[]; };
layout(std430, binding = BC_GL_PASS_TIMES_BINDING) readonly buffer PassTimes { float pass_time[]; };

uniform vec2 target_size;  // framebuffer width, height
uniform uint lattice_width;  // interleave: width * scale
uniform uint tile_count;     // interleave: tiles in the framebuffer
uniform int method_kind;   // 0 interleave, 1 interval, 2 accum
uniform uint pass_index;   // the tuple (interleave), stratum (interval) or pass (accum)
uniform uint scale;        // lattice cells per pixel side (interleave)
uniform vec2 pass_lens;    // interleave, accum
uniform float pass_t;      // interleave, accum
uniform vec2 pass_offset;  // accum

flat in int g_box;
layout(location = 0) out uint out_id;

void main() {
    uvec2 cell = fragment_cell(gl_FragCoord.xy, target_size);
    vec2 ndc;
    vec2 lens = pass_lens;
    float time = pass_t;
    if (method_kind == 0) {
        uint slot_cell = tuple_cell[pass_index * tile_count + cell.y * uint(target_size.x) + cell.x];
        if (slot_cell == 0xffffffffu) discard;
        cell = uvec2(slot_cell % lattice_width, slot_cell / lattice_width);
        ivec4 r = boxes[g_box].rect;
        if (int(cell.x) < r.x || int(cell.x) > r.z || int(cell.y) < r.y || int(cell.y) > r.w) discard;
        vec2 jitter = bc_interleaved_jitter(cell.x, cell.y, seed);
        ndc = bc_interleaved_sample_ndc(ivec2(cell), int(scale), jitter, image_size);
    } else if (method_kind == 1) {
        uint p = cell.y * uint(image_size.x) + cell.x;
        ndc = pass_ndc_lens[p].xy;
        lens = pass_ndc_lens[p].zw;
        time = pass_time[p];
    } else {
        ndc = sample_ndc(cell.x, cell.y, pass_offset);
    }
    ScreenBound b;
    b.empty = false;
    b.lo = boxes[g_box].box.xy;
    b.hi = boxes[g_box].box.zw;
    b.hull_count = 0;
    int triangle = boxes[g_box].index.x;
    float depth;
    int verdict = bc_sample_test(triangles[triangle], b, true, bc_no_sample_bounds(), ndc, lens, time, near_plane, depth);
    if (verdict == BC_SAMPLE_CULLED) discard;
    atomicAdd(tested, 1u);
    if (verdict != BC_SAMPLE_COVERED) discard;
    if (!mask_keeps(triangle, ndc, lens, time)) discard;  // alphaMode MASK, before the depth test
    atomicAdd(hit, 1u);
    gl_FragDepth = bc_depth_key(near_plane, depth);
    out_id = uint(triangle);
}
