// The secondary-ray kernel (docs/secondary-rays.md), in float and double:
// the dodecahedron's normals and facet classifier against brute force, the
// cluster-count rule and k-means, the virtual viewpoint's containment and
// minimality, and the image-space tracing step against analytic planes.
#include "secondary_generators.hpp"

#include <blurcull/layer_trace.hpp>
#include <blurcull/secondary_clusters.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <limits>
#include <set>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

using L = long double;

template <class Real>
typename kernel<Real>::vec3 to_vec3(dvec3 d) {
    return typename kernel<Real>::vec3(static_cast<Real>(d.x), static_cast<Real>(d.y), static_cast<Real>(d.z));
}

// Faces whose exact dot product with d is within the classifier's rounding
// (16 machine epsilons of |d|_1, far above its 3-epsilon error) of the largest.
template <class Real>
std::set<int> maximising_faces(typename kernel<Real>::vec3 d, const L n[12][3], L& best) {
    L dots[12];
    best = -std::numeric_limits<L>::infinity();
    for (int f = 0; f < 12; ++f) {
        dots[f] = n[f][0] * L(d.x) + n[f][1] * L(d.y) + n[f][2] * L(d.z);
        best = std::max(best, dots[f]);
    }
    L tol = 16 * L(std::numeric_limits<Real>::epsilon()) * (std::fabs(L(d.x)) + std::fabs(L(d.y)) + std::fabs(L(d.z)));
    std::set<int> faces;
    for (int f = 0; f < 12; ++f)
        if (dots[f] >= best - tol) faces.insert(f);
    return faces;
}

// The tie rule, stated on the classifier's sums: the family of the largest
// sum, lowest on equality; then the signs, zero counting as positive.
template <class Real>
int tie_rule_face(typename kernel<Real>::vec3 d) {
    using K = kernel<Real>;
    typename K::vec3 a = K::abs(d);
    Real phi = K::bc_golden_ratio();
    Real c[3] = {phi * a.y + a.z, a.x + phi * a.z, phi * a.x + a.y};
    int family = 0;
    for (int f = 1; f < 3; ++f)
        if (c[f] > c[family]) family = f;
    bool neg[3] = {d.x < 0, d.y < 0, d.z < 0};
    int first = family == 0 ? 1 : 0;
    int second = family == 2 ? 1 : 2;
    return 4 * family + (neg[first] ? 2 : 0) + (neg[second] ? 1 : 0);
}

}  // namespace

TEST_CASE_TEMPLATE("the dodecahedron's normals are exact, unit, and each has five neighbours", Real, float, double) {
    using K = kernel<Real>;
    L n[12][3];
    exact_normals(n);
    for (int f = 0; f < 12; ++f) {
        CAPTURE(f);
        typename K::vec3 v = K::dodecahedron_normal(f);
        for (int a = 0; a < 3; ++a) CHECK(v[a] == static_cast<Real>(n[f][a]));
        CHECK(std::fabs(L(K::dot(v, v)) - 1) <= 4 * L(std::numeric_limits<Real>::epsilon()));
        int neighbours = 0;
        for (int g = 0; g < 12; ++g) {
            L d = n[f][0] * n[g][0] + n[f][1] * n[g][1] + n[f][2] * n[g][2];
            if (std::fabs(d - 1 / std::sqrt(5.0L)) < 1e-9L) ++neighbours;
        }
        CHECK(neighbours == 5);
        // The classifier puts every normal on its own face.
        CHECK(K::dodecahedron_facet(v) == f);
    }
    CHECK(K::dodecahedron_normal(-1) == typename K::vec3(0));
    CHECK(K::dodecahedron_normal(12) == typename K::vec3(0));
    CHECK(K::bc_golden_ratio() == static_cast<Real>((1.0L + std::sqrt(5.0L)) / 2.0L));
}

TEST_CASE_TEMPLATE("dodecahedron_facet is brute-force argmax on 10^6 directions, borders and vertices included", Real,
                   float, double) {
    using K = kernel<Real>;
    L n[12][3];
    exact_normals(n);
    int count = static_cast<int>(1000000 * std::min(property_scale(), 1.0));
    std::vector<dvec3> directions = facet_test_directions(0xd0dec4ull, count);
    long ties = 0;
    long exact_sum_ties = 0;
    long failures = 0;
    for (const dvec3& dd : directions) {
        typename K::vec3 d = to_vec3<Real>(dd);
        int face = K::dodecahedron_facet(d);
        L best;
        std::set<int> faces = maximising_faces<Real>(d, n, best);
        if (faces.size() > 1) ++ties;
        bool ok = face >= 0 && face < 12 && faces.count(face) == 1 && face == tie_rule_face<Real>(d);
        // A tie the sums see exactly (or a zero component) is settled by the rule alone.
        typename K::vec3 a = K::abs(d);
        Real phi = K::bc_golden_ratio();
        Real c0 = phi * a.y + a.z, c1 = a.x + phi * a.z, c2 = phi * a.x + a.y;
        if (c0 == c1 || c1 == c2 || c0 == c2 || d.x == 0 || d.y == 0 || d.z == 0) ++exact_sum_ties;
        if (!ok && failures++ < 5)
            FAIL_CHECK("direction (" << dd.x << ", " << dd.y << ", " << dd.z << "): classifier " << face
                                     << ", rule " << tie_rule_face<Real>(d) << ", maximisers " << faces.size()
                                     << " starting at " << *faces.begin());
    }
    MESSAGE(directions.size() << " directions, " << ties << " on a border within rounding, " << exact_sum_ties
                              << " with sums tied exactly or a zero component");
    CHECK(failures == 0);
    CHECK(static_cast<long>(directions.size()) >= count);
    CHECK(ties > count / 10);
    CHECK(exact_sum_ties > count / 20);
}

