// Host driver of the secondary-ray clustering (Xie, Sun, Wang, JCST 28(3)
// 2013, section 3.2): reflector pixels by dodecahedron facet of their specular
// direction, then k-means by position inside each facet, then a virtual
// viewpoint per cluster. The per-pixel steps are the kernel's shared text
// (dodecahedron_facet, kmeans_nearest, cluster_sums_add, virtual_view_*), so
// a GPU pass that calls them per pixel computes the same values; only the
// loops over arrays of unknown size are here (docs/secondary-rays.md).
#pragma once

#include "kernel.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace blurcull {

struct ClusterOptions {
    // Clusters wanted in all; sets the target size ceil(pixels / wanted)
    // (cluster_target_size). The paper ends with 20 to 30.
    std::uint32_t wanted_clusters = 24;
    // Clusters per facet at most, 1 to BC_CLUSTERS_PER_FACET_MAX (the paper: 3).
    std::uint32_t max_per_facet = BC_CLUSTERS_PER_FACET_MAX;
    // Lloyd iterations per facet at most; fewer when the assignment settles.
    int max_iterations = 8;
    // Picks the first centre of every facet (kmeans_first_centre).
    std::uint32_t seed = 0x5eedu;
};

template <class Real>
struct Cluster {
    using K = kernel<Real>;
    int facet = 0;                   // dodecahedron facet, 0..11
    typename K::ClusterSums sums{};  // over its pixels, in pixel order
};

template <class Real>
struct Clustering {
    std::vector<int> cluster_of;         // per pixel: index into clusters
    std::vector<Cluster<Real>> clusters;  // by facet, then by k-means index; none empty
    int iterations = 0;                  // Lloyd iterations run, summed over facets
    int unsettled_facets = 0;            // facets stopped by max_iterations, not by a settled assignment
};

// Runs body(i) for every i in [0, count): the serial default of
// cluster_reflector_pixels's `parallel_for`. A caller's own may run the
// calls on several threads, in any order, at once: each writes its own
// outputs only.
struct SerialFor {
    template <class Body>
    void operator()(std::size_t count, const Body& body) const {
        for (std::size_t i = 0; i < count; ++i) body(i);
    }
};

namespace detail {

// The items of the chunked loops (classification, k-means assignment): many
// per call, few calls.
inline constexpr std::size_t cluster_chunk = 1u << 16;

// body(first, last) over [0, count) in chunks of cluster_chunk, by `parallel_for`.
template <class ParallelFor, class Body>
void for_chunks(const ParallelFor& parallel_for, std::size_t count, const Body& body) {
    parallel_for((count + cluster_chunk - 1) / cluster_chunk, [&](std::size_t chunk) {
        std::size_t first = chunk * cluster_chunk;
        body(first, std::min(count, first + cluster_chunk));
    });
}

// The centres of one facet's k-means start: the point the seed picks, then
// repeatedly the point farthest from the centres so far (ties: the lowest
// index). Fewer than k when the points coincide.
template <class Real>
int first_centres(const std::vector<typename kernel<Real>::vec3>& positions, const std::vector<std::size_t>& members,
                  int k, std::uint32_t seed, int facet,
                  std::array<typename kernel<Real>::vec3, BC_CLUSTERS_PER_FACET_MAX>& centres) {
    using K = kernel<Real>;
    auto count = static_cast<std::uint32_t>(members.size());
    centres[0] = positions[members[K::kmeans_first_centre(count, seed, facet)]];
    int chosen = 1;
    while (chosen < k) {
        Real farthest = Real(0);
        std::size_t pick = 0;
        for (std::size_t m : members) {
            Real d = K::bc_distance2(positions[m], centres[0]);
            for (int c = 1; c < chosen; ++c)
                d = K::min(d, K::bc_distance2(positions[m], centres[static_cast<std::size_t>(c)]));
            if (d > farthest) {
                farthest = d;
                pick = m;
            }
        }
        if (!(farthest > Real(0))) break;
        centres[static_cast<std::size_t>(chosen++)] = positions[pick];
    }
    return chosen;
}

// Lloyd's k-means on one facet's members; returns the iterations run and
// leaves each member's local cluster index in `local`; `settled` says the
// last assignment changed nothing.
// The assignment runs in chunks by `parallel_for` (each member's nearest
// centre on its own); the sums stay in member order, so the result does not
// depend on how the chunks run.
template <class Real, class ParallelFor>
int lloyd(const std::vector<typename kernel<Real>::vec3>& positions, const std::vector<std::size_t>& members,
          int k, int max_iterations, std::array<typename kernel<Real>::vec3, BC_CLUSTERS_PER_FACET_MAX>& centres,
          std::vector<int>& local, bool& settled, const ParallelFor& parallel_for) {
    using K = kernel<Real>;
    local.assign(members.size(), -1);
    int iterations = 0;
    settled = false;
    std::vector<char> chunk_changed((members.size() + cluster_chunk - 1) / cluster_chunk, 0);
    for (int it = 0; it < std::max(max_iterations, 1); ++it) {
        for_chunks(parallel_for, members.size(), [&](std::size_t first, std::size_t last) {
            bool changed = false;
            for (std::size_t i = first; i < last; ++i) {
                int c = K::kmeans_nearest(positions[members[i]], centres.data(), k);
                changed = changed || c != local[i];
                local[i] = c;
            }
            chunk_changed[first / cluster_chunk] = changed ? 1 : 0;
        });
        bool changed = std::find(chunk_changed.begin(), chunk_changed.end(), char(1)) != chunk_changed.end();
        ++iterations;
        if (!changed) {
            settled = true;
            break;
        }
        std::array<typename K::ClusterSums, BC_CLUSTERS_PER_FACET_MAX> sums;
        sums.fill(K::cluster_sums_empty());
        for (std::size_t i = 0; i < members.size(); ++i) {
            auto& s = sums[static_cast<std::size_t>(local[i])];
            s = K::cluster_sums_add(s, positions[members[i]], typename K::vec3(Real(0)));
        }
        // An emptied cluster keeps its centre (it stays empty and is dropped).
        for (int c = 0; c < k; ++c)
            if (sums[static_cast<std::size_t>(c)].count > 0u)
                centres[static_cast<std::size_t>(c)] = K::cluster_mean_position(sums[static_cast<std::size_t>(c)]);
    }
    return iterations;
}

}  // namespace detail

