// The shader-storage structs of dof-secondary's GL layer passes
// (gl_layer_images.cpp, shaders/render_layers_*), written once for C++ and
// GLSL (std430) in the style of gpu_layout_shared.h: every member is a
// 16-byte vec4 / ivec4, whose std430 offsets are those of the C++ struct of
// glm::vec4 / glm::ivec4; the C++ side checks them with static_assert.
// docs/secondary-rays.md, "What the gl backend runs".
#ifndef BLURCULL_GL_LAYER_SHARED_H
#define BLURCULL_GL_LAYER_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cstddef>

namespace blurcull::frontend::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
#endif

// Slots of the counter buffer (LayerStats' fields).
#define BC_LAYER_COUNT_FRAGMENTS 0
#define BC_LAYER_COUNT_CULLED_NEAR 1
#define BC_LAYER_COUNT_CULLED_IN_FRONT 2
#define BC_LAYER_COUNT_CULLED_NORMAL 3
#define BC_LAYER_COUNT_DROPPED 4
#define BC_LAYER_COUNT_FANS 5  // fan triangles written (render_layers_setup.comp)
// Slots 6 to 9: the draws' DrawArraysIndirectCommand (vertex count = 3 per
// fan, 1 instance, first 0, base instance 0), counted by the setup pass so
// the host draws the fans without reading their number back.
#define BC_LAYER_COUNT_DRAW 6
#define BC_LAYER_COUNTS 10
// Slots FANS to the end are one cluster's (reset before each); those before
// add up over a render's clusters on the GPU-resident path.
#define BC_LAYERS_COUNT_PER_CLUSTER (BC_LAYER_COUNTS - BC_LAYER_COUNT_FANS)

// The bits of +infinity: "no surface" in the layers, "no cluster point" in
// the cluster's depth map. Positive floats order as their bits, so atomicMin
// on the bits is a min on the depths.
#define BC_LAYER_EMPTY 0x7F800000u

// A triangle of the scene in world space (at the middle of the rays'
// shutter slice) and its unit winding normal.
struct LayerTriangle {
    vec4 p0;
    vec4 p1;
    vec4 p2;
    vec4 normal;
};

// One triangle of the fan of a triangle clipped at the near plane (at most
// two per scene triangle): image points (x, y, view depth) in the order the
// host's scan takes them; info.x the scene triangle, info.y 1 when it is one
// of the cluster's own triangles. Appended in any order (the k-buffer's
// result does not depend on the order of the fragments).
struct LayerFan {
    vec4 a;
    vec4 b;
    vec4 c;
    ivec4 info;
};

// The cluster's view and the pass's sizes.
struct LayerPass {
    vec4 eye;      // xyz
    vec4 forward;  // xyz
    vec4 right;    // xyz
    vec4 up;       // xyz
    vec4 frustum;  // tan_half_fov, near, far, the normal cull's threshold
    ivec4 sizes;   // texels per side, layers, triangles, cluster points
};

#ifndef __cplusplus
// The kernel's LayerView of a pass.
LayerView layer_pass_view(LayerPass p) {
    LayerView v;
    v.eye = p.eye.xyz;
    v.forward = p.forward.xyz;
    v.right = p.right.xyz;
    v.up = p.up.xyz;
    v.tan_half_fov = p.frustum.x;
    v.near = p.frustum.y;
    v.far = p.frustum.z;
    v.size = p.sizes.x;
    return v;
}
#else
static_assert(sizeof(LayerTriangle) == 64 && sizeof(LayerFan) == 64 && offsetof(LayerFan, info) == 48,
              "std430 LayerTriangle, LayerFan");
static_assert(sizeof(LayerPass) == 96 && offsetof(LayerPass, frustum) == 64 && offsetof(LayerPass, sizes) == 80,
              "std430 LayerPass");

}  // namespace blurcull::frontend::gpu
#endif

#endif  // BLURCULL_GL_LAYER_SHARED_H