TEST_CASE_TEMPLATE("the facet tie rule: lowest family, zero counts as positive", Real, float, double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    Real z = Real(0);
    Real nz = -Real(0);
    // Vertex (1, 1, 1): the three families tie exactly; family 0 by the signs of y, z.
    CHECK(K::dodecahedron_facet(V(1, 1, 1)) == 0);
    CHECK(K::dodecahedron_facet(V(-1, 1, -1)) == 1);
    CHECK(K::dodecahedron_facet(V(1, -1, 1)) == 2);
    CHECK(K::dodecahedron_facet(V(-1, -1, -1)) == 3);
    // Borders inside a family: a zero component, either sign, is positive.
    CHECK(K::dodecahedron_facet(V(Real(0.3), 1, z)) == 0);
    CHECK(K::dodecahedron_facet(V(Real(0.3), 1, nz)) == 0);
    CHECK(K::dodecahedron_facet(V(Real(0.3), -1, nz)) == 2);
    CHECK(K::dodecahedron_facet(V(1, nz, Real(-0.2))) == 8);
    CHECK(K::dodecahedron_facet(V(nz, Real(0.2), 1)) == 4);
    // Axes and the zero vector.
    CHECK(K::dodecahedron_facet(V(1, 0, 0)) == 8);
    CHECK(K::dodecahedron_facet(V(-1, 0, 0)) == 10);
    CHECK(K::dodecahedron_facet(V(0, 1, 0)) == 0);
    CHECK(K::dodecahedron_facet(V(0, 0, -1)) == 5);
    CHECK(K::dodecahedron_facet(V(0, 0, 0)) == 0);
    Real nan = std::numeric_limits<Real>::quiet_NaN();
    int face = K::dodecahedron_facet(V(nan, 1, 0));
    CHECK((face >= 0 && face < 12));
}

TEST_CASE("clusters_for_facet: round(pixels / target) in [1, 3], never more than the pixels") {
    using K = kerneld;
    CHECK(K::cluster_target_size(0, 24) == 1);
    CHECK(K::cluster_target_size(240, 24) == 10);
    CHECK(K::cluster_target_size(241, 24) == 11);
    CHECK(K::cluster_target_size(5, 0) == 5);
    CHECK(K::clusters_for_facet(0, 10, 3) == 0);
    CHECK(K::clusters_for_facet(1, 10, 3) == 1);
    CHECK(K::clusters_for_facet(14, 10, 3) == 1);
    CHECK(K::clusters_for_facet(15, 10, 3) == 2);  // 1.5 rounds up
    CHECK(K::clusters_for_facet(24, 10, 3) == 2);
    CHECK(K::clusters_for_facet(25, 10, 3) == 3);
    CHECK(K::clusters_for_facet(1000, 10, 3) == 3);
    CHECK(K::clusters_for_facet(1000, 10, 2) == 2);
    CHECK(K::clusters_for_facet(1000, 10, 0) == 1);
    CHECK(K::clusters_for_facet(1000, 10, 9) == 3);
    CHECK(K::clusters_for_facet(2, 1, 3) == 2);
    CHECK(K::clusters_for_facet(7, 0, 3) == 3);
    CHECK(K::clusters_for_facet(0xffffffffu, 0x80000000u, 3) == 2);
    // The chosen k gives the cluster size nearest the target among 1..3.
    for (std::uint32_t pixels = 1; pixels < 400; ++pixels)
        for (std::uint32_t target : {1u, 7u, 10u, 33u, 100u}) {
            std::uint32_t k = K::clusters_for_facet(pixels, target, 3);
            double best = 1e300;
            for (std::uint32_t j = 1; j <= std::min(3u, pixels); ++j)
                best = std::min(best, std::fabs(double(pixels) / j - target));
            CAPTURE(pixels);
            CAPTURE(target);
            // Nearest in the ratio's rounding sense: |pixels / target - k| <= 1/2 unless clamped.
            double ratio = double(pixels) / target;
            if (ratio >= 0.5 && ratio < 3.5 && ratio <= pixels) CHECK(std::fabs(ratio - k) <= 0.5);
            CHECK(k >= 1);
            CHECK(k <= std::min(3u, pixels));
        }
}

TEST_CASE_TEMPLATE("kmeans_nearest: the nearest centre, lowest index on ties", Real, float, double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    V c[BC_CLUSTERS_PER_FACET_MAX] = {V(0, 0, 0), V(2, 0, 0), V(0, 3, 0)};
    CHECK(K::kmeans_nearest(V(Real(0.9), 0, 0), c, 3) == 0);
    CHECK(K::kmeans_nearest(V(Real(1.1), 0, 0), c, 3) == 1);
    CHECK(K::kmeans_nearest(V(1, 0, 0), c, 3) == 0);  // equidistant from 0 and 1
    CHECK(K::kmeans_nearest(V(0, 5, 0), c, 3) == 2);
    CHECK(K::kmeans_nearest(V(0, 5, 0), c, 2) == 0);  // only the first two
    CHECK(K::kmeans_nearest(V(0, 5, 0), c, 0) == 0);  // count clamped to 1
    CHECK(K::kmeans_nearest(V(0, 5, 0), c, 9) == 2);
    // The start key: fixed by the seed, facet and pixel; another of any of them starts elsewhere.
    CHECK(K::kmeans_start_key(99, 3, 17) == K::kmeans_start_key(99, 3, 17));
    CHECK(K::kmeans_start_key(99, 3, 17) != K::kmeans_start_key(98, 3, 17));
    CHECK(K::kmeans_start_key(99, 3, 17) != K::kmeans_start_key(99, 4, 17));
    CHECK(K::kmeans_start_key(99, 3, 17) != K::kmeans_start_key(99, 3, 18));
}

