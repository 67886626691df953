// dof-secondary's GL layers, before the draws (gl_layer_images.cpp): the
// cluster's depth per texel, the nearest view depth of its ray origins that
// project there (render/secondary's cluster_origin_depth: the kernel's
// layer_project, then the texel under it). BC_LAYER_EMPTY where none does.
layout(local_size_x = 64) in;
layout(std430, binding = BC_GL_LAYER_PASS_BINDING) readonly buffer Pass { LayerPass pass; };
layout(std430, binding = BC_GL_LAYER_CLUSTER_DEPTH_BINDING) buffer ClusterDepth { uint cluster_depth[]; };
layout(std430, binding = BC_GL_LAYER_ORIGINS_BINDING) readonly buffer Origins { vec4 origins[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(pass.sizes.w)) return;
    LayerView v = layer_pass_view(pass);
    vec3 p = bc_layer_project(v, origins[i].xyz);
    if (!(p.z > 0.0)) return;
    int x = int(floor(p.x));
    int y = int(floor(p.y));
    if (x < 0 || y < 0 || x >= v.size || y >= v.size) return;
    atomicMin(cluster_depth[uint(y * v.size + x)], floatBitsToUint(p.z));
}
