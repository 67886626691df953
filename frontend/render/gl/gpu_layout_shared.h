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
#include <cstdint>
#include <initializer_list>

namespace blurcull::frontend::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uint = std::uint32_t;
#endif

// A moving triangle's pixel rectangle is split into at most 4 x 4 cells, each
// with the method's sample bounds for its pixels (render_bounds.comp).
#define BC_GL_CELLS_MAX 16

// TriangleInfo.path: which path draws the triangle.
#define BC_GL_PATH_NONE 0
#define BC_GL_PATH_STATIC 1
#define BC_GL_PATH_MOVING 2

// Every binding point of the GL passes, named once for both sides: the
// shaders' layout(binding = BC_GL_*) and the host's Buffer::bind_base. A
// binding point is context state, not program state, and each pass binds its
// buffers before it runs, so passes that never run together reuse numbers;
// within one pass they are distinct (the static_asserts at the end check it).
// The GL limit is at least 8 shader-storage bindings (GL 4.5, table 23.64);
// llvmpipe and NVIDIA offer far more than the 19 of the stochastic pass.
//
// The stochastic passes (gl_backend.cpp; shaders/render_{setup,bounds,
// samples,static*,moving,resolve}.*, render_common.glsl):
#define BC_GL_TRIANGLES_BINDING 0      // Triangles: MovingTriangle[] (render_common.glsl)
#define BC_GL_INFOS_BINDING 1          // Infos: TriangleInfo[]
#define BC_GL_COUNTERS_BINDING 2       // Counters: samples tested, hit (SampleCounters)
#define BC_GL_COLOURS_BINDING 3        // Colours: each triangle's, the background's last
#define BC_GL_SUMS_BINDING 4           // Sums: per pixel rgb and hit count
#define BC_GL_SAMPLE_IDS_BINDING 5     // SampleIds: per sample the triangle it shows
#define BC_GL_CELLS_BINDING 6          // Cells: CellBounds[]
#define BC_GL_PASS_SAMPLES_BINDING 7   // PassSamples: the pass's ndc and lens per sample
#define BC_GL_PASS_TIMES_BINDING 8     // PassTimes: the pass's time per sample
#define BC_GL_CLASSES_BINDING 9        // Classes: classify() of each triangle
#define BC_GL_STATIC_LIST_BINDING 10   // StaticList: the static path's triangles
#define BC_GL_MOVING_LIST_BINDING 11   // MovingList: the moving path's triangles
#define BC_GL_GROUP_SAMPLES_BINDING 12 // GroupSamples: a group of passes' samples
#define BC_GL_GROUP_TIMES_BINDING 13   // GroupTimes: and their times
#define BC_GL_GROUP_IDS_BINDING 14     // GroupIds: the group's static winner per sample
#define BC_GL_GROUP_DEPTHS_BINDING 15  // GroupDepths: and its depth key
#define BC_GL_MASK_SLOTS_BINDING 16    // MaskSlots (render_mask.glsl, gl_alpha_mask.cpp)
#define BC_GL_MASK_TRIANGLES_BINDING 17  // MaskTriangles
#define BC_GL_MASK_TEXELS_BINDING 18   // MaskTexels
// The compute pipeline (gl_compute_pipeline.cpp; shaders/render_compute_*,
// render_setup.comp, render_resolve.comp): the triangles, infos, counters,
// colours, sums, sample ids, classes and mask as above (it never runs with
// the fragment passes' cells, pass samples or draw lists), and
#define BC_GL_TILE_COUNTS_BINDING 6    // TileCounts: triangles listed per tile
#define BC_GL_TILE_ENDS_BINDING 7      // TileEnds: each tile's list start, its end after the fill
#define BC_GL_TILE_LIST_BINDING 8      // TileList: the tiles' triangle lists, one after another
#define BC_GL_TILE_STATE_BINDING 10    // TileState: TileBinState
#define BC_GL_SAMPLE_KEYS_BINDING 11   // SampleKeys: per sample the depth key of its winner so far
#define BC_GL_STRATUM_BOXES_BINDING 12 // StratumBoxes: per triangle BC_GL_TIME_STRATA screen boxes
// The compute pipeline's shutter slices: a moving triangle's samples of
// slice s (time in [s, s + 1] / BC_GL_TIME_STRATA) are tested only inside
// the kernel's stratum_screen_box of that slice.
#define BC_GL_TIME_STRATA 4
// render_resolve.comp's sampler of the pass's triangle ids: a texture unit.
#define BC_GL_PASS_IDS_UNIT 0
// The interleave / interval / accum passes (gl_sampling_methods.cpp;
// shaders/render_method*): the triangles, counters, pass samples and times
// and the mask as above, and
#define BC_GL_METHOD_BOXES_BINDING 9        // Boxes: MethodBox[]
#define BC_GL_METHOD_TUPLE_CELLS_BINDING 10 // TupleCells: interleave's cell per tile and pass
// dof-secondary's layer passes (gl_layer_images.cpp; shaders/render_layers*):
#define BC_GL_LAYER_TRIANGLES_BINDING 0      // Triangles: LayerTriangle[]
#define BC_GL_LAYER_PASS_BINDING 1           // Pass: LayerPass
#define BC_GL_LAYER_OWN_BINDING 2            // Own: the cluster's own triangles, a bit each
#define BC_GL_LAYER_FANS_BINDING 3           // Fans: LayerFan[]
#define BC_GL_LAYER_COUNTS_BINDING 4         // Counts: BC_LAYER_COUNT_*
#define BC_GL_LAYER_DEPTH_BINDING 5          // LayerDepth: the k-buffer's depth bits
#define BC_GL_LAYER_TRIANGLE_IDS_BINDING 6   // LayerTriangleIds: and its triangles
#define BC_GL_LAYER_CLUSTER_DEPTH_BINDING 7  // ClusterDepth: the cluster's depth map
#define BC_GL_LAYER_ORIGINS_BINDING 8        // Origins: the cluster's points
#define BC_GL_LAYER_PYRAMID_BINDING 9        // Pyramid: min/max levels
#define BC_GL_LAYER_TEXEL_COUNTS_BINDING 10  // TexelCounts: fragments per texel
#define BC_GL_LAYER_BINDINGS 11              // the layer passes' buffers: 0 .. 10
#define BC_GL_LAYER_ORIGIN_INDICES_BINDING 11  // OriginIndices: with origins gathered, the cluster's rays (not owned)
// dof-secondary's trace pass (gl_layer_trace.cpp; shaders/render_secondary_trace.comp):
#define BC_GL_TRACE_DEPTHS_BINDING 0    // Depths: the layers' depths
#define BC_GL_TRACE_SEGMENTS_BINDING 1  // Segments: 10 floats per ray
#define BC_GL_TRACE_VIEW_BINDING 2      // View: the cluster's view
#define BC_GL_TRACE_HITS_BINDING 3      // Hits: 8 words per ray
// ... and the GPU-resident bounce's (gl_layer_trace.cpp; render_secondary_clip.comp and the trace pass):
#define BC_GL_TRACE_TRIANGLE_IDS_BINDING 4  // TriangleIds: the layers' triangles (GlLayerBuilder's)
#define BC_GL_TRACE_PYRAMID_BINDING 5       // Pyramid: the layers' min/max levels (GlLayerBuilder's)
#define BC_GL_TRACE_RAYS_BINDING 6          // Rays: per ray its start and direction (vec4 each)
#define BC_GL_TRACE_GROUPS_BINDING 7        // Groups: per group of rays clipped together its end
//
// dof-secondary's clustering pass (gl_clustering.cpp; shaders/
// render_secondary_cluster.comp, after the trace passes' prelude, so
// numbered past their bindings):
#define BC_GL_CLUSTER_POINTS_BINDING 8  // Points: per ray its position and direction (vec4 each)
#define BC_GL_CLUSTER_LABELS_BINDING 9  // Labels: per ray facet * 4 + local cluster
#define BC_GL_CLUSTER_STATE_BINDING 10  // State: ClusterState (gl_cluster_shared.h)
#define BC_GL_CLUSTER_VIEWS_BINDING 11  // Views: ClusterViewFit per slot and fit (gl_cluster_shared.h)
#define BC_GL_GATHER_INDICES_BINDING 12 // Indices: a cluster's rays, as indices of Points (render_secondary_gather.comp)
// The grouping pass (render_secondary_group.comp), beside Points and Labels:
#define BC_GL_GROUP_SLOTS_BINDING 13    // Slots: ClusterSlotGroups per slot (gl_cluster_shared.h)
#define BC_GL_GROUP_LISTS_BINDING 14    // Lists: each slot's rays, group after group, from its first
#define BC_GL_GROUP_PAIRS_BINDING 15    // Pairs: each slot's groups (begin, end in its list), then scratch
#define BC_GL_GROUP_OWN_BINDING 16      // Own: each slot's own triangles, a bit each
//
// dof-secondary's primary resolve (gl_secondary_resolve.cpp, shaders/
// render_secondary_resolve.comp), writing the clustering's Points (8):
#define BC_GL_RESOLVE_IDS_BINDING 0       // SampleIds: per sample its winning triangle
#define BC_GL_RESOLVE_VERTICES_BINDING 1  // Vertices: per vertex view and world positions at open and close
#define BC_GL_RESOLVE_TRIANGLES_BINDING 2 // Triangles: per triangle its vertices, material, colour
#define BC_GL_RESOLVE_FRAME_BINDING 3     // Frame: the inverse views (double)
#define BC_GL_RESOLVE_COLOURS_BINDING 4   // Colours: per sample its direct colour
#define BC_GL_RESOLVE_COUNTS_BINDING 5    // Counts: per sample its rays; per chunk their sum, then its first ray
#define BC_GL_RESOLVE_RAYS_BINDING 6      // RayInfo: per ray its sample, time and weight

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

