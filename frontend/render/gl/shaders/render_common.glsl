// Shared by the GL backend's stages (frontend/render/gl/gl_backend.cpp): compiled
// after the kernel's GLSL and gpu_layout_shared.h (TriangleInfo, CellBounds,
// MethodBox, BC_GL_CELLS_MAX, BC_GL_PATH_*) and before each stage's main.
// docs/gl-backend.md.

// The clip-space triangles, made on the host by make_moving_triangle<float>.
layout(std430, binding = BC_GL_TRIANGLES_BINDING) readonly buffer Triangles { MovingTriangle triangles[]; };

// Adds uint `n` to the 64-bit counter held as two buffer words, `lo` and
// `carry`: atomically, the carry counted where lo wraps (old + n < old). A
// frame of the compute pipeline can test more than 2^32 samples (about 20
// times the forest at 1024x768, 16 spp); the host reads lo + 2^32 carry
// (SampleCounters). A macro: atomics take the buffer variable itself.
#define BC_COUNTER_ADD(lo, carry, n)                    \
    {                                                   \
        uint bc_counter_before_ = atomicAdd(lo, (n));   \
        if (bc_counter_before_ + (n) < bc_counter_before_) atomicAdd(carry, 1u); \
    }

uniform vec2 image_size;   // width, height in pixels
uniform float near_plane;  // CameraModel::znear
uniform uint spp;
uniform uint seed;
uniform uint pass_base;    // samples pass_base .. pass_base + 3 are drawn in this pass

// CameraModel::sample_ndc: pixel (px, py)'s sample at offset, as on the host.
vec2 sample_ndc(uint px, uint py, vec2 offset) {
    return bc_pixel_sample_ndc(ivec2(px, py), offset, image_size);
}

// Pixel `pixel`'s sample j of the pattern (setup: bc_sampler_setup of the
// pixel, in the settings' sampler): NDC and lens in ndc_lens, its time. The
// fragment pipeline's render_samples.comp and the compute pipeline's
// render_compute_raster.comp draw the same samples through it.
void pattern_sample(SamplerSetup setup, uvec2 pixel, uint j, out vec4 ndc_lens, out float time) {
    PixelSample s = bc_sampler_sample(setup, j);
    ndc_lens = vec4(sample_ndc(pixel.x, pixel.y, s.offset), s.lens);
    time = s.time;
}

// The sample bounds a cell (CellBounds, render_bounds.comp) or a compute
// tile carries: lens ranges and time lines; no edge planes (those cull whole
// cells and tiles only, when bc_sample_bounds finds them empty).
SampleBounds carried_sample_bounds(vec4 lens, vec4 u_time_a, vec4 u_time_b, vec4 v_time_a, vec4 v_time_b) {
    SampleBounds sb;
    sb.empty = false;
    sb.u_range = lens.xy;
    sb.v_range = lens.zw;
    sb.u_time_a = u_time_a;
    sb.u_time_b = u_time_b;
    sb.v_time_a = v_time_a;
    sb.v_time_b = v_time_b;
    sb.edges = bc_no_edge_bounds();
    sb.centre = vec2(0.0);
    return sb;
}

// The compute pipeline's tile lists (render_compute_bin.comp fills them,
// render_compute_scan.comp sizes them, render_compute_raster.comp reads them).
#define TILE_BUFFERS \
    layout(std430, binding = BC_GL_TILE_COUNTS_BINDING) buffer TileCounts { uint tile_counts[]; }; \
    layout(std430, binding = BC_GL_TILE_ENDS_BINDING) buffer TileEnds { uint tile_ends[]; }; \
    layout(std430, binding = BC_GL_TILE_LIST_BINDING) buffer TileList { uint tile_list[]; }; \
    layout(std430, binding = BC_GL_TILE_STATE_BINDING) buffer TileState { TileBinState bin_state; };

// The cell (row 0 at the top) of a fragment at window position frag_coord
// (gl_FragCoord.xy) in a framebuffer of `size` cells: GL's window rows grow upwards.
uvec2 fragment_cell(vec2 frag_coord, vec2 size) {
    return uvec2(uint(frag_coord.x), uint(size.y) - 1u - uint(frag_coord.y));
}

// The current pass's samples (render_samples.comp): pixel p's sample
// pass_base + k is at slot 4 p + k.
#define PASS_SAMPLE_BUFFERS \
    layout(std430, binding = BC_GL_PASS_SAMPLES_BINDING) readonly buffer PassSamples { vec4 pass_ndc_lens[]; }; \
    layout(std430, binding = BC_GL_PASS_TIMES_BINDING) readonly buffer PassTimes { float pass_time[]; };

// A group of passes' samples (render_samples.comp with stride group_samples):
// pixel p's sample pass_base + k at slot group_samples p + k; and a static
// triangle's depth key at one of them, as the per-pass static draw writes it
// to gl_FragDepth (clamped to the depth range as the depth buffer clamps it),
// or -1 where it does not cover the sample.
#define GROUP_SAMPLE_BUFFERS \
    layout(std430, binding = BC_GL_GROUP_SAMPLES_BINDING) readonly buffer GroupSamples { vec4 group_ndc_lens[]; }; \
    layout(std430, binding = BC_GL_GROUP_TIMES_BINDING) readonly buffer GroupTimes { float group_time[]; }; \
    uniform uint group_samples; \
    float static_depth_key(int i, uint slot) { \
        vec4 ndc_lens = group_ndc_lens[slot]; \
        float depth; \
        if (!bc_covers(triangles[i], ndc_lens.xy, ndc_lens.zw, group_time[slot], near_plane, depth)) return -1.0; \
        return bc_depth_key(near_plane, depth); \
    }

// Corner k (0..5, two triangles) of the quad over pixels rect, in NDC.
vec2 quad_corner(ivec4 rect, int k) {
    bool right = k == 1 || k == 4 || k == 5;
    bool top = k == 2 || k == 3 || k == 5;
    return bc_raster_to_ndc(vec2(float(right ? rect.z + 1 : rect.x), float(top ? rect.y : rect.w + 1)), image_size);
}
