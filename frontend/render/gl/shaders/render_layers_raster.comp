// dof-secondary's GL layers, passes 2 and 3 in compute (gl_layer_images.cpp,
// GlLayerRaster::compute): a work group per fan triangle of the setup pass
// scans the texel centres of its box with the host's coverage test and depth
// (layer_raster_shared.h: the texels the host's scan covers, on any GPU,
// where the GL rasterizer snaps to its own fixed point), its 32 invocations
// (a warp: most fans cover a few texels) taking the box's texels in turn,
// each covered one to layer_fragment (render_layers_fragment.glsl). The
// fans are dispatched as rows of work groups (at most 65,535 a row); groups
// past the setup pass's fan count return.
layout(local_size_x = 32) in;
layout(std430, binding = BC_GL_LAYER_FANS_BINDING) readonly buffer Fans { LayerFan fans[]; };

void main() {
    // The invocation's counts, added to the buffer's at its end (not an
    // atomic per fragment; no barrier, which llvmpipe makes dear).
    uint fragments = 0u;
    uint in_front = 0u;
    uint dropped = 0u;
    uint f = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (f < counts[BC_LAYER_COUNT_FANS]) {  // the same for the whole group
        LayerFan fan = fans[f];
        RasterTriangle t = bc_raster_ccw(fan.a.xyz, fan.b.xyz, fan.c.xyz);
        ivec4 box = bc_raster_texel_box(t, pass.sizes.x);
        int width = box.z - box.x + 1;
        int height = box.w - box.y + 1;
        if (t.area > 0.0 && width > 0 && height > 0) {
            bvec3 owns = bc_raster_owned_edges(t);
            uint texels = uint(width) * uint(height);
            for (uint i = gl_LocalInvocationIndex; i < texels; i += gl_WorkGroupSize.x) {
                ivec2 texel = ivec2(box.x + int(i % uint(width)), box.y + int(i / uint(width)));
                vec2 centre = vec2(texel) + vec2(0.5);
                if (!bc_raster_covers(t, owns, centre)) continue;
                uint done = layer_fragment(texel, bc_raster_depth(t.a, t.b, t.c, t.area, centre), fan.info.x,
                                           fan.info.y != 0);
                fragments += 1u;
                if (done == BC_LAYER_FRAGMENT_CULLED_IN_FRONT) in_front += 1u;
                if (done == BC_LAYER_FRAGMENT_DROPPED) dropped += 1u;
            }
        }
    }
    if (peel_pass != 0) return;
    if (fragments > 0u) atomicAdd(counts[BC_LAYER_COUNT_FRAGMENTS], fragments);
    if (in_front > 0u) atomicAdd(counts[BC_LAYER_COUNT_CULLED_IN_FRONT], in_front);
    if (dropped > 0u) atomicAdd(counts[BC_LAYER_COUNT_DROPPED], dropped);
}
