// Host driver of the secondary-ray clustering (Xie, Sun, Wang, JCST 28(3)
// 2013, section 3.2): reflector pixels by dodecahedron facet of their specular
// direction, then k-means by position inside each facet, then a virtual
// viewpoint per cluster. The per-pixel steps are the kernel's shared text
// (dodecahedron_facet, kmeans_start_key, kmeans_nearest, cluster_sums_add,
// virtual_view_*), and every sum is exact, so a GPU pass that calls them per
// pixel computes the same clusters; only the loops over arrays of unknown
// size are here (docs/secondary-rays.md).
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
    // Picks the first centre of every facet (kmeans_start_key).
    std::uint32_t seed = 0x5eedu;
};

template <class Real>
struct Cluster {
    using K = kernel<Real>;
    int facet = 0;                   // dodecahedron facet, 0..11
    typename K::ClusterSums sums{};  // over its pixels (exact)
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

// The items of the chunked loops (classification, k-means steps, sums): many
// per call, few calls.
inline constexpr std::size_t cluster_chunk = 1u << 16;

inline std::size_t chunk_count(std::size_t count) { return (count + cluster_chunk - 1) / cluster_chunk; }

// body(first, last) over [0, count) in chunks of cluster_chunk, by `parallel_for`.
template <class ParallelFor, class Body>
void for_chunks(const ParallelFor& parallel_for, std::size_t count, const Body& body) {
    parallel_for(chunk_count(count), [&](std::size_t chunk) {
        std::size_t first = chunk * cluster_chunk;
        body(first, std::min(count, first + cluster_chunk));
    });
}

// The largest finite |coordinate| of the positions (0 for none).
template <class Real, class ParallelFor>
Real largest_coordinate(const std::vector<typename kernel<Real>::vec3>& positions, std::size_t n,
                        const ParallelFor& parallel_for) {
    using K = kernel<Real>;
    std::vector<Real> chunk_largest(chunk_count(n), Real(0));
    for_chunks(parallel_for, n, [&](std::size_t first, std::size_t last) {
        Real largest = Real(0);
        for (std::size_t i = first; i < last; ++i)
            for (int a = 0; a < 3; ++a)
                if (K::bc_finite(positions[i][a])) largest = std::max(largest, std::abs(positions[i][a]));
        chunk_largest[first / cluster_chunk] = largest;
    });
    Real largest = Real(0);
    for (Real l : chunk_largest) largest = std::max(largest, l);
    return largest;
}

// A pick among a facet's members: the best value so far and its pixel.
template <class Real>
struct Pick {
    Real value;
    std::size_t pixel;
};

// The member whose value(pixel) is least (`least`) or greatest, ties to the
// lowest pixel; the chunks' picks merged in member order (members ascend),
// so any run of the chunks picks the same. `none`: the pick of no member.
template <class Real, class ParallelFor, class Value>
Pick<Real> pick_member(const std::vector<std::size_t>& members, bool least, Pick<Real> none, const Value& value,
                       const ParallelFor& parallel_for) {
    auto better = [least](Real a, Real b) { return least ? a < b : a > b; };
    std::vector<Pick<Real>> chunk_pick(chunk_count(members.size()), none);
    for_chunks(parallel_for, members.size(), [&](std::size_t first, std::size_t last) {
        Pick<Real> pick = none;
        for (std::size_t i = first; i < last; ++i) {
            Real v = value(members[i]);
            if (better(v, pick.value)) pick = {v, members[i]};
        }
        chunk_pick[first / cluster_chunk] = pick;
    });
    Pick<Real> pick = none;
    for (const Pick<Real>& p : chunk_pick)
        if (better(p.value, pick.value)) pick = p;
    return pick;
}

// The centres of one facet's k-means start: the member of least
// kmeans_start_key, then repeatedly the member farthest from the centres so
// far (ties: the lowest index). Fewer than k when the points coincide.
template <class Real, class ParallelFor>
int first_centres(const std::vector<typename kernel<Real>::vec3>& positions, const std::vector<std::size_t>& members,
                  int k, std::uint32_t seed, int facet,
                  std::array<typename kernel<Real>::vec3, BC_CLUSTERS_PER_FACET_MAX>& centres,
                  const ParallelFor& parallel_for) {
    using K = kernel<Real>;
    // Keys are 32-bit: exact in double.
    Pick<double> start = pick_member<double>(
        members, true, {4294967296.0, 0},
        [&](std::size_t m) { return double(K::kmeans_start_key(seed, facet, static_cast<std::uint32_t>(m))); },
        parallel_for);
    centres[0] = positions[start.pixel];
    int chosen = 1;
    while (chosen < k) {
        Pick<Real> far = pick_member<Real>(
            members, false, {Real(0), 0},
            [&](std::size_t m) {
                Real d = K::bc_distance2(positions[m], centres[0]);
                for (int c = 1; c < chosen; ++c)
                    d = K::min(d, K::bc_distance2(positions[m], centres[static_cast<std::size_t>(c)]));
                return d;
            },
            parallel_for);
        if (!(far.value > Real(0))) break;
        centres[static_cast<std::size_t>(chosen++)] = positions[far.pixel];
    }
    return chosen;
}

// A cluster's exact sums in 64-bit integers: the kernel's fixed-point
// terms (cluster_fixed_terms) added as the kernel's two 32-bit words would
// add them (integer sums are the same in any grouping), in one machine add
// each; sums() gives the kernel's ClusterSums.
template <class Real>
struct FixedSums {
    using K = kernel<Real>;
    std::array<std::int64_t, 6> total{};  // position xyz, direction xyz
    std::uint32_t count = 0, unfit = 0;

