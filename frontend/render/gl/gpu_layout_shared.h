// The GL backend's shader-storage structs, written once for C++ and GLSL
// (std430), as Blender's *_shared.h structs are: the C++ side includes this
// header and checks every size and offset with static_assert; the GLSL side
// gets the same text after the kernel's GLSL (which defines BC_HULL_MAX and
// MovingTriangle) and before render_common.glsl (frontend/render/gl/CMakeLists.txt
// embeds it beside the shader mains). Every member is a 16-byte vec4 / ivec4
// or four 4-byte ints filling 16 bytes, whose std430 offsets are those of the
// C++ struct of glm::vec4 / glm::ivec4 / int; the one struct that is not
// (MovingTriangle, vec3 p[6] at stride 16) is the kernel's in GLSL and
// GpuMovingTriangle here.
// docs/gl-backend.md, "Buffers".
#ifndef BLURCULL_GPU_LAYOUT_SHARED_H
#define BLURCULL_GPU_LAYOUT_SHARED_H

#ifdef __cplusplus
#include <blurcull/kernel.hpp>

#include <glm/glm.hpp>

#include <cstddef>

namespace blurcull::frontend::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
#endif

// A moving triangle's pixel rectangle is split into at most 4 x 4 cells, each
// with the method's sample bounds for its pixels (render_bounds.comp).
#define BC_GL_CELLS_MAX 16

// TriangleInfo.path: which path draws the triangle.
#define BC_GL_PATH_NONE 0
#define BC_GL_PATH_STATIC 1
#define BC_GL_PATH_MOVING 2

// What render_setup.comp finds out about triangle i, once per frame.
struct TriangleInfo {
    vec4 box;        // screen_bound: lo.xy, hi.xy (NDC)
    ivec4 rect;      // box_cell_rect of box: pixels x0, y0, x1, y1 (inclusive, row 0 at the top)
    int needs;       // bc_classify(): 0 (static, in focus), BC_NEEDS_* bits, or BC_INVALID
    int hull_count;  // screen_bound's hull edges in hull[]
    int path;        // the path that draws it: BC_GL_PATH_*
    int padding;     // 0; the four ints fill the 16 bytes before outline01 (std430)
    vec4 outline01;  // static path: the one triangle it draws (window pixels,
    vec4 outline2;   // y up), vertices 0, 1 in outline01 and 2 in outline2.xy
    vec4 hull[BC_HULL_MAX];  // the hull's edges (xyz)
};

// One cell of a moving triangle (render_bounds.comp) and its sample bounds.
struct CellBounds {
    ivec4 rect;  // pixels x0, y0, x1, y1; empty when x0 > x1
    vec4 lens;   // SampleBounds u_range, v_range
    // SampleBounds' time lines (sample_passes): each holds (a, b, c, d) for
    // a + b u <= t <= c + d u, over the lens u (time_lines_u_*) or v
    // (time_lines_v_*). Two-stage: _a from the footprint's far edge (condition
    // A), _b from its near edge (B); dual-space: _a the time range, _b [0, 1].
    vec4 time_lines_u_a;  // SampleBounds.u_time_a
    vec4 time_lines_u_b;  // SampleBounds.u_time_b
    vec4 time_lines_v_a;  // SampleBounds.v_time_a
    vec4 time_lines_v_b;  // SampleBounds.v_time_b
};

// One (pass, triangle) box of the interleave, interval and accum methods
// (gl_sampling_methods.cpp fills it from method_pass_box; render_method.*).
struct MethodBox {
    ivec4 quad;   // framebuffer cells x0, y0, x1, y1 (inclusive, row 0 at the top)
    ivec4 rect;   // lattice cells (pixels but for interleave) x0, y0, x1, y1, inclusive
    vec4 box;     // screen box lo.xy, hi.xy (NDC), rounded inwards to float
    ivec4 index;  // x: the triangle
};

// The alpha mask test's buffers (shaders/render_mask.glsl, filled by
// gl_alpha_mask.cpp): MaskSlots holds per triangle its entry in
// MaskTriangles, or -1 when its material is not alphaMode MASK; MaskTexels
// holds BC_GL_ALPHA_CODES floats (code / 255 of every 8-bit alpha, so the
// GPU reads the host's value), then the masked textures' alpha bytes, four
// per uint (texel k of a texture at byte texture.x + k, little end first).
#define BC_GL_MASK_SLOTS_BINDING 16
#define BC_GL_MASK_TRIANGLES_BINDING 17
#define BC_GL_MASK_TEXELS_BINDING 18
#define BC_GL_ALPHA_CODES 256

