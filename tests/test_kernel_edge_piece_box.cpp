// plane_piece_culls_box (sample_bounds_body.inl, over the internal
// bc_edge_piece_culls_box of edge_bounds_body.inl), which lets the CPU backend
// skip a shutter piece's run of time-sorted samples: where it says a piece
// culls the footprint, no sample of the piece (in the footprint, inside the
// lens ranges) may pass sample_passes_at, and none is covered by the double
// oracle. Samples at random and at the box's corners, on the property
// generators' families, float and double; not vacuous (pieces are culled).
#include "kernel_generators.hpp"

#include <doctest/doctest.h>

#include <cstdio>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

struct Tally {
    std::uint64_t pieces = 0, culled_pieces = 0, samples = 0, passed = 0, covered = 0;
};

// A value in [lo, hi]: an end (chance 1/4 each) or uniform between.
double in_range(Rng& rng, double lo, double hi) { return value_or_end(rng, lo, hi, 4); }

template <class Real>
void check_config(const Config& cfg, Rng& rng, Tally& tally) {
    using K = kernel<Real>;
    const typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
    const Kd::MovingTriangle tri_d = to_double<Real>(tri);
    const typename K::vec2 lo(cfg.s_lo), hi(cfg.s_hi);
    const typename K::SampleBounds b = K::sample_bounds(tri, lo, hi, BC_CULL_EDGES);
    if (b.empty || K::plane_pieces(b) == 0) return;
    for (int q = 0; q < K::plane_pieces(b); ++q) {
        ++tally.pieces;
        const typename K::vec2 piece_time = K::plane_piece_time(b, q);
        if (!K::plane_piece_culls_box(b, q, lo, hi)) continue;
        ++tally.culled_pieces;
        for (int n = 0; n < 64; ++n) {
            const typename K::vec2 s(static_cast<Real>(in_range(rng, double(lo.x), double(hi.x))),
                                     static_cast<Real>(in_range(rng, double(lo.y), double(hi.y))));
            const typename K::vec2 uv(static_cast<Real>(in_range(rng, double(b.u_range.x), double(b.u_range.y))),
                                      static_cast<Real>(in_range(rng, double(b.v_range.x), double(b.v_range.y))));
            const Real t = static_cast<Real>(in_range(rng, double(piece_time.x), double(piece_time.y)));
            // Only the piece's own samples (an end shared with a neighbour is the neighbour's).
            if (K::bc_edge_piece(b.edges, t) != q || !(glm::all(glm::lessThanEqual(lo, s)) && glm::all(glm::lessThanEqual(s, hi))))
                continue;
            ++tally.samples;
            if (K::sample_passes_at(b, s, uv, t)) ++tally.passed;
            double depth = 0.0;
            if (Kd::covers(tri_d, Kd::vec2(s), Kd::vec2(uv), double(t), cfg.near, depth)) ++tally.covered;
        }
    }
}

template <class Real>
void check_all(const char* precision) {
    Tally tally;
    const int configs = static_cast<int>(600 * property_scale());
    for (Family family : all_families()) {
        Rng rng(0xb0c5ull * 977 + static_cast<std::uint64_t>(family));
        for (int c = 0; c < configs; ++c) check_config<Real>(make_config(rng, family), rng, tally);
    }
    std::printf("edge piece box %-6s pieces %llu culled %llu samples %llu passed %llu covered %llu\n", precision,
                static_cast<unsigned long long>(tally.pieces), static_cast<unsigned long long>(tally.culled_pieces),
                static_cast<unsigned long long>(tally.samples), static_cast<unsigned long long>(tally.passed),
                static_cast<unsigned long long>(tally.covered));
    CHECK(tally.passed == 0);
    CHECK(tally.covered == 0);
    CHECK(tally.culled_pieces > 0);
    CHECK(tally.culled_pieces < tally.pieces);
    CHECK(tally.samples > 1000);
}

}  // namespace

TEST_CASE("edge piece box: a piece that culls the box culls every sample in it, double") { check_all<double>("double"); }

TEST_CASE("edge piece box: a piece that culls the box culls every sample in it, float") { check_all<float>("float"); }
