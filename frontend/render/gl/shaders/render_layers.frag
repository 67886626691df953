// dof-secondary's GL layers, passes 2 and 3 on the GL rasterizer
// (gl_layer_images.cpp, GlLayerRaster::graphics): one fragment per texel
// centre the rasterizer gives a fan triangle, its depth computed from the
// flat image points as the host's scan does, then layer_fragment
// (render_layers_fragment.glsl).
flat in vec3 corner_a;
flat in vec3 corner_b;
flat in vec3 corner_c;
flat in ivec2 fan_info;

void main() {
    RasterTriangle t = bc_raster_ccw(corner_a, corner_b, corner_c);
    if (!(t.area > 0.0)) return;
    float z = bc_raster_depth(t.a, t.b, t.c, t.area, gl_FragCoord.xy);
    uint done = layer_fragment(ivec2(gl_FragCoord.xy), z, fan_info.x, fan_info.y != 0);
    if (peel_pass != 0) return;
    atomicAdd(counts[BC_LAYER_COUNT_FRAGMENTS], 1u);
    if (done == BC_LAYER_FRAGMENT_CULLED_IN_FRONT) atomicAdd(counts[BC_LAYER_COUNT_CULLED_IN_FRONT], 1u);
    if (done == BC_LAYER_FRAGMENT_DROPPED) atomicAdd(counts[BC_LAYER_COUNT_DROPPED], 1u);
}
