// dof-secondary's rays of one cluster gathered on the GPU (gl_layer_trace.cpp,
// queue_bounce_gathered): ray i is point indices[i] of the clustering's
// buffer, started `offset` along its direction off its own surface, as the
// host's cluster_rays starts it (origin + offset * direction, each product
// and sum rounded once: precise), and written where the clip and trace
// passes read their rays.
layout(local_size_x = BC_TRACE_GROUP) in;
layout(std430, binding = BC_GL_CLUSTER_POINTS_BINDING) readonly buffer Points { vec4 point[]; };  // position, direction
layout(std430, binding = BC_GL_GATHER_INDICES_BINDING) readonly buffer Indices { uint ray_index[]; };
layout(std430, binding = BC_GL_TRACE_RAYS_BINDING) writeonly buffer Rays { vec4 ray_out[]; };  // start, direction
uniform uint count;
uniform float offset;

void main() {
    uint i = dispatch_item();
    if (i >= count) return;
    uint r = ray_index[i];
    vec3 origin = point[2u * r].xyz;
    vec3 direction = point[2u * r + 1u].xyz;
    precise vec3 start = origin + offset * direction;
    ray_out[2u * i] = vec4(start, 0.0);
    ray_out[2u * i + 1u] = vec4(direction, 0.0);
}