TEST_CASE_TEMPLATE("cluster sums are exact: any split merged in any order gives one loop's bits", Real, float,
                   double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    Rng rng(0x5053ull + sizeof(Real));
    std::vector<V> p, d;
    for (int i = 0; i < 20000; ++i) {
        // Magnitudes over 6 decades and both signs, so the low words carry.
        double scale = std::pow(10.0, rng.uniform() * 6.0 - 3.0);
        p.push_back(to_vec3<Real>(dvec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5) * scale * 200.0));
        d.push_back(to_vec3<Real>(random_unit(rng)));
    }
    const typename K::ClusterSums loop = cluster_sums_of<Real>(p, d);
    REQUIRE(loop.count == p.size());
    CHECK(loop.unfit == 0u);
    // Backwards, in 7 interleaved parts merged last first.
    const Real scale = loop.position_scale;
    std::array<typename K::ClusterSums, 7> parts;
    parts.fill(K::cluster_sums_empty(scale));
    for (std::size_t i = p.size(); i-- > 0;) parts[i % 7] = K::cluster_sums_add(parts[i % 7], p[i], d[i]);
    typename K::ClusterSums merged = K::cluster_sums_empty(scale);
    for (std::size_t k = parts.size(); k-- > 0;) merged = K::cluster_sums_merge(merged, parts[k]);
    CHECK(merged.position_hi == loop.position_hi);
    CHECK(merged.position_lo == loop.position_lo);
    CHECK(merged.direction_hi == loop.direction_hi);
    CHECK(merged.direction_lo == loop.direction_lo);
    CHECK(merged.count == loop.count);
    // The host driver's 64-bit integer adds of the same terms: the same words.
    detail::FixedSums<Real> wide;
    for (std::size_t i = 0; i < p.size(); ++i) wide.add(p[i], d[i], scale);
    const typename K::ClusterSums from_wide = wide.sums(scale);
    CHECK(from_wide.position_hi == loop.position_hi);
    CHECK(from_wide.position_lo == loop.position_lo);
    CHECK(from_wide.direction_hi == loop.direction_hi);
    CHECK(from_wide.direction_lo == loop.direction_lo);
    CHECK(from_wide.count == loop.count);
    // The mean and direction sum: those of the points to within the fixed
    // point's step (2^-30 of the largest |coordinate|) and one rounding.
    long double sum[3] = {0, 0, 0}, dsum[3] = {0, 0, 0}, largest = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (int a = 0; a < 3; ++a) {
            sum[a] += static_cast<long double>(p[i][a]);
            dsum[a] += static_cast<long double>(d[i][a]);
            largest = std::max(largest, std::fabs(static_cast<long double>(p[i][a])));
        }
    const V mean = K::cluster_mean_position(loop);
    const V directions = K::cluster_direction_sum(loop);
    const long double eps = std::numeric_limits<Real>::epsilon();
    for (int a = 0; a < 3; ++a) {
        const long double exact_mean = sum[a] / static_cast<long double>(p.size());
        CHECK(std::fabs(static_cast<long double>(mean[a]) - exact_mean) <=
              largest * (std::ldexp(1.0L, -29) + 4 * eps));
        CHECK(std::fabs(static_cast<long double>(directions[a]) - dsum[a]) <=
              static_cast<long double>(p.size()) * std::ldexp(1.0L, -30) + 4 * eps * std::fabs(dsum[a]) + eps);
    }
    // The scale: a power of two that takes the largest coordinate to at most 2^30.
    for (Real largest_value : {Real(0), Real(1), Real(0.75), Real(3e4), Real(1e-20)}) {
        const Real s = K::cluster_position_scale(largest_value);
        int e = 0;
        CHECK(std::frexp(s, &e) == Real(0.5));
        CHECK(largest_value * s <= Real(1073741824.0));
        if (largest_value > Real(0)) CHECK(largest_value * s >= Real(536870912.0));
    }
    // A point that does not fit (NaN, infinite, beyond the scale) is counted,
    // not summed; a view of it is not finite.
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    typename K::ClusterSums odd = K::cluster_sums_empty(K::cluster_position_scale(Real(1)));
    odd = K::cluster_sums_add(odd, V(nan, 0, 0), V(0, 0, 1));
    odd = K::cluster_sums_add(odd, V(0, 0, 0), V(std::numeric_limits<Real>::infinity(), 0, 0));
    odd = K::cluster_sums_add(odd, V(4, 0, 0), V(0, 0, 1));
    odd = K::cluster_sums_add(odd, V(Real(0.5), 0, 0), V(0, 0, 1));
    CHECK(odd.count == 1u);
    CHECK(odd.unfit == 3u);
    CHECK(K::cluster_mean_position(odd).x == Real(0.5));
    CHECK((K::virtual_view_begin(odd, Real(1), Real(0.1)).flags & BC_VIEW_NOT_FINITE) != 0);
}