// Clusters of reflector pixels: positions (scene units) and unit specular
// directions, one each per pixel. Deterministic: the same input and options
// give the same clusters on every run, whatever `parallel_for` (SerialFor,
// or the caller's threads: the facet of each pixel and each k-means
// assignment are computed by it in chunks, every sum in pixel order). Each
// facet's pixel count n gets clusters_for_facet(n, cluster_target_size(total,
// wanted), max_per_facet) clusters; k-means by position then splits it (at
// most max_iterations Lloyd iterations). Empty input gives no clusters.
template <class Real, class ParallelFor = SerialFor>
Clustering<Real> cluster_reflector_pixels(const std::vector<typename kernel<Real>::vec3>& positions,
                                          const std::vector<typename kernel<Real>::vec3>& directions,
                                          const ClusterOptions& options = {}, const ParallelFor& parallel_for = {}) {
    using K = kernel<Real>;
    Clustering<Real> out;
    std::size_t n = std::min(positions.size(), directions.size());
    out.cluster_of.assign(n, -1);
    std::vector<std::uint8_t> facet_of(n);
    detail::for_chunks(parallel_for, n, [&](std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i)
            facet_of[i] = static_cast<std::uint8_t>(K::dodecahedron_facet(directions[i]));
    });
    std::array<std::vector<std::size_t>, BC_DODECAHEDRON_FACES> members;
    for (std::size_t i = 0; i < n; ++i) members[facet_of[i]].push_back(i);
    std::uint32_t target = K::cluster_target_size(static_cast<std::uint32_t>(n), options.wanted_clusters);
    std::vector<int> local;
    for (int facet = 0; facet < BC_DODECAHEDRON_FACES; ++facet) {
        const auto& m = members[static_cast<std::size_t>(facet)];
        auto pixels = static_cast<std::uint32_t>(m.size());
        auto k = static_cast<int>(K::clusters_for_facet(pixels, target, options.max_per_facet));
        if (k == 0) continue;
        std::array<typename K::vec3, BC_CLUSTERS_PER_FACET_MAX> centres{};
        k = detail::first_centres<Real>(positions, m, k, options.seed, facet, centres);
        bool settled = false;
        out.iterations +=
            detail::lloyd<Real>(positions, m, k, options.max_iterations, centres, local, settled, parallel_for);
        if (!settled) ++out.unsettled_facets;
        // Final sums in pixel order; empty clusters dropped, the rest numbered in order.
        std::array<typename K::ClusterSums, BC_CLUSTERS_PER_FACET_MAX> sums;
        sums.fill(K::cluster_sums_empty());
        for (std::size_t i = 0; i < m.size(); ++i) {
            auto& s = sums[static_cast<std::size_t>(local[i])];
            s = K::cluster_sums_add(s, positions[m[i]], directions[m[i]]);
        }
        std::array<int, BC_CLUSTERS_PER_FACET_MAX> global{};
        for (int c = 0; c < k; ++c) {
            const auto& s = sums[static_cast<std::size_t>(c)];
            global[static_cast<std::size_t>(c)] = static_cast<int>(out.clusters.size());
            if (s.count > 0u) out.clusters.push_back({facet, s});
        }
        for (std::size_t i = 0; i < m.size(); ++i) out.cluster_of[m[i]] = global[static_cast<std::size_t>(local[i])];
    }
    return out;
}

// The virtual viewpoint of one cluster (virtual_view_begin/add/finish over
// its pixels in order). tan_half_fov = tan(fov / 2), min_near > 0 in scene
// units; check the result's flags (BC_VIEW_*).
template <class Real>
typename kernel<Real>::VirtualView fit_virtual_view(const typename kernel<Real>::ClusterSums& sums,
                                                     const std::vector<typename kernel<Real>::vec3>& positions,
                                                     const std::vector<typename kernel<Real>::vec3>& directions,
                                                     Real tan_half_fov, Real min_near) {
    using K = kernel<Real>;
    typename K::VirtualViewFit fit = K::virtual_view_begin(sums, tan_half_fov, min_near);
    std::size_t n = std::min(positions.size(), directions.size());
    for (std::size_t i = 0; i < n; ++i) fit = K::virtual_view_add(fit, positions[i], directions[i]);
    return K::virtual_view_finish(fit);
}

}  // namespace blurcull
