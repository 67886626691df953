// dof-secondary's GL layers, pass 1 of 4 (gl_layer_images.cpp): per scene
// triangle, the normal cull (the paper's third), the clip at the cluster's
// near plane (the first) and the projection into the view, with the host's
// arithmetic (layer_raster_shared.h); appends the fan of at most two image
// triangles that render_layers.vert draws (culled triangles append none),
// and counts their vertices into the indirect draw's command.
// docs/secondary-rays.md.
layout(local_size_x = 64) in;
layout(std430, binding = BC_GL_LAYER_TRIANGLES_BINDING) readonly buffer Triangles { LayerTriangle triangles[]; };
layout(std430, binding = BC_GL_LAYER_PASS_BINDING) readonly buffer Pass { LayerPass pass; };
layout(std430, binding = BC_GL_LAYER_OWN_BINDING) readonly buffer Own { uint own_bits[]; };  // bit t: the cluster's own triangle
layout(std430, binding = BC_GL_LAYER_FANS_BINDING) writeonly buffer Fans { LayerFan fans[]; };  // up to 2 per triangle
layout(std430, binding = BC_GL_LAYER_COUNTS_BINDING) buffer Counts { uint counts[]; };           // BC_LAYER_COUNT_*

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= uint(pass.sizes.z)) return;
    LayerView v = layer_pass_view(pass);
    LayerTriangle tri = triangles[t];
    if (bc_dot3(tri.normal.xyz, v.forward) > pass.frustum.w) {
        atomicAdd(counts[BC_LAYER_COUNT_CULLED_NORMAL], 1u);
        return;
    }
    vec3 local[3] = vec3[3](bc_raster_view_point(v, tri.p0.xyz), bc_raster_view_point(v, tri.p1.xyz),
                            bc_raster_view_point(v, tri.p2.xyz));
    // Sutherland-Hodgman against depth >= near, as layer_raster.inl's clip_near.
    vec3 clipped[4];
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        vec3 a = local[i];
        vec3 b = local[(i + 1) % 3];
        bool a_in = a.z >= v.near;
        bool b_in = b.z >= v.near;
        if (a_in) {
            clipped[count] = a;
            count += 1;
        }
        if (a_in != b_in) {
            clipped[count] = bc_raster_near_crossing(a, b, v.near);
            count += 1;
        }
    }
    if (count < 3) {
        atomicAdd(counts[BC_LAYER_COUNT_CULLED_NEAR], 1u);
        return;
    }
    vec3 image[4];
    for (int k = 0; k < count; ++k) image[k] = bc_raster_image_point(v, clipped[k]);
    int own = int((own_bits[t >> 5u] >> (t & 31u)) & 1u);
    uint first = atomicAdd(counts[BC_LAYER_COUNT_FANS], uint(count - 2));
    atomicAdd(counts[BC_LAYER_COUNT_DRAW], 3u * uint(count - 2));  // the indirect draw's vertex count
    for (int k = 1; k + 1 < count; ++k) {
        LayerFan fan;
        fan.a = vec4(image[0], 0.0);
        fan.b = vec4(image[k], 0.0);
        fan.c = vec4(image[k + 1], 0.0);
        fan.info = ivec4(int(t), own, 0, 0);
        fans[first + uint(k - 1)] = fan;
    }
}
