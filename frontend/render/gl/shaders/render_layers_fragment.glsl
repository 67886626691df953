// dof-secondary's GL layers, what passes 2 and 3 do with one covered texel
// centre, whichever scan found it (render_layers.frag on the GL rasterizer,
// render_layers_raster.comp in compute; gl_layer_images.cpp). The view
// depth there is the host's (layer_raster_shared.h); the paper's second cull
// drops the cluster's own triangles and depths not beyond the cluster's
// nearest point in the texel.
//   peel_pass 0: a k-buffer of the `layers` nearest depths per texel, by an
//     atomicMin cascade on the depth bits (order-independent: slot l ends
//     with the l-th smallest, as the host's sorted insertion), and the count
//     of depths offered per texel (the pyramid's base reads the first and the
//     last of them only);
//   peel_pass 1: each fragment whose depth is in its texel's list writes its
//     triangle there (atomicMin: equal depths keep the lowest triangle).
layout(std430, binding = BC_GL_LAYER_PASS_BINDING) readonly buffer Pass { LayerPass pass; };
layout(std430, binding = BC_GL_LAYER_COUNTS_BINDING) buffer Counts { uint counts[]; };
layout(std430, binding = BC_GL_LAYER_DEPTH_BINDING) buffer LayerDepth { uint layer_depth[]; };        // [layer][y][x] depth bits
layout(std430, binding = BC_GL_LAYER_TRIANGLE_IDS_BINDING) buffer LayerTriangleIds { uint layer_triangle[]; };  // [layer][y][x]
layout(std430, binding = BC_GL_LAYER_CLUSTER_DEPTH_BINDING) readonly buffer ClusterDepth { uint cluster_depth[]; };  // [y][x] depth bits
layout(std430, binding = BC_GL_LAYER_TEXEL_COUNTS_BINDING) buffer TexelCounts { uint texel_count[]; };           // [y][x]
uniform int peel_pass;

// What layer_fragment did, for the pass's counts (peel_pass 0 only).
#define BC_LAYER_FRAGMENT_CULLED_IN_FRONT 1u
#define BC_LAYER_FRAGMENT_DROPPED 2u

// Texel `texel` covered by `triangle` (the cluster's own: `own`) at view
// depth z; returns 0 or one of BC_LAYER_FRAGMENT_*.
uint layer_fragment(ivec2 texel, float z, int triangle, bool own) {
    int size = pass.sizes.x;
    uint at = uint(texel.y * size + texel.x);
    uint plane = uint(size * size);
    uint nearest = cluster_depth[at];
    if (own || (nearest != BC_LAYER_EMPTY && z <= uintBitsToFloat(nearest))) return BC_LAYER_FRAGMENT_CULLED_IN_FRONT;
    uint bits = floatBitsToUint(z);
    int layers = pass.sizes.y;
    if (peel_pass == 0) {
        atomicAdd(texel_count[at], 1u);
        uint carried = bits;
        for (int l = 0; l < layers; ++l) {
            uint held = atomicMin(layer_depth[uint(l) * plane + at], carried);
            carried = max(held, carried);
            if (carried == BC_LAYER_EMPTY) break;
        }
        return carried != BC_LAYER_EMPTY ? BC_LAYER_FRAGMENT_DROPPED : 0u;
    }
    for (int l = 0; l < layers; ++l) {
        if (layer_depth[uint(l) * plane + at] == bits) atomicMin(layer_triangle[uint(l) * plane + at], uint(triangle));
    }
    return 0u;
}
