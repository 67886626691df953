// Motion segments (detail/motion_segment_body.inl): the window, the local
// time and the map of a segment's shutter interval back to shutter time.
// The property: a segment's bounds, evaluated at the sample's local time and
// mapped back with segment_shutter_range, never drop a sample the double
// oracle says the segment covers (0 false culls, float and double).
#include "kernel_generators.hpp"

#include <doctest/doctest.h>

#include <cinttypes>
#include <cstdio>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

// A shutter time inside the window, sometimes exactly on its ends.
template <class Real>
Real time_in(Rng& rng, typename kernel<Real>::vec2 window) {
    const int pick = rng.below(32);
    if (pick == 0) return window.x;
    if (pick == 1) return window.y;
    return static_cast<Real>(rng.uniform(double(window.x), double(window.y)));
}

struct SegmentTally {
    std::uint64_t samples = 0, covered = 0, false_culls = 0, outside_window = 0;
};

// One configuration as segment k of K: bounds in local time, samples drawn in
// shutter time, the oracle at the sample's local time.
template <class Real>
void judge_segment(const Config& cfg, Rng& rng, SegmentTally& tally) {
    using K = kernel<Real>;
    const typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
    const Kd::MovingTriangle tri_d = to_double<Real>(tri);
    const Real near = static_cast<Real>(cfg.near);
    const typename K::vec2 lo(cfg.s_lo), hi(cfg.s_hi);
    const int segments = 1 + rng.below(64);
    const typename K::vec2 window = K::segment_window(rng.below(segments), segments);
    for (int method : all_methods) {
        const typename K::SampleBounds bounds = K::sample_bounds(tri, lo, hi, method);
        const typename K::vec2 range = K::segment_shutter_range(window, K::sample_time_range(bounds));
        for (int n = 0; n < 24; ++n) {
            const Sample5 smp = make_sample(rng, cfg);
            const typename K::vec2 s = glm::clamp(typename K::vec2(smp.s), lo, hi);
            const typename K::vec2 uv(smp.uv);
            const Real t = time_in<Real>(rng, window);
            if (!K::segment_holds(window, t)) continue;  // the closed end of an inner window
            const Real local = K::segment_local_time(window, t);
            ++tally.samples;
            double depth = 0.0;
            if (!Kd::covers(tri_d, Kd::vec2(s), Kd::vec2(uv), double(local), double(near), depth)) continue;
            ++tally.covered;
            if (!K::sample_passes(bounds, uv, local) || t < range.x || t > range.y) {
                if (tally.false_culls < 3)
                    std::printf("FALSE CULL [%s, %s] window (%a, %a) t %a local %a range (%a, %a)\n",
                                sizeof(Real) == 4 ? "float" : "double", method_name(method), double(window.x),
                                double(window.y), double(t), double(local), double(range.x), double(range.y));
                ++tally.false_culls;
            }
        }
    }
}

template <class Real>
void check_segments_conservative(const char* precision) {
    SegmentTally tally;
    Rng rng(0x5e65e600u + sizeof(Real));
    const std::uint64_t target = static_cast<std::uint64_t>(1000000 * property_scale());
    for (std::uint64_t configs = 0; tally.covered < target && configs < 40 * target; ++configs) {
        const std::vector<Family> families = all_families();
        judge_segment<Real>(make_config(rng, families[configs % families.size()]), rng, tally);
    }
    std::printf("%s: %" PRIu64 " segment samples, %" PRIu64 " covered, %" PRIu64 " false culls\n", precision,
                tally.samples, tally.covered, tally.false_culls);
    CHECK(tally.covered >= target);
    CHECK(tally.false_culls == 0);
}

// The two maps alone: every time the window holds has a local time in
// [0, 1], and lies in the mapped range of any local interval holding it.
template <class Real>
void check_maps_round_trip() {
    using K = kernel<Real>;
    Rng rng(0x3a95u + sizeof(Real));
    std::uint64_t checked = 0, escaped = 0;
    for (int n = 0; n < 400000; ++n) {
        const int segments = 1 + rng.below(1024);
        const typename K::vec2 window = K::segment_window(rng.below(segments), segments);
        const Real t = time_in<Real>(rng, window);
        if (!K::segment_holds(window, t)) continue;
        const Real local = K::segment_local_time(window, t);
        REQUIRE(local >= Real(0));
        REQUIRE(local <= Real(1));
        // A tight local interval around the sample's local time, its ends
        // sometimes the value itself.
        const Real a = rng.chance(0.3) ? local : static_cast<Real>(double(local) - rng.uniform(0.0, 1e-3));
        const Real b = rng.chance(0.3) ? local : static_cast<Real>(double(local) + rng.uniform(0.0, 1e-3));
        if (!(a <= local && local <= b)) continue;
        const typename K::vec2 range = K::segment_shutter_range(window, typename K::vec2(a, b));
        ++checked;
        if (t < range.x || t > range.y) ++escaped;
    }
    INFO("checked ", checked);
    CHECK(checked > 100000);
    CHECK(escaped == 0);
}

}  // namespace

TEST_CASE("segment windows tile the shutter: one segment per time, the last closed") {
    for (int segments : {1, 2, 3, 7, 64, 1024}) {
        CHECK(kerneld::segment_window(0, segments).x == 0.0);
        CHECK(kerneld::segment_window(segments - 1, segments).y == 1.0);
        for (double t : {0.0, 0.25, 0.5, 1.0 / 3.0, 0.999, 1.0}) {
            int holders = 0;
            for (int k = 0; k < segments; ++k) holders += kerneld::segment_holds(kerneld::segment_window(k, segments), t);
            INFO("K ", segments, " t ", t);
            CHECK(holders == 1);
        }
    }
    // One segment is the whole shutter and the identity map: today's images.
    const kernelf::vec2 whole = kernelf::segment_window(0, 1);
    for (float t : {0.0f, 0.1f, 0.7f, 1.0f}) CHECK(kernelf::segment_local_time(whole, t) == t);
    CHECK(kerneld::segment_local_time(kerneld::vec2(0.25, 0.5), 0.375) == 0.5);
    const kerneld::vec2 empty = kerneld::segment_shutter_range(kerneld::vec2(0.25, 0.5), kerneld::vec2(1.0, 0.0));
    CHECK(empty.x > empty.y);
    const kerneld::vec2 mapped = kerneld::segment_shutter_range(kerneld::vec2(0.25, 0.5), kerneld::vec2(0.0, 0.5));
    CHECK(mapped.x == 0.25);
    CHECK(mapped.y == doctest::Approx(0.375).epsilon(1e-12));
}

TEST_CASE_TEMPLATE("segment maps are conservative round trips", Real, float, double) {
    check_maps_round_trip<Real>();
}

TEST_CASE("a segment's bounds in local time are conservative against the double oracle, float") {
    check_segments_conservative<float>("float");
}

TEST_CASE("a segment's bounds in local time are conservative against the double oracle, double") {
    check_segments_conservative<double>("double");
}