// MaskTriangle.flags: which of its attributes the mask formula reads (the
// host's hit_alpha takes 1 for a missing one, not an interpolated 1).
#define BC_GL_MASK_HAS_TEXCOORD 1
#define BC_GL_MASK_HAS_COLOR 2

// One triangle of an alphaMode MASK material: what hit_alpha reads.
struct MaskTriangle {
    vec4 uv01;           // TEXCOORD_0 of vertices 0 (xy) and 1 (zw)
    vec4 uv2_alpha;      // vertex 2's (xy); z: baseColorFactor's alpha, w: alphaCutoff
    vec4 vertex_alpha;   // COLOR_0's alpha of vertices 0, 1, 2 (xyz); w: 0
    vec4 transform_row0; // the base colour texture's KHR_texture_transform, rows 0
    vec4 transform_row1; // and 1 (xyz); w: 0
    ivec4 texture;       // x: its first alpha byte in MaskTexels' bytes (-1: none), y: width, z: height, w: 0
    ivec4 wrap_flags;    // x: wrap_s, y: wrap_t (BC_WRAP_*), z: BC_GL_MASK_HAS_* bits, w: 0
};

#ifdef __cplusplus
// The kernel's MovingTriangle as std430 lays it out (vec3 p[6] at stride 16,
// then vec2 c[6]): what the Triangles buffer holds.
struct GpuMovingTriangle {
    glm::vec4 p[6];  // clip (x, y, w, 0)
    glm::vec2 c[6];
};

// The float triangle the shaders see (make_moving_triangle<float>).
inline GpuMovingTriangle to_gpu(const kernelf::MovingTriangle& tri) {
    GpuMovingTriangle out;
    for (int j = 0; j < 6; ++j) {
        out.p[j] = glm::vec4(tri.p[j], 0.0f);
        out.c[j] = tri.c[j];
    }
    return out;
}

static_assert(sizeof(vec4) == 16 && sizeof(ivec4) == 16, "std430 vec4 / ivec4");
static_assert(sizeof(TriangleInfo) == (5 + BC_HULL_MAX) * 16, "std430 TriangleInfo");
static_assert(offsetof(TriangleInfo, rect) == 16 && offsetof(TriangleInfo, needs) == 32 &&
                  offsetof(TriangleInfo, hull_count) == 36 && offsetof(TriangleInfo, path) == 40 &&
                  offsetof(TriangleInfo, padding) == 44 &&
                  offsetof(TriangleInfo, outline01) == 48 && offsetof(TriangleInfo, outline2) == 64 &&
                  offsetof(TriangleInfo, hull) == 80,
              "std430 TriangleInfo offsets");
static_assert(sizeof(CellBounds) == 6 * 16 && offsetof(CellBounds, lens) == 16 &&
                  offsetof(CellBounds, time_lines_u_a) == 32 && offsetof(CellBounds, time_lines_v_b) == 80,
              "std430 CellBounds");
static_assert(sizeof(MethodBox) == 64 && offsetof(MethodBox, rect) == 16 && offsetof(MethodBox, box) == 32 &&
                  offsetof(MethodBox, index) == 48,
              "std430 MethodBox");
static_assert(sizeof(MaskTriangle) == 7 * 16 && offsetof(MaskTriangle, texture) == 80 &&
                  offsetof(MaskTriangle, wrap_flags) == 96,
              "std430 MaskTriangle");
static_assert(sizeof(GpuMovingTriangle) == 144 && offsetof(GpuMovingTriangle, c) == 96,
              "std430 MovingTriangle (vec3 p[6] at stride 16, vec2 c[6])");
// A buffer of these is an array: std430 rounds a struct's stride up to its
// alignment (16, that of its largest member), which every size above is.
static_assert(sizeof(TriangleInfo) % 16 == 0 && sizeof(CellBounds) % 16 == 0 && sizeof(MethodBox) % 16 == 0 &&
                  sizeof(MaskTriangle) % 16 == 0 &&
                  sizeof(GpuMovingTriangle) % 16 == 0,
              "std430 array strides");

}  // namespace blurcull::frontend::gpu
#endif

#endif  // BLURCULL_GPU_LAYOUT_SHARED_H