TEST_CASE_TEMPLATE("clustering a mirror sphere: facets, 1-3 clusters each, deterministic, balanced", Real, float,
                   double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    // A mirror sphere: each visible point's mirror direction of the view ray.
    std::vector<dvec3> dp, dd;
    mirror_sphere_pixels(dp, dd);
    std::vector<V> positions;
    std::vector<V> directions;
    for (std::size_t i = 0; i < dp.size(); ++i) {
        positions.push_back(to_vec3<Real>(dp[i]));
        directions.push_back(to_vec3<Real>(dd[i]));
    }
    ClusterOptions options;
    Clustering<Real> a = cluster_reflector_pixels<Real>(positions, directions, options);
    Clustering<Real> b = cluster_reflector_pixels<Real>(positions, directions, options);
    REQUIRE(a.cluster_of.size() == positions.size());
    CHECK(a.cluster_of == b.cluster_of);
    CHECK(a.iterations == b.iterations);
    MESSAGE(positions.size() << " sphere pixels, " << a.clusters.size() << " clusters, " << a.iterations
                             << " Lloyd iterations, " << a.unsettled_facets << " facets stopped at "
                             << options.max_iterations);
    CHECK(a.clusters.size() >= 12);
    CHECK(a.iterations <= 12 * options.max_iterations);
    std::array<int, 12> per_facet{};
    std::uint32_t total = 0;
    std::uint32_t smallest = ~0u;
    std::uint32_t largest = 0;
    for (const auto& c : a.clusters) {
        ++per_facet[static_cast<std::size_t>(c.facet)];
        total += c.sums.count;
        smallest = std::min(smallest, c.sums.count);
        largest = std::max(largest, c.sums.count);
    }
    CHECK(total == positions.size());
    for (int f : per_facet) CHECK(f <= 3);
    MESSAGE("cluster sizes " << smallest << " to " << largest << ", target "
                             << K::cluster_target_size(static_cast<std::uint32_t>(positions.size()), 24));
    for (std::size_t i = 0; i < positions.size(); ++i) {
        int c = a.cluster_of[i];
        REQUIRE((c >= 0 && c < static_cast<int>(a.clusters.size())));
        CHECK(a.clusters[static_cast<std::size_t>(c)].facet == K::dodecahedron_facet(directions[i]));
    }
    // Once Lloyd has settled, each pixel is nearest its own cluster's mean
    // among its facet's clusters, to within rounding of the means.
    ClusterOptions patient = options;
    patient.max_iterations = 1000;
    a = cluster_reflector_pixels<Real>(positions, directions, patient);
    CHECK(a.unsettled_facets == 0);
    long misplaced = 0;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const auto& own = a.clusters[static_cast<std::size_t>(a.cluster_of[i])];
        Real d_own = K::bc_distance2(positions[i], K::cluster_mean_position(own.sums));
        for (const auto& other : a.clusters)
            if (other.facet == own.facet &&
                K::bc_distance2(positions[i], K::cluster_mean_position(other.sums)) < d_own * Real(0.999))
                ++misplaced;
    }
    CHECK(misplaced == 0);
    // Another seed may start elsewhere but ends with the same number of clusters per facet.
    options.seed = 77;
    Clustering<Real> c = cluster_reflector_pixels<Real>(positions, directions, options);
    CHECK(c.clusters.size() == a.clusters.size());
    // Empty input, and options at their limits.
    CHECK(cluster_reflector_pixels<Real>({}, {}).clusters.empty());
    options.max_per_facet = 1;
    CHECK(cluster_reflector_pixels<Real>(positions, directions, options).clusters.size() <= 12);
    options.max_iterations = 0;  // counts as 1
    CHECK(cluster_reflector_pixels<Real>(positions, directions, options).iterations <= 12);
}

namespace {

// Smallest back-off t >= 0 at which every point is inside the square frustum
// of the fitted axes and at least min_near in front, by bisection on the
// containment predicate in long double: independent of the closed form.
template <class Real>
L bisected_backoff(const typename kernel<Real>::VirtualView& v, const std::vector<typename kernel<Real>::vec3>& p,
                   typename kernel<Real>::vec3 origin, Real min_near) {
    auto inside_all = [&](L t) {
        for (const auto& q : p) {
            L r[3] = {L(q.x) - (L(origin.x) - t * L(v.forward.x)), L(q.y) - (L(origin.y) - t * L(v.forward.y)),
                      L(q.z) - (L(origin.z) - t * L(v.forward.z))};
            L x = r[0] * L(v.right.x) + r[1] * L(v.right.y) + r[2] * L(v.right.z);
            L y = r[0] * L(v.up.x) + r[1] * L(v.up.y) + r[2] * L(v.up.z);
            L z = r[0] * L(v.forward.x) + r[1] * L(v.forward.y) + r[2] * L(v.forward.z);
            if (std::max(std::fabs(x), std::fabs(y)) > z * L(v.tan_half_fov) || z < L(min_near)) return false;
        }
        return true;
    };
    if (inside_all(0)) return 0;
    L lo = 0, hi = 1;
    while (!inside_all(hi)) hi *= 2;
    for (int i = 0; i < 200; ++i) {
        L mid = (lo + hi) / 2;
        (inside_all(mid) ? hi : lo) = mid;
    }
    return hi;
}

}  // namespace

TEST_CASE_TEMPLATE("virtual viewpoints contain their clusters with the smallest back-off", Real, float, double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    Rng rng(0x71e3ull + sizeof(Real));
    const Real tan_half = static_cast<Real>(std::tan(40.0 * 3.14159265358979323846 / 180.0));
    const L eps = L(std::numeric_limits<Real>::epsilon());
    int outside_flagged = 0;
    L worst_excess = 0;
    for (int n = 0; n < 2000; ++n) {
        double cone = n % 5 == 0 ? 80.0 : 30.0;
        SyntheticCluster sc = make_cluster(rng, cone);
        std::vector<V> p, d;
        for (std::size_t i = 0; i < sc.positions.size(); ++i) {
            p.push_back(to_vec3<Real>(sc.positions[i]));
            d.push_back(to_vec3<Real>(sc.directions[i]));
        }
        const typename K::ClusterSums sums = cluster_sums_of<Real>(p, d);
        Real min_near = Real(0.01);
        typename K::VirtualView v = fit_virtual_view<Real>(sums, p, d, tan_half, min_near);
        CAPTURE(n);
        CHECK((v.flags & ~BC_VIEW_DIRECTION_OUTSIDE) == 0);
        if (v.flags & BC_VIEW_DIRECTION_OUTSIDE) ++outside_flagged;
        // The flag is exactly "some direction outside the frustum" (judged in long double, with a rounding band).
        bool any_outside = false, any_borderline = false;
        for (const V& q : d) {
            L z = L(q.x) * L(v.forward.x) + L(q.y) * L(v.forward.y) + L(q.z) * L(v.forward.z);
            L x = L(q.x) * L(v.right.x) + L(q.y) * L(v.right.y) + L(q.z) * L(v.right.z);
            L y = L(q.x) * L(v.up.x) + L(q.y) * L(v.up.y) + L(q.z) * L(v.up.z);
            L excess = std::max(std::fabs(x), std::fabs(y)) - z * L(tan_half);
            any_outside = any_outside || excess > 16 * eps || z <= 0;
            any_borderline = any_borderline || std::fabs(excess) <= 16 * eps;
        }
        if (!any_borderline) CHECK(((v.flags & BC_VIEW_DIRECTION_OUTSIDE) != 0) == any_outside);
        // Every pixel inside at the fitted eye, and at least near in front.
        L scale = 0;
        for (const V& q : p) scale = std::max({scale, std::fabs(L(q.x)), std::fabs(L(q.y)), std::fabs(L(q.z))});
        scale += L(v.backoff);
        L closest = std::numeric_limits<L>::infinity();
        for (const V& q : p) {
            L r[3] = {L(q.x) - L(v.eye.x), L(q.y) - L(v.eye.y), L(q.z) - L(v.eye.z)};
            L x = r[0] * L(v.right.x) + r[1] * L(v.right.y) + r[2] * L(v.right.z);
            L y = r[0] * L(v.up.x) + r[1] * L(v.up.y) + r[2] * L(v.up.z);
            L z = r[0] * L(v.forward.x) + r[1] * L(v.forward.y) + r[2] * L(v.forward.z);
            CHECK(std::max(std::fabs(x), std::fabs(y)) <= z * L(tan_half));
            CHECK(z >= L(v.near));
            closest = std::min(closest, z);
        }
        CHECK(L(v.near) >= L(min_near) - 16 * eps * scale);
        CHECK(closest - L(v.near) <= 1e3L * eps * scale);
        // Smallest: the bisected back-off of the same axes, within rounding.
        L t = bisected_backoff<Real>(v, p, K::cluster_mean_position(sums), min_near);
        L excess = L(v.backoff) - t;
        CHECK(excess >= -1e3L * eps * scale);
        CHECK(excess <= 1e3L * eps * scale);
        worst_excess = std::max(worst_excess, excess / scale);
    }
    MESSAGE("worst back-off excess over the bisected minimum: " << double(worst_excess / eps)
                                                                << " machine epsilons of the cluster's scale; "
                                                                << outside_flagged << " clusters flagged");
    CHECK(outside_flagged > 100);
}

