// dof-secondary's GL layers, before the draws (gl_layer_images.cpp): the
// cluster's depth per texel, the nearest view depth of its ray origins that
// project there (render/secondary's cluster_origin_depth: the kernel's
// layer_project, then the texel under it). BC_LAYER_EMPTY where none does.
// `gathered`: origin i is the first vec4 of point origin_index[i] of the
// clustering's buffer (2 vec4 a ray: gl_clustering.cpp), else origins[i].
// Dispatched in rows of at most 65,535 work groups.
layout(local_size_x = 64) in;
layout(std430, binding = BC_GL_LAYER_PASS_BINDING) readonly buffer Pass { LayerPass pass; };
layout(std430, binding = BC_GL_LAYER_CLUSTER_DEPTH_BINDING) buffer ClusterDepth { uint cluster_depth[]; };
layout(std430, binding = BC_GL_LAYER_ORIGINS_BINDING) readonly buffer Origins { vec4 origins[]; };
layout(std430, binding = BC_GL_LAYER_ORIGIN_INDICES_BINDING) readonly buffer OriginIndices { uint origin_index[]; };
uniform bool gathered;

void main() {
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
    if (i >= uint(pass.sizes.w)) return;
    LayerView v = layer_pass_view(pass);
    vec3 p = bc_layer_project(v, gathered ? origins[2u * origin_index[i]].xyz : origins[i].xyz);
    if (!(p.z > 0.0)) return;
    int x = int(floor(p.x));
    int y = int(floor(p.y));
    if (x < 0 || y < 0 || x >= v.size || y >= v.size) return;
    atomicMin(cluster_depth[uint(y * v.size + x)], floatBitsToUint(p.z));
}
