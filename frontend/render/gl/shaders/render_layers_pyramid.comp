// dof-secondary's GL layers, pass 4 (gl_layer_images.cpp): the min/max depth
// pyramid in two dispatches. Level 0 (its cells are texels: the min and max
// over the layers' surfaces) is made together with level 1, one invocation
// per level-1 cell writing its 2 x 2 texels (from_layers 1); then one
// workgroup makes every later level in turn, a barrier between levels (few
// dispatches: each costs a wake-up of llvmpipe's threads). A texel's depths
// are sorted (render_layers.frag), so its min is the first and its max the
// last of its min(count, layers) depths, as the host's loop over every layer
// finds them. A cell of a later
// level is the min of the mins and the max of the maxes of the 2 x 2 cells of
// the level before under it (fewer on an odd border). min and max are exact,
// so this is render/secondary's DepthPyramid bit for bit. Cells hold
// (lo, hi); lo = +inf, hi = -inf where no surface.
layout(local_size_x = 16, local_size_y = 16) in;
layout(std430, binding = BC_GL_LAYER_PASS_BINDING) readonly buffer Pass { LayerPass pass; };
layout(std430, binding = BC_GL_LAYER_DEPTH_BINDING) readonly buffer LayerDepth { uint layer_depth[]; };
layout(std430, binding = BC_GL_LAYER_PYRAMID_BINDING) buffer Pyramid { float pyramid[]; };  // levels, finest first, 2 floats a cell
layout(std430, binding = BC_GL_LAYER_TEXEL_COUNTS_BINDING) readonly buffer TexelCounts { uint texel_count[]; };
uniform int from_layers;  // 1: levels 0 and 1 from the layers; 0: levels 2 and on, one workgroup
uniform int base_size;    // level 0's cells per side (texels)

// Texel `fine` of level 0 from the layers, written; returns its (lo, hi).
vec2 base_cell(ivec2 fine, int fine_size, int fine_offset) {
    float lo = uintBitsToFloat(BC_LAYER_EMPTY);
    float hi = -lo;
    uint plane = uint(fine_size * fine_size);
    uint at = uint(fine.y * fine_size + fine.x);
    uint count = min(texel_count[at], uint(pass.sizes.y));
    if (count > 0u) {
        lo = uintBitsToFloat(layer_depth[at]);
        hi = uintBitsToFloat(layer_depth[(count - 1u) * plane + at]);
    }
    int to = fine_offset + 2 * int(at);
    pyramid[to] = lo;
    pyramid[to + 1] = hi;
    return vec2(lo, hi);
}

// Cell `cell` of the level of `size` cells at float `offset`, from the level
// of `fine_size` cells at `fine_offset` (from_layers: from the layers, level
// 0 written on the way).
void make_cell(ivec2 cell, int size, int offset, int fine_size, int fine_offset) {
    float lo = uintBitsToFloat(BC_LAYER_EMPTY);
    float hi = -lo;
    for (int dy = 0; dy < 2; ++dy) {
        for (int dx = 0; dx < 2; ++dx) {
            ivec2 fine = 2 * cell + ivec2(dx, dy);
            if (fine.x >= fine_size || fine.y >= fine_size) continue;
            vec2 range;
            if (from_layers != 0) {
                range = base_cell(fine, fine_size, fine_offset);
            } else {
                int from = fine_offset + 2 * (fine.y * fine_size + fine.x);
                range = vec2(pyramid[from], pyramid[from + 1]);
            }
            lo = min(lo, range.x);
            hi = max(hi, range.y);
        }
    }
    int to = offset + 2 * (cell.y * size + cell.x);
    pyramid[to] = lo;
    pyramid[to + 1] = hi;
}

void main() {
    int level1_size = (base_size + 1) / 2;
    int level1_offset = 2 * base_size * base_size;
    if (from_layers != 0) {
        ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
        if (cell.x < level1_size && cell.y < level1_size) make_cell(cell, level1_size, level1_offset, base_size, 0);
        return;
    }
    int fine_size = level1_size;
    int fine_offset = level1_offset;
    int lanes = int(gl_WorkGroupSize.x * gl_WorkGroupSize.y);
    int lane = int(gl_LocalInvocationIndex);
    while (fine_size > 1) {
        int size = (fine_size + 1) / 2;
        int offset = fine_offset + 2 * fine_size * fine_size;
        for (int i = lane; i < size * size; i += lanes) make_cell(ivec2(i % size, i / size), size, offset, fine_size, fine_offset);
        memoryBarrierBuffer();
        barrier();
        fine_size = size;
        fine_offset = offset;
    }
}