TEST_CASE_TEMPLATE("along its facet's normal, a field of view of 74.76 degrees holds every direction of the facet", Real,
                   float, double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    Rng rng(0xface7ull);
    auto tan_deg = [](double degrees) { return static_cast<Real>(std::tan(degrees * 3.14159265358979323846 / 180.0)); };
    std::array<std::vector<V>, 12> by_facet;
    for (int i = 0; i < 200000; ++i) {
        V d = to_vec3<Real>(random_unit(rng));
        by_facet[static_cast<std::size_t>(K::dodecahedron_facet(d))].push_back(d);
    }
    for (int facet = 0; facet < 12; ++facet) {
        CAPTURE(facet);
        const std::vector<V>& d = by_facet[static_cast<std::size_t>(facet)];
        REQUIRE(d.size() > 1000);
        const std::vector<V>& p = d;  // positions on the unit sphere, like a mirror ball's
        const typename K::ClusterSums sums = cluster_sums_of<Real>(p, d);
        V normal = K::dodecahedron_normal(facet);
        auto fit_along = [&](Real tan_half) {
            typename K::VirtualViewFit f = K::virtual_view_begin_along(sums, normal, tan_half, Real(0.01));
            for (std::size_t i = 0; i < d.size(); ++i) f = K::virtual_view_add(f, p[i], d[i]);
            return K::virtual_view_finish(f);
        };
        CHECK(fit_along(tan_deg(37.38)).flags == BC_VIEW_OK);
        // Below the facet's inscribed radius (31.72 degrees) the square cannot hold it.
        CHECK((fit_along(tan_deg(30.0)).flags & BC_VIEW_DIRECTION_OUTSIDE) != 0);
        typename K::VirtualView v = fit_along(tan_deg(40.0));
        CHECK(K::dot(v.forward, normal) >= 1 - 4 * std::numeric_limits<Real>::epsilon());
    }
    // Mean direction and begin_along(mean) are the same fit.
    typename K::ClusterSums s = cluster_sums_of<Real>({V(1, 2, 3)}, {V(0, Real(0.6), Real(0.8))});
    typename K::VirtualViewFit a = K::virtual_view_begin(s, Real(1), Real(0.1));
    typename K::VirtualViewFit b = K::virtual_view_begin_along(s, K::cluster_direction_sum(s), Real(1), Real(0.1));
    CHECK(a.forward == b.forward);
    CHECK(a.right == b.right);
    CHECK((K::virtual_view_begin_along(s, V(0), Real(1), Real(0.1)).flags & BC_VIEW_EMPTY) != 0);
}

TEST_CASE_TEMPLATE("virtual viewpoint failures are flags, not hangs", Real, float, double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    Real tan_half = Real(0.8391);
    auto fit = [&](std::vector<V> p, std::vector<V> d, Real t = Real(0.8391), Real near = Real(0.01)) {
        return fit_virtual_view<Real>(cluster_sums_of<Real>(p, d), p, d, t, near);
    };
    // Directions spread over 120 degrees: no FOV of 80 contains their rays.
    typename K::VirtualView spread = fit({V(0), V(1, 0, 0)}, {V(0, 0, 1), V(Real(0.866), 0, Real(-0.5))});
    CHECK((spread.flags & BC_VIEW_DIRECTION_OUTSIDE) != 0);
    CHECK(K::bc_finite(spread.backoff));
    // One pixel: the eye min_near behind it.
    typename K::VirtualView one = fit({V(1, 2, 3)}, {V(0, 1, 0)});
    CHECK(one.flags == BC_VIEW_OK);
    CHECK(one.backoff == doctest::Approx(0.01).epsilon(1e-3));
    CHECK(one.near == doctest::Approx(0.01).epsilon(1e-3));
    CHECK(one.eye.y == doctest::Approx(2 - 0.01).epsilon(1e-3));
    // Nothing, opposite directions, bad parameters, NaN.
    CHECK((fit({}, {}).flags & BC_VIEW_EMPTY) != 0);
    CHECK((fit({V(0), V(1)}, {V(0, 0, 1), V(0, 0, -1)}).flags & BC_VIEW_EMPTY) != 0);
    CHECK((fit({V(0)}, {V(0, 0, 1)}, Real(0)).flags & BC_VIEW_BAD_PARAMETERS) != 0);
    CHECK((fit({V(0)}, {V(0, 0, 1)}, tan_half, Real(0)).flags & BC_VIEW_BAD_PARAMETERS) != 0);
    Real nan = std::numeric_limits<Real>::quiet_NaN();
    CHECK((fit({V(0), V(nan, 0, 0)}, {V(0, 0, 1), V(0, 0, 1)}).flags & BC_VIEW_NOT_FINITE) != 0);
    CHECK((fit({V(0)}, {V(0, 0, 1)}, std::numeric_limits<Real>::infinity()).flags & BC_VIEW_BAD_PARAMETERS) != 0);
    // The basis is orthonormal and right-handed for any axis.
    Rng rng(5);
    for (int i = 0; i < 1000; ++i) {
        V f = to_vec3<Real>(random_unit(rng));
        f = f / std::sqrt(K::dot(f, f));
        V r, u;
        K::virtual_view_basis(f, r, u);
        Real tol = 8 * std::numeric_limits<Real>::epsilon();
        CHECK(std::fabs(K::dot(r, f)) <= tol);
        CHECK(std::fabs(K::dot(u, f)) <= tol);
        CHECK(std::fabs(K::dot(r, u)) <= tol);
        CHECK(std::fabs(K::dot(r, r) - 1) <= tol);
        V c = K::cross(r, u);
        CHECK(K::dot(c, f) >= 1 - tol);
    }
}

