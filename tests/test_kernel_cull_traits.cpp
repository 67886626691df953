// The kernel's record of each cull method (cull_traits) says what the
// bounds compute: a hull only for BC_CULL_BUILDS_HULL, lens and time bounds
// only for BC_CULL_BOUNDS_SAMPLES, planes only for BC_CULL_ADDS_PLANES; and
// the public steps a backend composes (sample_bounds_without_planes,
// add_sample_planes, with_tile_planes, plane_pieces, plane_piece_time)
// give sample_bounds and sample_bounds_in_tile bit for bit. Every method,
// the property generators' families, float and double; not vacuous.
#include "kernel_generators.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

template <class V>
bool same_bits(const V& a, const V& b) {
    return std::memcmp(&a, &b, sizeof(V)) == 0;
}

// The fields sample_passes_at reads, compared bit for bit.
template <class K>
bool same_bounds(const typename K::SampleBounds& a, const typename K::SampleBounds& b) {
    if (a.empty != b.empty) return false;
    if (a.empty) return true;
    if (!same_bits(a.u_range, b.u_range) || !same_bits(a.v_range, b.v_range) || !same_bits(a.u_time_a, b.u_time_a) ||
        !same_bits(a.u_time_b, b.u_time_b) || !same_bits(a.v_time_a, b.v_time_a) ||
        !same_bits(a.v_time_b, b.v_time_b) || !same_bits(a.centre, b.centre))
        return false;
    const int pieces = K::plane_pieces(a);
    if (pieces != K::plane_pieces(b)) return false;
    for (int q = 0; q < pieces; ++q)
        if (!same_bits(K::plane_piece_time(a, q), K::plane_piece_time(b, q))) return false;
    return true;
}

struct Tally {
    std::uint64_t configs = 0, hulls = 0, bounded = 0, planes = 0, in_tile = 0, mismatches = 0;
};

template <class Real>
void check_config(const Config& cfg, Tally& tally) {
    using K = kernel<Real>;
    const typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
    const Real near = static_cast<Real>(cfg.near);
    const typename K::vec2 lo(cfg.s_lo), hi(cfg.s_hi);
    const typename K::vec2 mid = (lo + hi) * Real(0.5);
    const typename K::SampleBounds none = K::no_sample_bounds();
    ++tally.configs;
    for (int method : all_methods) {
        const int traits = K::cull_traits(method);
        const typename K::ScreenBound sb = K::screen_bound(tri, near, method);
        if (sb.hull_count > 0) {
            ++tally.hulls;
            if ((traits & BC_CULL_BUILDS_HULL) == 0) ++tally.mismatches;
        }
        const typename K::SampleBounds b = K::sample_bounds(tri, lo, hi, method);
        if ((traits & BC_CULL_BOUNDS_SAMPLES) == 0) {
            if (!same_bounds<K>(b, none)) ++tally.mismatches;
            continue;
        }
        ++tally.bounded;
        if (K::plane_pieces(b) > 0) {
            ++tally.planes;
            if ((traits & BC_CULL_ADDS_PLANES) == 0) ++tally.mismatches;
        }
        // sample_bounds composed from the public steps.
        const typename K::SampleBounds without = K::sample_bounds_without_planes(tri, lo, hi, method);
        if (K::plane_pieces(without) != 0) ++tally.mismatches;
        const typename K::SampleBounds composed =
            K::sample_bounds_apply(tri) ? K::add_sample_planes(tri, lo, hi, method, without) : without;
        if (!same_bounds<K>(b, composed)) ++tally.mismatches;
        // A quarter of the footprint inside it as a tile: sample_bounds_in_tile
        // composed from the footprint's own bounds without planes.
        if ((traits & BC_CULL_ADDS_PLANES) != 0) {
            ++tally.in_tile;
            const typename K::SampleBounds quarter = K::sample_bounds_in_tile(tri, lo, mid, method, b);
            const typename K::SampleBounds own = K::sample_bounds_without_planes(tri, lo, mid, method);
            if (!same_bounds<K>(quarter, K::with_tile_planes(lo, mid, method, own, b))) ++tally.mismatches;
        }
    }
}

template <class Real>
void check_all(const char* precision) {
    Tally tally;
    const int configs = static_cast<int>(200 * property_scale());
    for (Family family : all_families()) {
        Rng rng(0xc011ull * 31 + static_cast<std::uint64_t>(family));
        for (int c = 0; c < configs; ++c) check_config<Real>(make_config(rng, family), tally);
    }
    std::printf("cull traits %-6s configs %llu hulls %llu bounded %llu planes %llu in tile %llu mismatches %llu\n",
                precision, static_cast<unsigned long long>(tally.configs),
                static_cast<unsigned long long>(tally.hulls), static_cast<unsigned long long>(tally.bounded),
                static_cast<unsigned long long>(tally.planes), static_cast<unsigned long long>(tally.in_tile),
                static_cast<unsigned long long>(tally.mismatches));
    CHECK(tally.mismatches == 0);
    CHECK(tally.hulls > 0);
    CHECK(tally.planes > 0);
    CHECK(tally.in_tile > 0);
}

}  // namespace

TEST_CASE_TEMPLATE("cull traits: the record of each method", Real, float, double) {
    using K = kernel<Real>;
    // What each method needs, as the registry and the backends read it.
    CHECK(K::cull_traits(BC_CULL_BBOX) == 0);
    CHECK(K::cull_traits(BC_CULL_HULL) == BC_CULL_BUILDS_HULL);
    CHECK(K::cull_traits(BC_CULL_DUALSPACE) == BC_CULL_DUAL_SPACE_AXES);
    CHECK(K::cull_traits(BC_CULL_TWO_STAGE) == (BC_CULL_BUILDS_HULL | BC_CULL_TWO_STAGE_AXES));
    CHECK(K::cull_traits(BC_CULL_EDGES) ==
          (BC_CULL_BUILDS_HULL | BC_CULL_TWO_STAGE_AXES | BC_CULL_EDGE_PLANES_PER_BLOCK));
    CHECK(K::cull_traits(BC_CULL_HYPERPLANE) ==
          (BC_CULL_BUILDS_HULL | BC_CULL_TWO_STAGE_AXES | BC_CULL_HYPERPLANES_PER_TILE));
    CHECK(K::cull_traits(-1) == 0);
    CHECK(K::cull_traits(method_count) == 0);
}

TEST_CASE("cull traits: the bounds compute what the traits say, and the public steps compose them, double") {
    check_all<double>("double");
}

TEST_CASE("cull traits: the bounds compute what the traits say, and the public steps compose them, float") {
    check_all<float>("float");
}
