// Shared C++/GLSL text (see dialect.hpp): the per-point steps of clustering
// reflector pixels (Xie, Sun, Wang 2013, section 3.2): each pixel's specular
// direction picks a dodecahedron facet, then k-means by position splits each
// facet into 1 to BC_CLUSTERS_PER_FACET_MAX clusters. The loop over a
// facet's pixels is the caller's (include/blurcull/secondary_clusters.hpp on
// the host; a compute pass per step on the GPU), because the bodies cannot
// declare buffers of unknown size (docs/secondary-rays.md, "Clusters").

#define BC_CLUSTERS_PER_FACET_MAX 3

// Cluster sums are exact (docs/secondary-rays.md, "Exact sums"): every
// coordinate is added as a fixed-point integer into 64 bits, a signed high
// word and an unsigned low word. Integer sums do not depend on their order,
// so sums split over threads or GPU work groups (atomics on the two words)
// and merged give the same bits as one loop, on every backend; only the
// means round. A position coordinate is scaled by a power of two,
// position_scale (cluster_position_scale of the largest |coordinate|, so
// at most 2^30 after scaling), a direction's by 2^30; the fraction is cut
// off. Exact for fewer than 2^32 points.
#define BC_CLUSTER_DIRECTION_ONE 1073741824.0
// A scaled coordinate beyond this (2^31 - 128), or one not finite, does
// not fit: its point is not summed, only counted (ClusterSums.unfit).
#define BC_CLUSTER_FIXED_LIMIT 2147483520.0

// Sums over a cluster's pixels: positions (scene units), unit specular
// directions, pixel count.
struct ClusterSums {
    ivec3 position_hi;   // sum of the scaled positions: high words
    uvec3 position_lo;   // and low words
    ivec3 direction_hi;  // sum of the scaled directions
    uvec3 direction_lo;
    uint count;           // points summed
    uint unfit;           // points not summed: a coordinate not finite or out of range
    real position_scale;  // a power of two
};

// The scale of position coordinates up to `largest` in magnitude: the power
// of two 2^(30 - e) where largest < 2^e (e clamped to [-90, 90]); 2^30 for
// 0 or a value that is not finite. Exact (frexp, ldexp).
BC_FN real cluster_position_scale(real largest) {
    int e = 0;
    frexp(bc_finite(largest) ? abs(largest) : real(0), e);
    return ldexp(real(1), 30 - clamp(e, -90, 90));
}

// Sums over no pixel, positions to be scaled by `position_scale`.
BC_FN ClusterSums cluster_sums_empty(real position_scale) {
    ClusterSums s;
    s.position_hi = ivec3(0);
    s.position_lo = uvec3(0u);
    s.direction_hi = ivec3(0);
    s.direction_lo = uvec3(0u);
    s.count = 0u;
    s.unfit = 0u;
    s.position_scale = position_scale;
    return s;
}

// The fixed-point integer of an already scaled coordinate `x` (the fraction
// cut off); 0 with `fits` cleared when it does not fit.
BC_FN int bc_fixed(real x, BC_INOUT(bool) fits) {
    if (!(abs(x) <= real(BC_CLUSTER_FIXED_LIMIT))) {
        fits = false;
        return 0;
    }
    return int(x);
}

// The fixed-point terms of one point, as cluster_sums_add adds them (a GPU
// pass adds them with atomics on the words): false when the point does not
// fit (then it counts in unfit only).
BC_FN bool cluster_fixed_terms(vec3 position, vec3 direction, real position_scale, BC_OUT(ivec3) p, BC_OUT(ivec3) d) {
    bool fits = true;
    p = ivec3(bc_fixed(position.x * position_scale, fits), bc_fixed(position.y * position_scale, fits),
              bc_fixed(position.z * position_scale, fits));
    real one = real(BC_CLUSTER_DIRECTION_ONE);
    d = ivec3(bc_fixed(direction.x * one, fits), bc_fixed(direction.y * one, fits), bc_fixed(direction.z * one, fits));
    return fits;
}

// (hi, lo) + q, 64-bit two's complement: the low word's carry and q's sign
// go to the high word.
BC_FN void bc_fixed_add(BC_INOUT(int) hi, BC_INOUT(uint) lo, int q) {
    uint sum = lo + uint(q);
    hi = hi + (sum < lo ? 1 : 0) + (q < 0 ? -1 : 0);
    lo = sum;
}

// (hi, lo) + (hi2, lo2).
BC_FN void bc_fixed_merge(BC_INOUT(int) hi, BC_INOUT(uint) lo, int hi2, uint lo2) {
    uint sum = lo + lo2;
    hi = hi + hi2 + (sum < lo ? 1 : 0);
    lo = sum;
}

// The value of a 64-bit sum (rounded once to real, then once more when added).
BC_FN real bc_fixed_value(int hi, uint lo) {
    return real(hi) * real(4294967296.0) + real(lo);
}

BC_FN vec3 bc_fixed_vec3(ivec3 hi, uvec3 lo) {
    return vec3(bc_fixed_value(hi.x, lo.x), bc_fixed_value(hi.y, lo.y), bc_fixed_value(hi.z, lo.z));
}