namespace {

template <class Real>
typename kernel<Real>::LayerView layer_view_of(const LayerScene& s) {
    typename kernel<Real>::LayerView v;
    v.eye = to_vec3<Real>(s.eye);
    v.forward = to_vec3<Real>(s.forward);
    v.right = to_vec3<Real>(s.right);
    v.up = to_vec3<Real>(s.up);
    v.tan_half_fov = static_cast<Real>(s.tan_half_fov);
    v.near = static_cast<Real>(s.near);
    v.far = static_cast<Real>(s.far);
    v.size = s.size;
    return v;
}

template <class Real>
auto layer_fetch(const LayerScene& s) {
    return [&s](int layer, int x, int y) {
        return static_cast<Real>(s.depth[layer][static_cast<std::size_t>(y * s.size + x)]);
    };
}

// The exact first hit of a ray with the scene's two planes (the occluder
// only where it projects into its window), or infinity.
double exact_hit(const LayerScene& s, dvec3 o, dvec3 d, int& layer) {
    layer = -1;
    double best = std::numeric_limits<double>::infinity();
    double t0 = (s.plane_offset - glm::dot(s.plane_normal, o)) / glm::dot(s.plane_normal, d);
    if (t0 > 0) { best = t0; layer = 0; }
    double t1 = (s.occluder_offset - glm::dot(s.occluder_normal, o)) / glm::dot(s.occluder_normal, d);
    if (t1 > 0 && t1 < best) {
        dvec3 p = o + t1 * d;
        double ix = (p.x / p.z / s.tan_half_fov + 1) * 0.5 * s.size;
        double iy = (p.y / p.z / s.tan_half_fov + 1) * 0.5 * s.size;
        if (ix >= s.window_lo && ix < s.window_hi && iy >= s.window_lo && iy < s.window_hi) { best = t1; layer = 1; }
    }
    return best;
}

}  // namespace

TEST_CASE_TEMPLATE("layer_segment clips to the frustum and the depth interval, and no further", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(0xc119ull);
    LayerScene s = make_layer_scene(rng);
    typename K::LayerView v = layer_view_of<Real>(s);
    const double tol = 1e-4;
    for (int n = 0; n < 20000; ++n) {
        dvec3 o(rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-2, 10));
        dvec3 d = random_unit(rng);
        double s_max = rng.uniform(0.1, 30);
        double zlo = rng.uniform(0, 6), zhi = zlo + rng.uniform(0, 10);
        typename K::LayerSegment seg =
            K::layer_segment(v, to_vec3<Real>(o), to_vec3<Real>(d), Real(s_max), typename K::vec2(Real(zlo), Real(zhi)));
        auto inside = [&](double t, double slack) {
            dvec3 p = o + t * d;
            double lo = std::max(s.near, zlo), hi = std::min(s.far, zhi);
            return t >= -slack && t <= s_max + slack && p.z >= lo - slack && p.z <= hi + slack &&
                   std::fabs(p.x) <= p.z * s.tan_half_fov + slack && std::fabs(p.y) <= p.z * s.tan_half_fov + slack;
        };
        CAPTURE(n);
        if (seg.empty) {
            for (int k = 0; k <= 64; ++k) CHECK(!inside(s_max * k / 64.0, -tol));
            continue;
        }
        CHECK(inside(seg.s0, tol));
        CHECK(inside(seg.s1, tol));
        CHECK(inside(0.5 * (seg.s0 + seg.s1), tol));
        // Just beyond either end is outside (or beyond the ray's own range).
        CHECK((seg.s0 <= tol || !inside(seg.s0 - 1e-2, -1e-3)));
        CHECK((seg.s1 >= s_max - tol || !inside(seg.s1 + 1e-2, -1e-3)));
        // The projected ends are the ends' image positions.
        typename K::vec3 q0 = K::layer_project(v, to_vec3<Real>(o + double(seg.s0) * d));
        CHECK(std::fabs(double(q0.x - seg.p0.x)) <= 1e-2);
        CHECK(std::fabs(double(q0.y - seg.p0.y)) <= 1e-2);
        CHECK(K::layer_step_count(v, seg) <= 2 * s.size + 2);
        typename K::vec4 box = K::layer_footprint(v, seg);
        CHECK(box.x <= box.z);
        CHECK((box.x >= 0 && box.w <= Real(s.size - 1)));
    }
}