    void add(const typename K::vec3& position, const typename K::vec3& direction, Real scale) {
        glm::ivec3 p(0), d(0);
        if (!K::cluster_fixed_terms(position, direction, scale, p, d)) {
            ++unfit;
            return;
        }
        for (int a = 0; a < 3; ++a) {
            total[static_cast<std::size_t>(a)] += p[a];
            total[static_cast<std::size_t>(3 + a)] += d[a];
        }
        ++count;
    }
    void merge(const FixedSums& other) {
        for (std::size_t w = 0; w < total.size(); ++w) total[w] += other.total[w];
        count += other.count;
        unfit += other.unfit;
    }
    typename K::ClusterSums sums(Real scale) const {
        typename K::ClusterSums s = K::cluster_sums_empty(scale);
        for (int a = 0; a < 3; ++a) {
            const auto position = static_cast<std::uint64_t>(total[static_cast<std::size_t>(a)]);
            const auto direction = static_cast<std::uint64_t>(total[static_cast<std::size_t>(3 + a)]);
            s.position_hi[a] = static_cast<std::int32_t>(static_cast<std::uint32_t>(position >> 32));
            s.position_lo[a] = static_cast<std::uint32_t>(position);
            s.direction_hi[a] = static_cast<std::int32_t>(static_cast<std::uint32_t>(direction >> 32));
            s.direction_lo[a] = static_cast<std::uint32_t>(direction);
        }
        s.count = count;
        s.unfit = unfit;
        return s;
    }
};

// The exact sums of each local cluster of one facet's members (member i in
// local[i]), by chunks merged (any order gives the same bits).
template <class Real, class ParallelFor>
std::array<typename kernel<Real>::ClusterSums, BC_CLUSTERS_PER_FACET_MAX> local_sums(
    const std::vector<typename kernel<Real>::vec3>& positions, const std::vector<typename kernel<Real>::vec3>& directions,
    const std::vector<std::size_t>& members, const std::vector<int>& local, Real scale, const ParallelFor& parallel_for) {
    using Sums = std::array<FixedSums<Real>, BC_CLUSTERS_PER_FACET_MAX>;
    std::vector<Sums> chunk_sums(chunk_count(members.size()));
    for_chunks(parallel_for, members.size(), [&](std::size_t first, std::size_t last) {
        Sums& sums = chunk_sums[first / cluster_chunk];
        for (std::size_t i = first; i < last; ++i)
            sums[static_cast<std::size_t>(local[i])].add(positions[members[i]], directions[members[i]], scale);
    });
    Sums sums;
    for (const Sums& chunk : chunk_sums)
        for (std::size_t c = 0; c < sums.size(); ++c) sums[c].merge(chunk[c]);
    std::array<typename kernel<Real>::ClusterSums, BC_CLUSTERS_PER_FACET_MAX> out;
    for (std::size_t c = 0; c < sums.size(); ++c) out[c] = sums[c].sums(scale);
    return out;
}

// Lloyd's k-means on one facet's members; returns the iterations run and
// leaves each member's local cluster index in `local`; `settled` says the
// last assignment changed nothing. Each step runs in chunks by
// `parallel_for`; the result does not depend on how the chunks run.
template <class Real, class ParallelFor>
int lloyd(const std::vector<typename kernel<Real>::vec3>& positions,
          const std::vector<typename kernel<Real>::vec3>& directions, const std::vector<std::size_t>& members, int k,
          int max_iterations, Real scale, std::array<typename kernel<Real>::vec3, BC_CLUSTERS_PER_FACET_MAX>& centres,
          std::vector<int>& local, bool& settled, const ParallelFor& parallel_for) {
    using K = kernel<Real>;
    local.assign(members.size(), -1);
    int iterations = 0;
    settled = false;
    std::vector<char> chunk_changed(chunk_count(members.size()), 0);
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
        const auto sums = local_sums<Real>(positions, directions, members, local, scale, parallel_for);
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
// or the caller's threads: every step runs in chunks of pixels, and its
// sums are exact, so they do not depend on the order). A GPU build that
// runs the same steps (render/gl/gl_clustering.hpp) gets the same clusters.
// Each facet's pixel count n gets clusters_for_facet(n,
// cluster_target_size(total, wanted), max_per_facet) clusters; k-means by
// position then splits it (at most max_iterations Lloyd iterations). Empty
// input gives no clusters.
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
    const Real scale = K::cluster_position_scale(detail::largest_coordinate<Real>(positions, n, parallel_for));
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
        k = detail::first_centres<Real>(positions, m, k, options.seed, facet, centres, parallel_for);
        bool settled = false;
        out.iterations += detail::lloyd<Real>(positions, directions, m, k, options.max_iterations, scale, centres, local,
                                              settled, parallel_for);
        if (!settled) ++out.unsettled_facets;
        // Final sums; empty clusters dropped, the rest numbered in order.
        const auto sums = detail::local_sums<Real>(positions, directions, m, local, scale, parallel_for);
        std::array<int, BC_CLUSTERS_PER_FACET_MAX> global{};
        for (int c = 0; c < k; ++c) {
            const auto& s = sums[static_cast<std::size_t>(c)];
            global[static_cast<std::size_t>(c)] = static_cast<int>(out.clusters.size());
            if (s.count + s.unfit > 0u) out.clusters.push_back({facet, s});
        }
        for (std::size_t i = 0; i < m.size(); ++i) out.cluster_of[m[i]] = global[static_cast<std::size_t>(local[i])];
    }
    return out;
}

