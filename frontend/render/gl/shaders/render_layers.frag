// dof-secondary's GL layers, passes 2 and 3 (gl_layer_images.cpp): one
// fragment per texel centre the GL rasterizer gives a fan triangle. The view
// depth there is the host's (layer_raster_shared.h, from the flat image
// points); the paper's second cull drops the cluster's own triangles and
// depths not beyond the cluster's nearest point in the texel.
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
flat in vec3 corner_a;
flat in vec3 corner_b;
flat in vec3 corner_c;
flat in ivec2 fan_info;

void main() {
    vec3 a = corner_a;
    vec3 b = corner_b;
    vec3 c = corner_c;
    float area = bc_raster_edge(a.xy, b.xy, c.xy);
    if (!(abs(area) > 0.0)) return;
    if (area < 0.0) {
        vec3 swap = b;
        b = c;
        c = swap;
        area = -area;
    }
    float z = bc_raster_depth(a, b, c, area, gl_FragCoord.xy);
    int size = pass.sizes.x;
    ivec2 texel = ivec2(gl_FragCoord.xy);
    uint at = uint(texel.y * size + texel.x);
    uint plane = uint(size * size);
    if (peel_pass == 0) atomicAdd(counts[BC_LAYER_COUNT_FRAGMENTS], 1u);
    uint nearest = cluster_depth[at];
    if (fan_info.y != 0 || (nearest != BC_LAYER_EMPTY && z <= uintBitsToFloat(nearest))) {
        if (peel_pass == 0) atomicAdd(counts[BC_LAYER_COUNT_CULLED_IN_FRONT], 1u);
        return;
    }
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
        if (carried != BC_LAYER_EMPTY) atomicAdd(counts[BC_LAYER_COUNT_DROPPED], 1u);
        return;
    }
    for (int l = 0; l < layers; ++l) {
        if (layer_depth[uint(l) * plane + at] == bits) atomicMin(layer_triangle[uint(l) * plane + at], uint(fan_info.x));
    }
}