TEST_CASE_TEMPLATE("layer_trace finds the first of two layered planes within a texel", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(0x7ace0ull + sizeof(Real));
    long hits = 0, occluder_hits = 0, total_steps = 0;
    const double thickness = 0.5;
    double worst = 0;
    for (int scene = 0; scene < 8; ++scene) {
        LayerScene s = make_layer_scene(rng);
        typename K::LayerView v = layer_view_of<Real>(s);
        auto fetch = layer_fetch<Real>(s);
        for (int n = 0; n < 2000; ++n) {
            TraceRay ray = make_trace_ray(rng, s);
            typename K::vec3 o = to_vec3<Real>(ray.origin);
            typename K::vec3 d = to_vec3<Real>(ray.direction);
            typename K::LayerSegment seg = K::layer_segment(v, o, d, Real(1000), typename K::vec2(Real(0), K::bc_huge()));
            typename K::LayerHit h = trace_layers<Real>(v, seg, 2, Real(thickness), fetch);
            int layer;
            double t = exact_hit(s, ray.origin, ray.direction, layer);
            dvec3 p = ray.origin + t * ray.direction;
            // A texel at the hit's depth spans 2 tan z / size; the stored depth is
            // the texel centre's, so the hit may be off by about a texel along the
            // plane, more at grazing angles.
            double texel = 2 * s.tan_half_fov * p.z / s.size;
            double cosine = std::fabs(glm::dot(ray.direction, layer == 1 ? s.occluder_normal : s.plane_normal));
            CAPTURE(scene);
            CAPTURE(n);
            total_steps += h.steps;
            CHECK(h.steps <= 2 * s.size + 2);
            // The occluder's texels are slabs [D, D + thickness]: a ray whose image
            // over that depth range comes near the window's border may go either way.
            double border = 1e300;
            for (int k = 0; k <= 64; ++k) {
                double z1 = -s.occluder_offset + thickness * k / 64.0;  // the occluder is z = -offset
                double t1 = (z1 - ray.origin.z) / ray.direction.z;
                dvec3 p1 = ray.origin + t1 * ray.direction;
                double wx = (p1.x / p1.z / s.tan_half_fov + 1) * 0.5 * s.size;
                double wy = (p1.y / p1.z / s.tan_half_fov + 1) * 0.5 * s.size;
                bool in = wx >= s.window_lo && wx < s.window_hi && wy >= s.window_lo && wy < s.window_hi;
                double edge = std::min({std::fabs(wx - s.window_lo), std::fabs(wx - s.window_hi),
                                        std::fabs(wy - s.window_lo), std::fabs(wy - s.window_hi)});
                border = std::min(border, in == (layer == 1) ? edge : 0.0);
            }
            if (border < 1.5) continue;
            REQUIRE(h.hit);
            CHECK(h.layer == layer);
            double error = glm::length(dvec3(o.x, o.y, o.z) + double(h.s) * dvec3(d.x, d.y, d.z) - p);
            CHECK(error <= 2 * texel / std::max(cosine, 0.2));
            worst = std::max(worst, error / texel * std::max(cosine, 0.2));
            ++hits;
            if (layer == 1) ++occluder_hits;
        }
    }
    MESSAGE(hits << " hits checked (" << occluder_hits << " on the occluder), " << total_steps << " steps; worst error "
                 << worst << " texels (scaled by the cosine)");
    CHECK(occluder_hits > 100);
    CHECK(hits - occluder_hits > 1000);
}

TEST_CASE_TEMPLATE("layer_trace: misses, depth intervals and empty segments", Real, float, double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    using V2 = typename K::vec2;
    Rng rng(0x3155ull);
    LayerScene s = make_layer_scene(rng);
    typename K::LayerView v = layer_view_of<Real>(s);
    auto fetch = layer_fetch<Real>(s);
    Real huge = K::bc_huge();
    V o(0, 0, 1);
    V d(0, 0, 1);
    int layer;
    double t = exact_hit(s, dvec3(0, 0, 1), dvec3(0, 0, 1), layer);
    REQUIRE(layer == 1);  // straight through the occluder's window
    // Away from the planes: a miss that steps over the image and stops.
    typename K::LayerHit away = trace_layers<Real>(v, K::layer_segment(v, V(0, 0, 1), V(0, 0, -1), Real(100), V2(0, huge)),
                                                   2, Real(0.5), fetch);
    CHECK(!away.hit);
    // The segment ends before the surface: no hit.
    CHECK(!trace_layers<Real>(v, K::layer_segment(v, o, d, Real(t * 0.5), V2(0, huge)), 2, Real(0.5), fetch).hit);
    // A depth interval around the surface finds the same hit; one beyond it finds the plane behind.
    typename K::LayerHit full = trace_layers<Real>(v, K::layer_segment(v, o, d, Real(100), V2(0, huge)), 2, Real(0.5), fetch);
    typename K::LayerHit clipped =
        trace_layers<Real>(v, K::layer_segment(v, o, d, Real(100), V2(Real(t), Real(t + 2))), 2, Real(0.5), fetch);
    REQUIRE(full.hit);
    REQUIRE(clipped.hit);
    CHECK(full.layer == 1);
    CHECK(double(full.s) == doctest::Approx(t).epsilon(1e-3));
    CHECK(double(clipped.s) == doctest::Approx(double(full.s)).epsilon(1e-3));
    typename K::LayerHit behind =
        trace_layers<Real>(v, K::layer_segment(v, o, d, Real(100), V2(Real(1 + t + 0.6), huge)), 2, Real(0.5), fetch);
    CHECK(behind.hit);
    CHECK(behind.layer == 0);
    // Only layer 0 read: the occluder is not seen.
    CHECK(trace_layers<Real>(v, K::layer_segment(v, o, d, Real(100), V2(0, huge)), 1, Real(0.5), fetch).layer == 0);
    // Outside the frustum, or an interval that is empty: 0 steps.
    typename K::LayerSegment out = K::layer_segment(v, V(0, 0, -5), V(0, 1, 0), Real(100), V2(0, huge));
    CHECK(out.empty);
    CHECK(K::layer_step_count(v, out) == 0);
    CHECK(trace_layers<Real>(v, out, 2, Real(0.5), fetch).steps == 0);
    CHECK(K::layer_segment(v, o, d, Real(100), V2(Real(5), Real(4))).empty);
    // An unbounded ray is bounded by the far plane; a zero direction unbounded is empty.
    typename K::LayerHit unbounded = trace_layers<Real>(
        v, K::layer_segment(v, o, d, std::numeric_limits<Real>::infinity(), V2(0, huge)), 2, Real(0.5), fetch);
    CHECK(unbounded.hit);
    CHECK(unbounded.s == full.s);
    CHECK(K::layer_segment(v, o, V(0), std::numeric_limits<Real>::infinity(), V2(0, huge)).empty);
    CHECK(!K::layer_segment(v, o, V(0), Real(1), V2(0, huge)).empty);
    // A NaN ray is empty, not a hang.
    Real nan = std::numeric_limits<Real>::quiet_NaN();
    CHECK(K::layer_segment(v, V(nan, 0, 0), d, Real(100), V2(0, huge)).empty);
    // NaN and infinite stored depths are no surface.
    auto holes = [](int, int, int) { return std::numeric_limits<Real>::quiet_NaN(); };
    CHECK(!trace_layers<Real>(v, K::layer_segment(v, o, d, Real(100), V2(0, huge)), 2, Real(0.5), holes).hit);
    // Layer view from a virtual view keeps its axes; size is at least 1.
    typename K::VirtualView vv;
    vv.eye = V(1, 2, 3);
    vv.forward = V(0, 0, 1);
    vv.right = V(1, 0, 0);
    vv.up = V(0, 1, 0);
    vv.tan_half_fov = Real(1);
    vv.near = Real(0.5);
    vv.backoff = Real(1);
    vv.flags = 0;
    typename K::LayerView lv = K::layer_view_from(vv, Real(50), 0);
    CHECK(lv.size == 1);
    CHECK(lv.far == Real(50));
    CHECK(lv.eye == vv.eye);
    typename K::vec3 proj = K::layer_project(lv, V(1, 2, 4));
    CHECK(proj.x == Real(0.5));
    CHECK(proj.z == Real(1));
    CHECK(K::layer_project(lv, V(1, 2, 2)).z == Real(-1));
}