// `s` with one more pixel at `position` whose specular direction is
// `direction` (unit length expected; summed as given).
BC_FN ClusterSums cluster_sums_add(BC_IN(ClusterSums) s, vec3 position, vec3 direction) {
    ClusterSums r = s;
    ivec3 p = ivec3(0);
    ivec3 d = ivec3(0);
    if (!cluster_fixed_terms(position, direction, s.position_scale, p, d)) {
        r.unfit = r.unfit + 1u;
        return r;
    }
    bc_fixed_add(r.position_hi.x, r.position_lo.x, p.x);
    bc_fixed_add(r.position_hi.y, r.position_lo.y, p.y);
    bc_fixed_add(r.position_hi.z, r.position_lo.z, p.z);
    bc_fixed_add(r.direction_hi.x, r.direction_lo.x, d.x);
    bc_fixed_add(r.direction_hi.y, r.direction_lo.y, d.y);
    bc_fixed_add(r.direction_hi.z, r.direction_lo.z, d.z);
    r.count = r.count + 1u;
    return r;
}

// The sums over the pixels of `a` and of `b` (of one position_scale): exact,
// so any split of the pixels merged in any order gives one loop's bits.
BC_FN ClusterSums cluster_sums_merge(BC_IN(ClusterSums) a, BC_IN(ClusterSums) b) {
    ClusterSums r = a;
    bc_fixed_merge(r.position_hi.x, r.position_lo.x, b.position_hi.x, b.position_lo.x);
    bc_fixed_merge(r.position_hi.y, r.position_lo.y, b.position_hi.y, b.position_lo.y);
    bc_fixed_merge(r.position_hi.z, r.position_lo.z, b.position_hi.z, b.position_lo.z);
    bc_fixed_merge(r.direction_hi.x, r.direction_lo.x, b.direction_hi.x, b.direction_lo.x);
    bc_fixed_merge(r.direction_hi.y, r.direction_lo.y, b.direction_hi.y, b.direction_lo.y);
    bc_fixed_merge(r.direction_hi.z, r.direction_lo.z, b.direction_hi.z, b.direction_lo.z);
    r.count = a.count + b.count;
    r.unfit = a.unfit + b.unfit;
    return r;
}

// Mean position of the pixels summed in `s`; the zero vector for no pixel.
BC_FN vec3 cluster_mean_position(BC_IN(ClusterSums) s) {
    if (s.count == 0u) return vec3(real(0));
    return bc_fixed_vec3(s.position_hi, s.position_lo) / real(s.count) / s.position_scale;
}

// Sum of the specular directions summed in `s` (its direction is their mean's).
BC_FN vec3 cluster_direction_sum(BC_IN(ClusterSums) s) {
    return bc_fixed_vec3(s.direction_hi, s.direction_lo) / real(BC_CLUSTER_DIRECTION_ONE);
}

// Target pixel count of one cluster: ceil(total_pixels / wanted_clusters),
// at least 1 (wanted_clusters 0 counts as 1). The paper has 20 to 30
// clusters in all; wanted_clusters is that total.
BC_FN uint cluster_target_size(uint total_pixels, uint wanted_clusters) {
    uint wanted = max(wanted_clusters, 1u);
    uint size = total_pixels / wanted + (total_pixels % wanted != 0u ? 1u : 0u);
    return max(size, 1u);
}

// How many clusters a facet of `facet_pixels` pixels gets: the k in
// [1, max_clusters] whose cluster size facet_pixels / k is nearest
// target_size, i.e. round(facet_pixels / target_size) with halves rounded
// up, clamped to [1, min(max_clusters, facet_pixels)]; 0 for an empty facet.
// max_clusters is clamped to [1, BC_CLUSTERS_PER_FACET_MAX]; target_size 0
// counts as 1. Integer arithmetic only, so every backend agrees.
BC_FN uint clusters_for_facet(uint facet_pixels, uint target_size, uint max_clusters) {
    if (facet_pixels == 0u) return 0u;
    uint target = max(target_size, 1u);
    uint most = min(max(max_clusters, 1u), uint(BC_CLUSTERS_PER_FACET_MAX));
    uint rest = facet_pixels % target;
    uint k = facet_pixels / target + (rest >= target - rest ? 1u : 0u);
    return min(max(k, 1u), min(most, facet_pixels));
}

// Squared distance between two positions (summed x, y, z in that order).
BC_FN real bc_distance2(vec3 a, vec3 b) {
    vec3 d = a - b;
    return bc_dot3(d, d);
}

// The k-means assignment step: index of the centre nearest `position` among
// centres[0 .. count - 1] (count clamped to [1, BC_CLUSTERS_PER_FACET_MAX]);
// on equal distances the lowest index wins. A NaN position goes to 0.
BC_FN int kmeans_nearest(vec3 position, vec3 centres[BC_CLUSTERS_PER_FACET_MAX], int count) {
    int n = min(max(count, 1), BC_CLUSTERS_PER_FACET_MAX);
    int best = 0;
    real best_d = bc_distance2(position, centres[0]);
    for (int k = 1; k < n; ++k) {
        real d = bc_distance2(position, centres[k]);
        if (d < best_d) {
            best = k;
            best_d = d;
        }
    }
    return best;
}

// The key of pixel `index` (its place in the input) in the choice of a
// facet's first k-means centre: the facet's pixel of least key (ties: the
// lowest index) starts, so the start is fixed by the seed and found by a
// minimum over the pixels in any order. The host driver takes the other
// centres by farthest point.
BC_FN uint kmeans_start_key(uint seed, int facet, uint index) {
    return bc_hash3(seed, uint(facet), index);
}
