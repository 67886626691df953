// The CPU backend's fast coverage test (render/cpu/fast_coverage.hpp) against
// the oracle it stands in front of: on the kernel's property generators, in
// float and in double, it must never reject a sample that kernel<Real>::covers
// accepts (0 disagreements), and its AVX2 and scalar paths must give the
// same decision for every sample. Prints how many non-covered samples it
// rejects (the rest go to the oracle). BLURCULL_PROPERTY_SCALE=k scales it.
#include "kernel_generators.hpp"
#include "render/cpu/fast_coverage.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace blurcull;
using namespace blurcull::testing;
using blurcull::frontend::CoverageSetup;

namespace {

struct Tally {
    std::uint64_t samples = 0;
    std::uint64_t covered = 0;
    std::uint64_t rejected = 0;       // samples the fast test rejects
    std::uint64_t disagreements = 0;  // rejected, yet covered by the oracle
    std::uint64_t path_mismatches = 0;  // AVX2 and scalar (or batch and single) differ
};

// Samples as the fast test takes them: `float_samples` rounds them first (as
// the CPU backend's samples are), else the oracle sees the unrounded values.
template <class Real>
void run_config(const Config& cfg, Rng& rng, int batches, bool float_samples, Tally& tally) {
    using K = kernel<Real>;
    const typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
    const Real near = static_cast<Real>(cfg.near);
    const CoverageSetup setup =
        frontend::make_coverage_setup<Real>(tri, frontend::SampleBox{cfg.s_lo.x, cfg.s_lo.y, cfg.s_hi.x, cfg.s_hi.y});
    for (int b = 0; b < batches; ++b) {
        // 24 samples, of which one batch of eight is sometimes not wanted.
        float sx[32], sy[32], u[32], v[32], t[32];
        Real rsx[32], rsy[32], ru[32], rv[32], rt[32];
        for (int i = 0; i < 24; ++i) {
            Sample5 smp = make_sample(rng, cfg);
            const Kd::vec2 s = glm::clamp(smp.s, cfg.s_lo, cfg.s_hi);
            rsx[i] = static_cast<Real>(s.x);
            rsy[i] = static_cast<Real>(s.y);
            ru[i] = static_cast<Real>(smp.uv.x);
            rv[i] = static_cast<Real>(smp.uv.y);
            rt[i] = static_cast<Real>(smp.t);
            if (float_samples) {
                for (Real* value : {&rsx[i], &rsy[i], &ru[i], &rv[i], &rt[i]}) *value = Real(float(*value));
            }
            sx[i] = float(rsx[i]);
            sy[i] = float(rsy[i]);
            u[i] = float(ru[i]);
            v[i] = float(rv[i]);
            t[i] = float(rt[i]);
        }
        const std::uint32_t wanted = rng.chance(0.5) ? 0xFFFFFFu : 0xFF00FFu;
        const std::uint32_t fast = frontend::may_cover32(setup, sx, sy, u, v, t, wanted) & wanted;
        const std::uint32_t scalar = frontend::may_cover32_scalar(setup, sx, sy, u, v, t, wanted) & wanted;
        if (fast != scalar) ++tally.path_mismatches;
        for (int i = 0; i < 24; ++i) {
            if (((wanted >> i) & 1u) == 0) continue;
            const bool maybe = (fast >> i) & 1u;
            if (maybe != frontend::may_cover(setup, sx[i], sy[i], u[i], v[i], t[i])) ++tally.path_mismatches;
            Real depth = Real(0);
            const bool covered = K::covers(tri, typename K::vec2(rsx[i], rsy[i]), typename K::vec2(ru[i], rv[i]),
                                           rt[i], near, depth);
            ++tally.samples;
            if (covered) ++tally.covered;
            if (!maybe) ++tally.rejected;
            if (covered && !maybe) ++tally.disagreements;
        }
    }
}

template <class Real>
void check_families(const char* precision, bool float_samples) {
    const int configs = static_cast<int>(1500 * property_scale());
    Tally total;
    for (Family family : all_families()) {
        Rng rng(0x5eedull * 977 + static_cast<std::uint64_t>(family) * 31 + (float_samples ? 7 : 0));
        Tally tally;
        for (int c = 0; c < configs; ++c) run_config<Real>(make_config(rng, family), rng, 3, float_samples, tally);
        const std::uint64_t missed = tally.samples - tally.covered;
        std::printf("fast coverage %-6s %-13s samples %-7s %8llu covered %8llu rejected %5.1f%% of the rest, "
                    "disagreements %llu\n",
                    precision, family_name(family), float_samples ? "float" : "double",
                    static_cast<unsigned long long>(tally.samples), static_cast<unsigned long long>(tally.covered),
                    missed ? 100.0 * double(tally.rejected) / double(missed) : 0.0,
                    static_cast<unsigned long long>(tally.disagreements));
        CHECK_MESSAGE(tally.disagreements == 0, family_name(family));
        CHECK_MESSAGE(tally.path_mismatches == 0, family_name(family));
        total.samples += tally.samples;
        total.covered += tally.covered;
        total.rejected += tally.rejected;
    }
    // Not vacuous: most samples the oracle rejects are rejected without it.
    CHECK(double(total.rejected) > 0.5 * double(total.samples - total.covered));
}

}  // namespace