// cluster_reflector_pixels with a caller's parallel_for: the chunks of its
// loops (65,536 pixels each) in another order (last first, as threads may
// finish them) give the serial run's clusters exactly: the same pixel
// assignment, iterations and sums bit for bit.
TEST_CASE_TEMPLATE("clustering: the same clusters whatever order parallel_for runs the chunks in", Real, float,
                   double) {
    using K = kernel<Real>;
    using V = typename K::vec3;
    Rng rng(2026);
    std::vector<V> positions, directions;
    for (int i = 0; i < 200000; ++i) {  // four chunks, over every facet
        const dvec3 p(rng.uniform(-3.0, 3.0), rng.uniform(0.0, 2.0), rng.uniform(-1.0, 1.0));
        positions.push_back(to_vec3<Real>(p));
        directions.push_back(to_vec3<Real>(random_unit(rng)));
    }
    std::size_t calls = 0, items = 0;
    auto last_first = [&](std::size_t count, const auto& body) {
        ++calls;
        items += count;
        for (std::size_t i = count; i-- > 0;) body(i);
    };
    const Clustering<Real> serial = cluster_reflector_pixels<Real>(positions, directions);
    const Clustering<Real> reordered = cluster_reflector_pixels<Real>(positions, directions, {}, last_first);
    CHECK(items > calls);  // some calls ran several chunks
    CHECK(reordered.cluster_of == serial.cluster_of);
    CHECK(reordered.iterations == serial.iterations);
    CHECK(reordered.unsettled_facets == serial.unsettled_facets);
    REQUIRE(reordered.clusters.size() == serial.clusters.size());
    CHECK(serial.clusters.size() >= 12);
    for (std::size_t c = 0; c < serial.clusters.size(); ++c) {
        const auto& a = serial.clusters[c].sums;
        const auto& b = reordered.clusters[c].sums;
        CHECK(reordered.clusters[c].facet == serial.clusters[c].facet);
        CHECK(a.count == b.count);
        CHECK(a.position_hi == b.position_hi);
        CHECK(a.position_lo == b.position_lo);
        CHECK(a.direction_hi == b.direction_hi);
        CHECK(a.direction_lo == b.direction_lo);
    }
    // The views of all clusters in one pass, its chunks in either order:
    // fit_virtual_view's over each cluster's pixels in order, along the mean
    // and along the facet's normal, bit for bit.
    const Real tan_half = Real(0.8391), min_near = Real(0.01);
    const ClusterViews<Real> views = fit_cluster_views<Real>(serial, positions, directions, tan_half, min_near);
    const ClusterViews<Real> views_reordered =
        fit_cluster_views<Real>(serial, positions, directions, tan_half, min_near, last_first);
    REQUIRE(views.along_mean.size() == serial.clusters.size());
    REQUIRE(views.along_normal.size() == serial.clusters.size());
    auto same = [](const typename K::VirtualView& x, const typename K::VirtualView& y) {
        return x.eye == y.eye && x.forward == y.forward && x.right == y.right && x.up == y.up &&
               x.tan_half_fov == y.tan_half_fov && x.near == y.near && x.backoff == y.backoff && x.flags == y.flags;
    };
    int outside = 0;
    for (std::size_t c = 0; c < serial.clusters.size(); ++c) {
        std::vector<V> p, d;
        for (std::size_t i = 0; i < positions.size(); ++i)
            if (serial.cluster_of[i] == static_cast<int>(c)) {
                p.push_back(positions[i]);
                d.push_back(directions[i]);
            }
        const auto& sums = serial.clusters[c].sums;
        CHECK(same(views.along_mean[c], fit_virtual_view<Real>(sums, p, d, tan_half, min_near)));
        typename K::VirtualViewFit f = K::virtual_view_begin_along(
            sums, K::dodecahedron_normal(serial.clusters[c].facet), tan_half, min_near);
        for (std::size_t i = 0; i < p.size(); ++i) f = K::virtual_view_add(f, p[i], d[i]);
        CHECK(same(views.along_normal[c], K::virtual_view_finish(f)));
        CHECK(same(views_reordered.along_mean[c], views.along_mean[c]));
        CHECK(same(views_reordered.along_normal[c], views.along_normal[c]));
        outside += (views.along_mean[c].flags & BC_VIEW_DIRECTION_OUTSIDE) != 0;
    }
    MESSAGE(serial.clusters.size() << " clusters' views, " << outside << " with a direction outside along the mean");
}
