// Compute pipeline, binning (gl_compute_pipeline.cpp): one invocation per
// triangle that render_setup.comp put on a path. With fill = 0 it counts
// itself into every BC_GL_TILE_SIZE-pixel screen tile its pixel rectangle
// (bc_box_cell_rect of the kernel's screen bound) meets; render_compute_scan.comp
// turns the counts into list starts; with fill = 1 it writes its index into
// each of those tiles' lists (TileEnds advances from a list's start to its
// end). The order within a list is whatever the atomics give: the raster
// pass's depth rule (bc_depth_key_wins) does not depend on it. The host
// sizes the lists from the scan before the fill; an entry past the capacity
// is never written and sets bin_state.overflow = 2, which fails the frame.
layout(local_size_x = 64) in;

layout(std430, binding = BC_GL_INFOS_BINDING) readonly buffer Infos { TriangleInfo infos[]; };
TILE_BUFFERS

uniform int triangle_count;
uniform int fill;       // 0: count, 1: fill
uniform uint tiles_x;   // tiles per row

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= triangle_count) return;
    if (infos[i].path == BC_GL_PATH_NONE) return;
    ivec4 r = infos[i].rect / BC_GL_TILE_SIZE;  // the rect is on screen: non-negative
    for (int ty = r.y; ty <= r.w; ++ty) {
        for (int tx = r.x; tx <= r.z; ++tx) {
            uint t = uint(ty) * tiles_x + uint(tx);
            if (fill == 0) {
                atomicAdd(tile_counts[t], 1u);
            } else {
                uint slot = atomicAdd(tile_ends[t], 1u);
                if (slot < bin_state.capacity) {
                    tile_list[slot] = uint(i);
                } else {
                    atomicMax(bin_state.overflow, 2u);
                }
            }
        }
    }
}