// The exact sums of the points (positions, directions), positions scaled
// for their largest |coordinate|: one cluster's sums for fit_virtual_view.
template <class Real>
typename kernel<Real>::ClusterSums cluster_sums_of(const std::vector<typename kernel<Real>::vec3>& positions,
                                                   const std::vector<typename kernel<Real>::vec3>& directions) {
    using K = kernel<Real>;
    std::size_t n = std::min(positions.size(), directions.size());
    typename K::ClusterSums sums =
        K::cluster_sums_empty(K::cluster_position_scale(detail::largest_coordinate<Real>(positions, n, SerialFor{})));
    for (std::size_t i = 0; i < n; ++i) sums = K::cluster_sums_add(sums, positions[i], directions[i]);
    return sums;
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

// Each cluster's two virtual views, as the dof-secondary renderer fits
// them: along the cluster's mean direction (virtual_view_begin), and along
// its facet's normal (virtual_view_begin_along with dodecahedron_normal),
// which holds every direction of the facet from 74.76 degrees and is the
// view to take when the first has BC_VIEW_DIRECTION_OUTSIDE.
template <class Real>
struct ClusterViews {
    std::vector<typename kernel<Real>::VirtualView> along_mean, along_normal;
};

namespace detail {

// Two partial folds of virtual_view_add from one begun fit, as one: each
// field the fold changes is a maximum, a minimum or an or.
template <class Real>
typename kernel<Real>::VirtualViewFit merge_fits(typename kernel<Real>::VirtualViewFit a,
                                                 const typename kernel<Real>::VirtualViewFit& b) {
    a.backoff = std::max(a.backoff, b.backoff);
    a.depth_min = std::min(a.depth_min, b.depth_min);
    a.magnitude = std::max(a.magnitude, b.magnitude);
    a.flags |= b.flags;
    return a;
}

}  // namespace detail

// ClusterViews of `clustering` over the pixels it was made of, in one pass
// over the pixels (chunks by `parallel_for`, folded per chunk and merged:
// every field of the fold is a maximum, a minimum or an or, so the views are
// fit_virtual_view's bit for bit, whatever the order). tan_half_fov and
// min_near as in virtual_view_begin.
template <class Real, class ParallelFor = SerialFor>
ClusterViews<Real> fit_cluster_views(const Clustering<Real>& clustering,
                                     const std::vector<typename kernel<Real>::vec3>& positions,
                                     const std::vector<typename kernel<Real>::vec3>& directions, Real tan_half_fov,
                                     Real min_near, const ParallelFor& parallel_for = {}) {
    using K = kernel<Real>;
    using Fit = typename K::VirtualViewFit;
    const std::size_t clusters = clustering.clusters.size();
    std::vector<Fit> begun(2 * clusters);
    for (std::size_t c = 0; c < clusters; ++c) {
        const auto& cluster = clustering.clusters[c];
        begun[2 * c] = K::virtual_view_begin(cluster.sums, tan_half_fov, min_near);
        begun[2 * c + 1] =
            K::virtual_view_begin_along(cluster.sums, K::dodecahedron_normal(cluster.facet), tan_half_fov, min_near);
    }
    const std::size_t n = std::min({positions.size(), directions.size(), clustering.cluster_of.size()});
    std::vector<std::vector<Fit>> chunk_fits(detail::chunk_count(n));
    detail::for_chunks(parallel_for, n, [&](std::size_t first, std::size_t last) {
        std::vector<Fit>& fits = chunk_fits[first / detail::cluster_chunk];
        fits = begun;
        for (std::size_t i = first; i < last; ++i) {
            const auto c = static_cast<std::size_t>(clustering.cluster_of[i]);
            fits[2 * c] = K::virtual_view_add(fits[2 * c], positions[i], directions[i]);
            fits[2 * c + 1] = K::virtual_view_add(fits[2 * c + 1], positions[i], directions[i]);
        }
    });
    std::vector<Fit> fits = begun;
    for (const std::vector<Fit>& chunk : chunk_fits)
        for (std::size_t f = 0; f < fits.size(); ++f) fits[f] = detail::merge_fits<Real>(fits[f], chunk[f]);
    ClusterViews<Real> views;
    for (std::size_t c = 0; c < clusters; ++c) {
        views.along_mean.push_back(K::virtual_view_finish(fits[2 * c]));
        views.along_normal.push_back(K::virtual_view_finish(fits[2 * c + 1]));
    }
    return views;
}

}  // namespace blurcull