TEST_CASE("fast coverage test: never rejects a sample the double oracle covers") {
    std::printf("fast coverage test runs on: %s\n", frontend::fast_coverage_isa());
    check_families<double>("double", false);
    check_families<double>("double", true);
}

TEST_CASE("fast coverage test: never rejects a sample the float oracle covers") {
    check_families<float>("float", true);
}

TEST_CASE("fast coverage test: a static and a moving triangle, sample by sample") {
    // Half of a screen-filling static triangle: inside accepted, far outside rejected.
    kerneld::MovingTriangle tri{};
    tri.p[0] = kerneld::vec3(-1.0, -1.0, 1.0);
    tri.p[1] = kerneld::vec3(1.0, -1.0, 1.0);
    tri.p[2] = kerneld::vec3(-1.0, 1.0, 1.0);
    for (int i = 0; i < 3; ++i) tri.p[i + 3] = tri.p[i];
    const frontend::SampleBox screen{-1.0, -1.0, 1.0, 1.0};
    CoverageSetup setup = frontend::make_coverage_setup<double>(tri, screen);
    CHECK(setup.usable);
    CHECK(setup.variant == frontend::CoverageVariant::fixed);
    CHECK(frontend::may_cover(setup, -0.5f, -0.5f, 0.0f, 0.0f, 0.5f));
    CHECK_FALSE(frontend::may_cover(setup, 0.5f, 0.5f, 0.0f, 0.0f, 0.5f));
    // Moving right by 1 over the shutter: (0.25, 0.25) is covered from t = 0.5 on.
    for (int i = 0; i < 3; ++i) tri.p[i + 3] = tri.p[i] + kerneld::vec3(1.0, 0.0, 0.0);
    setup = frontend::make_coverage_setup<double>(tri, screen);
    CHECK(setup.variant == frontend::CoverageVariant::motion);
    CHECK_FALSE(frontend::may_cover(setup, 0.25f, 0.25f, 0.0f, 0.0f, 0.1f));
    CHECK(frontend::may_cover(setup, 0.25f, 0.25f, 0.0f, 0.0f, 0.9f));
    // Overflowing coordinates: no fast decision, every sample kept.
    tri.p[0] = kerneld::vec3(1e200, 0.0, 1.0);
    setup = frontend::make_coverage_setup<double>(tri, screen);
    CHECK_FALSE(setup.usable);
    CHECK(frontend::may_cover(setup, 0.9f, 0.9f, 0.0f, 0.0f, 0.0f));
}

TEST_CASE("fast coverage test: samples exactly on an edge stay with the oracle") {
    // Edges on x = -0.25 and y = -0.25 at depth 3 (clip x = X w), moving and
    // defocused along y only, so the x = -0.25 edge is the same at every sample.
    kerneld::MovingTriangle tri{};
    const double w = 3.0;
    tri.p[0] = kerneld::vec3(-0.25 * w, -0.25 * w, w);
    tri.p[1] = kerneld::vec3(0.5 * w, -0.25 * w, w);
    tri.p[2] = kerneld::vec3(-0.25 * w, 0.5 * w, w);
    for (int i = 0; i < 3; ++i) {
        tri.p[i + 3] = tri.p[i] + kerneld::vec3(0.0, 0.1, 0.0);
        tri.c[i] = kerneld::vec2(0.0, 0.05);
        tri.c[i + 3] = kerneld::vec2(0.0, 0.05);
    }
    const CoverageSetup setup = frontend::make_coverage_setup<double>(tri, frontend::SampleBox{-0.3, -0.3, 0.6, 0.6});
    Rng rng(99);
    int covered = 0;
    for (int n = 0; n < 4000; ++n) {
        const float sy = float(rng.uniform(-0.2, 0.3));
        const float u = float(rng.signed_unit()), v = float(rng.signed_unit()), t = float(rng.uniform());
        double depth = 0.0;
        if (!kerneld::covers(tri, kerneld::vec2(-0.25, sy), kerneld::vec2(u, v), t, 0.05, depth)) continue;
        ++covered;
        CHECK(frontend::may_cover(setup, -0.25f, sy, u, v, t));
    }
    CHECK(covered > 1000);
}
