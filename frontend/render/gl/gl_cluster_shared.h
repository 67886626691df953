// The state of dof-secondary's clustering on the GPU (gl_clustering.cpp,
// shaders/render_secondary_cluster.comp), written once for C++ and GLSL
// (std430) in the style of gpu_layout_shared.h: 4-byte scalars and arrays
// of them only (array stride 4 in std430), so the C++ struct has the same
// offsets; the C++ side checks them with static_assert.
// docs/secondary-rays.md, "Clusters on the GPU".
#ifndef BLURCULL_GL_CLUSTER_SHARED_H
#define BLURCULL_GL_CLUSTER_SHARED_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>

namespace blurcull::frontend::gpu {
using uint = std::uint32_t;
#endif

// The pass's step (uniform `step`): per ray or per facet (one work group).
#define BC_CLUSTER_STEP_CLASSIFY 0     // per ray: its facet; facet counts, largest |coordinate|
#define BC_CLUSTER_STEP_SETUP 1        // per facet: k (clusters_for_facet), the position scale
#define BC_CLUSTER_STEP_START_KEY 2    // per ray: least kmeans_start_key of its facet
#define BC_CLUSTER_STEP_START_RAY 3    // per ray: the least ray of that key
#define BC_CLUSTER_STEP_PICK 4         // per facet: the picked ray becomes a centre
#define BC_CLUSTER_STEP_FAR_DISTANCE 5 // per ray: the greatest distance to its facet's centres
#define BC_CLUSTER_STEP_FAR_RAY 6      // per ray: the least ray at that distance
#define BC_CLUSTER_STEP_ASSIGN 7       // per ray: Lloyd's assignment, its position summed
#define BC_CLUSTER_STEP_UPDATE 8       // per facet: settled, or the means become the centres
#define BC_CLUSTER_STEP_FINAL_SUMS 9   // per ray: its cluster's sums, positions and directions
#define BC_CLUSTER_STEP_VIEW_BEGIN 10  // per slot: its two fits begun (virtual_view_begin, _begin_along)
#define BC_CLUSTER_STEP_VIEW_ADD 11    // per ray: virtual_view_add of both, combined by max, min and or
#define BC_CLUSTER_STEP_VIEW_FINISH 12 // per slot: virtual_view_finish of both

// ClusterState.facet_flags bits.
#define BC_CLUSTER_CHANGED 1u  // an assignment of this iteration changed
#define BC_CLUSTER_SETTLED 2u  // an iteration changed nothing: Lloyd stopped

#define BC_CLUSTER_FACETS 12
// A facet's clusters are slots facet * BC_CLUSTERS_PER_FACET_MAX + local.
#define BC_CLUSTER_SLOTS 36
// Each slot's sums: 6 words of each kind (position xyz, direction xyz).
#define BC_CLUSTER_SUM_WORDS 216
// Rays per invocation of the per-ray steps (the sums taken in its registers,
// then added to the slots).
#define BC_CLUSTER_RUN 16
// A ray's label before its first assignment: local cluster 3 (none).
#define BC_CLUSTER_NO_LOCAL 3u

struct ClusterState {
    uint largest_bits;     // the largest finite |position coordinate| (float bits; atomicMax)
    float position_scale;  // cluster_position_scale(largest)
    uint facet_count[BC_CLUSTER_FACETS];      // rays per facet
    int facet_k[BC_CLUSTER_FACETS];           // clusters_for_facet, then the centres found
    int facet_chosen[BC_CLUSTER_FACETS];      // centres picked so far
    uint facet_flags[BC_CLUSTER_FACETS];      // BC_CLUSTER_*
    int facet_iterations[BC_CLUSTER_FACETS];  // Lloyd iterations run
    uint pick_key[BC_CLUSTER_FACETS];         // the pick's least start key or greatest distance (float bits)
    uint pick_ray[BC_CLUSTER_FACETS];         // and its least ray
    float centres[3 * BC_CLUSTER_SLOTS];      // slot * 3 + axis
    int sum_hi[BC_CLUSTER_SUM_WORDS];         // slot * 6 + word: ClusterSums' high words
    uint sum_lo[BC_CLUSTER_SUM_WORDS];        // and low words
    uint sum_count[BC_CLUSTER_SLOTS];
    uint sum_unfit[BC_CLUSTER_SLOTS];
};

// One fit of a slot's virtual view (fits[2 * slot]: along the mean
// direction; fits[2 * slot + 1]: along the facet's normal, what the host
// fits when the first leaves a direction outside): VirtualViewFit's fields
// as virtual_view_begin set them, the running maxima, minimum and flags of
// virtual_view_add over the slot's rays (each field of the fold is one of
// those, so the rays may come in any order), and the finished view's own
// fields (its basis and tan are the fit's).
struct ClusterViewFit {
    float origin[3];
    float forward[3];
    float right[3];
    float up[3];
    float tan_half_fov;
    float min_near;
    int begin_flags;
    uint backoff_bits;    // max over the rays (non-negative float bits)
    uint depth_min_key;   // min over the rays (bc_float_order of the depth)
    uint magnitude_bits;  // max over the rays (non-negative float bits)
    int add_flags;        // or over the rays
    float eye[3];
    float near;
    float backoff;
    int flags;
};

// The grouping pass's step (render_secondary_group.comp, uniform `step`).
#define BC_GROUP_STEP_RAYS 0        // per ray: own triangle, widest cosine; a pixel's first ray lists its run
#define BC_GROUP_STEP_RUNS 1        // per listed run: its groups sorted and listed in their slots
#define BC_GROUP_STEP_THRESHOLDS 2  // per slot: the normal cone's threshold
// The most rays one pixel spawns per sample (a dielectric: reflected and refracted).
#define BC_GROUP_RAYS_PER_SAMPLE 2
// A ray's key word (the direction's w in Points): pixel << BC_GROUP_PART_BITS | lens part.
#define BC_GROUP_PART_BITS 4u

// One slot's rays as the grouping pass sorts them (gl_clustering.cpp,
// GlClustering::group): where its list starts and how many rays it holds
// (the host's, from the clustering's counts), the list and groups filled so
// far (atomics), its chosen view's forward axis, the least cosine of a ray
// to it (bc_float_order bits; atomicMin) and the normal cone's threshold
// made from it (cluster_culls' rule, bc_normal_cone_threshold).
struct ClusterSlotGroups {
    uint first;
    uint rays;
    uint filled;
    uint groups;
    float forward[3];
    uint cos_key;
    float normal_threshold;
};

#ifndef __cplusplus
// A float's bits as a key that orders as the floats do, negative ones
// included (NaN apart): the sign bit flipped for positive floats, every bit
// for negative ones; for atomicMin and atomicMax of floats.
uint bc_float_order(float x) {
    uint bits = floatBitsToUint(x);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

float bc_float_of_order(uint key) {
    return uintBitsToFloat((key & 0x80000000u) != 0u ? key & 0x7fffffffu : ~key);
}
#endif

#ifdef __cplusplus
static_assert(sizeof(ClusterSlotGroups) == 9 * 4 && offsetof(ClusterSlotGroups, groups) == 12 &&
                  offsetof(ClusterSlotGroups, normal_threshold) == 32,
              "ClusterSlotGroups: std430 offsets");
static_assert(sizeof(ClusterViewFit) == 25 * 4 && offsetof(ClusterViewFit, backoff_bits) == 60 &&
                  offsetof(ClusterViewFit, eye) == 76,
              "ClusterViewFit: std430 offsets");
static_assert(offsetof(ClusterState, facet_count) == 8 && offsetof(ClusterState, centres) == 8 + 7 * 48 &&
                  offsetof(ClusterState, sum_hi) == 8 + 7 * 48 + 432 &&
                  sizeof(ClusterState) == 8 + 7 * 48 + 432 + 2 * 864 + 2 * 144,
              "ClusterState: std430 offsets");
}  // namespace blurcull::frontend::gpu
#endif

#endif  // BLURCULL_GL_CLUSTER_SHARED_H
