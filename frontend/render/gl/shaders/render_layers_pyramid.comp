// dof-secondary's GL layers, pass 4 (gl_layer_images.cpp): the min/max depth
// pyramid, one dispatch per level. Level 0: per texel the min and max over
// the layers' surfaces; level i: per cell the min of the mins and the max of
// the maxes of the 2 x 2 cells of level i - 1 under it (fewer on an odd
// border). min and max are exact, so this is render/secondary's DepthPyramid
// bit for bit. Cells hold (lo, hi); lo = +inf, hi = -inf where no surface.
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) readonly buffer Pass { LayerPass pass; };
layout(std430, binding = 5) readonly buffer LayerDepth { uint layer_depth[]; };
layout(std430, binding = 9) buffer Pyramid { float pyramid[]; };  // levels, finest first, 2 floats a cell
uniform int level;        // 0: from the layers
uniform int size;         // cells per side of this level
uniform int offset;       // its first float in pyramid[]
uniform int fine_size;    // level - 1's cells per side
uniform int fine_offset;  // its first float

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (cell.x >= size || cell.y >= size) return;
    float lo = uintBitsToFloat(BC_LAYER_EMPTY);
    float hi = -lo;
    if (level == 0) {
        uint plane = uint(size * size);
        uint at = uint(cell.y * size + cell.x);
        for (int l = 0; l < pass.sizes.y; ++l) {
            uint bits = layer_depth[uint(l) * plane + at];
            if (bits == BC_LAYER_EMPTY) continue;
            float d = uintBitsToFloat(bits);
            lo = min(lo, d);
            hi = max(hi, d);
        }
    } else {
        for (int dy = 0; dy < 2; ++dy) {
            for (int dx = 0; dx < 2; ++dx) {
                ivec2 fine = 2 * cell + ivec2(dx, dy);
                if (fine.x >= fine_size || fine.y >= fine_size) continue;
                int from = fine_offset + 2 * (fine.y * fine_size + fine.x);
                lo = min(lo, pyramid[from]);
                hi = max(hi, pyramid[from + 1]);
            }
        }
    }
    int to = offset + 2 * (cell.y * size + cell.x);
    pyramid[to] = lo;
    pyramid[to + 1] = hi;
}
