// Shared C++/GLSL text (see dialect.hpp): the per-point steps of clustering
// reflector pixels (Xie, Sun, Wang 2013, section 3.2): each pixel's specular
// direction picks a dodecahedron facet, then k-means by position splits each
// facet into 1 to BC_CLUSTERS_PER_FACET_MAX clusters. The loop over a
// facet's pixels is the caller's (include/blurcull/secondary_clusters.hpp on
// the host; a compute pass per step on the GPU), because the bodies cannot
// declare buffers of unknown size (docs/secondary-rays.md, "Clusters").

#define BC_CLUSTERS_PER_FACET_MAX 3

// Running sums over a cluster's pixels: positions (scene units), unit
// specular directions, pixel count.
struct ClusterSums {
    vec3 position;
    vec3 direction;
    uint count;
};

// Sums over no pixel.
BC_FN ClusterSums cluster_sums_empty() {
    ClusterSums s;
    s.position = vec3(real(0));
    s.direction = vec3(real(0));
    s.count = 0u;
    return s;
}

// `s` with one more pixel at `position` whose specular direction is
// `direction` (unit length expected; it is summed as given). Sums taken in
// the same order give the same bits on every backend.
BC_FN ClusterSums cluster_sums_add(BC_IN(ClusterSums) s, vec3 position, vec3 direction) {
    ClusterSums r;
    r.position = s.position + position;
    r.direction = s.direction + direction;
    r.count = s.count + 1u;
    return r;
}

// Mean position of the pixels summed in `s`; the zero vector for no pixel.
BC_FN vec3 cluster_mean_position(BC_IN(ClusterSums) s) {
    if (s.count == 0u) return vec3(real(0));
    return s.position / real(s.count);
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

// Index of the first k-means centre of a facet with `count` pixels (0 for
// none): a hash of (seed, facet, count), so the start is fixed by the seed.
// The host driver takes the others by farthest point.
BC_FN uint kmeans_first_centre(uint count, uint seed, int facet) {
    if (count == 0u) return 0u;
    return bc_hash3(seed, uint(facet), count) % count;
}