// The compute pipeline's screen tiles: BC_GL_TILE_SIZE x BC_GL_TILE_SIZE
// pixels, one work group of the raster pass each (one invocation per pixel).
#define BC_GL_TILE_SIZE 8

// The compute pipeline's binning state. render_compute_scan.comp writes the
// entries all tile lists need (a 64-bit count in two words), the longest
// list, and overflow = 1 when the entries exceed the capacity the host
// allocated; the host reads it before the fill and, on overflow, grows the
// list buffer first. The fill sets overflow = 2 if it ever finds no room
// (the host then fails the frame): no triangle is dropped silently.
struct TileBinState {
    uint entries;       // low word of the entries needed
    uint entries_high;  // high word (0 unless more than 2^32 - 1)
    uint capacity;      // entries the TileList buffer holds
    uint overflow;      // 1: entries > capacity (found by the scan), 2: the fill found no room
    uint max_count;     // the longest tile list
    uint occluded;      // (tile, entry, chunk of samples) the raster's occlusion test skipped
    uint padding1;
    uint padding2;
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
// MaskTriangles, or -1 when its material is opaque (not MASK or BLEND); MaskTexels
// holds BC_GL_ALPHA_CODES floats (code / 255 of every 8-bit alpha, so the
// GPU reads the host's value), then the masked textures' alpha bytes, four
// per uint (texel k of a texture at byte texture.x + k, little end first).
// Bound at BC_GL_MASK_*_BINDING (above).
#define BC_GL_ALPHA_CODES 256

// MaskTriangle.flags: which of its attributes the mask formula reads (the
// host's hit_alpha takes 1 for a missing one, not an interpolated 1).
#define BC_GL_MASK_HAS_TEXCOORD 1
#define BC_GL_MASK_HAS_COLOR 2
// alphaMode BLEND (stochastic transparency) instead of MASK's cutoff.
#define BC_GL_MASK_BLEND 4

// One triangle of an alphaMode MASK or BLEND material: what hit_alpha reads.
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
// Within one pass no two buffers share a binding point.
constexpr bool distinct_bindings(std::initializer_list<int> bindings) {
    for (const int* a = bindings.begin(); a != bindings.end(); ++a)
        for (const int* b = a + 1; b != bindings.end(); ++b)
            if (*a == *b) return false;
    return true;
}
constexpr bool bindings_below(std::initializer_list<int> bindings, int end) {
    for (int b : bindings)
        if (b < 0 || b >= end) return false;
    return true;
}
static_assert(distinct_bindings({BC_GL_TRIANGLES_BINDING, BC_GL_INFOS_BINDING, BC_GL_COUNTERS_BINDING,
                                 BC_GL_COLOURS_BINDING, BC_GL_SUMS_BINDING, BC_GL_SAMPLE_IDS_BINDING,
                                 BC_GL_CELLS_BINDING, BC_GL_PASS_SAMPLES_BINDING, BC_GL_PASS_TIMES_BINDING,
                                 BC_GL_CLASSES_BINDING, BC_GL_STATIC_LIST_BINDING, BC_GL_MOVING_LIST_BINDING,
                                 BC_GL_GROUP_SAMPLES_BINDING, BC_GL_GROUP_TIMES_BINDING, BC_GL_GROUP_IDS_BINDING,
                                 BC_GL_GROUP_DEPTHS_BINDING, BC_GL_MASK_SLOTS_BINDING,
                                 BC_GL_MASK_TRIANGLES_BINDING, BC_GL_MASK_TEXELS_BINDING}),
              "the stochastic passes' bindings");
static_assert(distinct_bindings({BC_GL_TRIANGLES_BINDING, BC_GL_INFOS_BINDING, BC_GL_COUNTERS_BINDING,
                                 BC_GL_COLOURS_BINDING, BC_GL_SUMS_BINDING, BC_GL_SAMPLE_IDS_BINDING,
                                 BC_GL_CLASSES_BINDING, BC_GL_TILE_COUNTS_BINDING, BC_GL_TILE_ENDS_BINDING,
                                 BC_GL_TILE_LIST_BINDING, BC_GL_TILE_STATE_BINDING, BC_GL_SAMPLE_KEYS_BINDING,
                                 BC_GL_STRATUM_BOXES_BINDING,
                                 BC_GL_MASK_SLOTS_BINDING,
                                 BC_GL_MASK_TRIANGLES_BINDING, BC_GL_MASK_TEXELS_BINDING}),
              "the compute pipeline's bindings");
static_assert(sizeof(TileBinState) == 32 && offsetof(TileBinState, overflow) == 12 &&
                  offsetof(TileBinState, max_count) == 16,
              "std430 TileBinState");
static_assert(distinct_bindings({BC_GL_TRIANGLES_BINDING, BC_GL_COUNTERS_BINDING, BC_GL_PASS_SAMPLES_BINDING,
                                 BC_GL_PASS_TIMES_BINDING, BC_GL_METHOD_BOXES_BINDING,
                                 BC_GL_METHOD_TUPLE_CELLS_BINDING, BC_GL_MASK_SLOTS_BINDING,
                                 BC_GL_MASK_TRIANGLES_BINDING, BC_GL_MASK_TEXELS_BINDING}),
              "the method passes' bindings");
static_assert(distinct_bindings({BC_GL_LAYER_TRIANGLES_BINDING, BC_GL_LAYER_PASS_BINDING, BC_GL_LAYER_OWN_BINDING,
                                 BC_GL_LAYER_FANS_BINDING, BC_GL_LAYER_COUNTS_BINDING, BC_GL_LAYER_DEPTH_BINDING,
                                 BC_GL_LAYER_TRIANGLE_IDS_BINDING, BC_GL_LAYER_CLUSTER_DEPTH_BINDING,
                                 BC_GL_LAYER_ORIGINS_BINDING, BC_GL_LAYER_PYRAMID_BINDING,
                                 BC_GL_LAYER_TEXEL_COUNTS_BINDING}) &&
                  bindings_below({BC_GL_LAYER_TRIANGLES_BINDING, BC_GL_LAYER_PASS_BINDING, BC_GL_LAYER_OWN_BINDING,
                                  BC_GL_LAYER_FANS_BINDING, BC_GL_LAYER_COUNTS_BINDING, BC_GL_LAYER_DEPTH_BINDING,
                                  BC_GL_LAYER_TRIANGLE_IDS_BINDING, BC_GL_LAYER_CLUSTER_DEPTH_BINDING,
                                  BC_GL_LAYER_ORIGINS_BINDING, BC_GL_LAYER_PYRAMID_BINDING,
                                  BC_GL_LAYER_TEXEL_COUNTS_BINDING},
                                 BC_GL_LAYER_BINDINGS),
              "the layer passes' bindings: distinct, each an index of GlLayerBuilder's buffers");
static_assert(distinct_bindings({BC_GL_TRACE_DEPTHS_BINDING, BC_GL_TRACE_SEGMENTS_BINDING, BC_GL_TRACE_VIEW_BINDING,
                                 BC_GL_TRACE_HITS_BINDING, BC_GL_TRACE_TRIANGLE_IDS_BINDING,
                                 BC_GL_TRACE_PYRAMID_BINDING, BC_GL_TRACE_RAYS_BINDING, BC_GL_TRACE_GROUPS_BINDING}),
              "the trace pass's bindings");
static_assert(distinct_bindings({BC_GL_TRACE_DEPTHS_BINDING, BC_GL_TRACE_SEGMENTS_BINDING, BC_GL_TRACE_VIEW_BINDING,
                                 BC_GL_TRACE_HITS_BINDING, BC_GL_TRACE_TRIANGLE_IDS_BINDING,
                                 BC_GL_TRACE_PYRAMID_BINDING, BC_GL_TRACE_RAYS_BINDING, BC_GL_TRACE_GROUPS_BINDING,
                                 BC_GL_CLUSTER_POINTS_BINDING, BC_GL_CLUSTER_LABELS_BINDING,
                                 BC_GL_CLUSTER_STATE_BINDING, BC_GL_CLUSTER_VIEWS_BINDING,
                                 BC_GL_GATHER_INDICES_BINDING, BC_GL_GROUP_SLOTS_BINDING,
                                 BC_GL_GROUP_LISTS_BINDING, BC_GL_GROUP_PAIRS_BINDING, BC_GL_GROUP_OWN_BINDING}),
              "the clustering and grouping passes' bindings, past the trace prelude's");
static_assert(distinct_bindings({BC_GL_RESOLVE_IDS_BINDING, BC_GL_RESOLVE_VERTICES_BINDING,
                                 BC_GL_RESOLVE_TRIANGLES_BINDING, BC_GL_RESOLVE_FRAME_BINDING,
                                 BC_GL_RESOLVE_COLOURS_BINDING, BC_GL_RESOLVE_COUNTS_BINDING,
                                 BC_GL_RESOLVE_RAYS_BINDING, BC_GL_CLUSTER_POINTS_BINDING}),
              "the resolve pass's bindings");
static_assert(sizeof(TriangleInfo) % 16 == 0 && sizeof(CellBounds) % 16 == 0 && sizeof(MethodBox) % 16 == 0 &&
                  sizeof(MaskTriangle) % 16 == 0 &&
                  sizeof(GpuMovingTriangle) % 16 == 0,
              "std430 array strides");

}  // namespace blurcull::frontend::gpu
#endif

#endif  // BLURCULL_GPU_LAYOUT_SHARED_H
