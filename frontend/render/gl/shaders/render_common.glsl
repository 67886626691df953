// Shared by the GL backend's stages (frontend/render/gl/gl_backend.cpp): compiled
// after the kernel's GLSL and before each stage's main. docs/gl-backend.md.

// What render_setup.comp finds out about triangle i, once per frame.
struct TriangleInfo {
    vec4 box;    // screen_bound: lo.xy, hi.xy (NDC)
    ivec4 rect;  // pixels x0, y0, x1, y1 (inclusive, row 0 at the top) holding every sample in box
    int needs;       // bc_classify(): 0 (static, in focus), BC_NEEDS_* bits, or BC_INVALID
    int hull_count;  // screen_bound's hull edges in hull[]
    int path;        // the path that draws it: PATH_NONE, PATH_STATIC or PATH_MOVING
    int padding;     // 0; the four ints fill the 16 bytes before outline01 (std430)
    vec4 outline01;  // static path: the one triangle it draws (window pixels,
    vec4 outline2;   // y up), vertices 0, 1 in outline01 and 2 in outline2.xy
    vec4 hull[BC_HULL_MAX];  // the hull's edges (xyz)
};

#define PATH_NONE 0
#define PATH_STATIC 1
#define PATH_MOVING 2

// The clip-space triangles, made on the host by make_moving_triangle<float>.
layout(std430, binding = 0) readonly buffer Triangles { MovingTriangle triangles[]; };

uniform vec2 image_size;   // width, height in pixels
uniform float near_plane;  // CameraModel::znear
uniform uint spp;
uniform uint seed;
uniform uint pass_base;    // samples pass_base .. pass_base + 3 are drawn in this pass

// CameraModel::sample_ndc: raster (x right, y down) to NDC, rounded as on the host.
vec2 sample_ndc(uint px, uint py, vec2 offset) {
    precise float rx = float(px) + offset.x;
    precise float ry = float(py) + offset.y;
    precise float x = -1.0 + 2.0 * rx / image_size.x;
    precise float y = 1.0 - 2.0 * ry / image_size.y;
    return vec2(x, y);
}

// NDC of the corner (x, y) of the pixel grid (x right, y down, in pixels).
vec2 grid_ndc(int x, int y) {
    precise float gx = -1.0 + 2.0 * float(x) / image_size.x;
    precise float gy = 1.0 - 2.0 * float(y) / image_size.y;
    return vec2(gx, gy);
}


// The current pass's samples (render_samples.comp): pixel p's sample
// pass_base + k is at slot 4 p + k.
#define PASS_SAMPLE_BUFFERS \
    layout(std430, binding = 7) readonly buffer PassSamples { vec4 pass_ndc_lens[]; }; \
    layout(std430, binding = 8) readonly buffer PassTimes { float pass_time[]; };

// A group of passes' samples (render_samples.comp with stride group_samples):
// pixel p's sample pass_base + k at slot group_samples p + k; and a static
// triangle's depth key at one of them, as the per-pass static draw writes it
// to gl_FragDepth (clamped to the depth range as the depth buffer clamps it),
// or -1 where it does not cover the sample.
#define GROUP_SAMPLE_BUFFERS \
    layout(std430, binding = 12) readonly buffer GroupSamples { vec4 group_ndc_lens[]; }; \
    layout(std430, binding = 13) readonly buffer GroupTimes { float group_time[]; }; \
    uniform uint group_samples; \
    float static_depth_key(int i, uint slot) { \
        vec4 ndc_lens = group_ndc_lens[slot]; \
        float depth; \
        if (!bc_covers(triangles[i], ndc_lens.xy, ndc_lens.zw, group_time[slot], near_plane, depth)) return -1.0; \
        return clamp(near_plane / depth, 0.0, 1.0); \
    }

// A moving triangle's pixel rectangle is split into at most 4 x 4 cells, each
// with the method's sample bounds for its pixels (render_bounds.comp).
#define CELLS_MAX 16
struct CellBounds {
    ivec4 rect;  // pixels x0, y0, x1, y1; empty when x0 > x1
    vec4 lens;   // u_range, v_range
    // SampleBounds' time lines (sample_passes): each holds (a, b, c, d) for
    // a + b u <= t <= c + d u, over the lens u (time_lines_u_*) or v
    // (time_lines_v_*). Two-stage: _a from the footprint's far edge (condition
    // A), _b from its near edge (B); dual-space: _a the time range, _b [0, 1].
    vec4 time_lines_u_a;  // SampleBounds.tx
    vec4 time_lines_u_b;  // SampleBounds.tx2
    vec4 time_lines_v_a;  // SampleBounds.ty
    vec4 time_lines_v_b;  // SampleBounds.ty2
};

// Corner k (0..5, two triangles) of the quad over pixels rect, in NDC.
vec2 quad_corner(ivec4 rect, int k) {
    bool right = k == 1 || k == 4 || k == 5;
    bool top = k == 2 || k == 3 || k == 5;
    return grid_ndc(right ? rect.z + 1 : rect.x, top ? rect.y : rect.w + 1);
}
