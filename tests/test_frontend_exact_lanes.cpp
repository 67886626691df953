// The CPU backend's four-lane exact test (render/cpu/exact_lanes.hpp) against
// kerneld::covers, the oracle it must reproduce: on the kernel's property
// generators (every family, samples inside and around the triangle, on its
// edges, with float-rounded and unrounded coordinates), covers4 and its
// scalar path must give covers' verdict for every lane and, on covered
// lanes, its depth bit for bit: 0 disagreements. BLURCULL_PROPERTY_SCALE=k
// scales it.
#include "kernel_generators.hpp"
#include "render/cpu/exact_lanes.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

struct Tally {
    std::uint64_t samples = 0, covered = 0, disagreements = 0, depth_mismatches = 0;
};

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void run_config(const Config& cfg, Rng& rng, bool float_samples, Tally& tally) {
    const kerneld::MovingTriangle tri = to_real<double>(cfg.tri);
    for (int batch = 0; batch < 16; ++batch) {
        double sx[4], sy[4], u[4], v[4], t[4];
        for (int i = 0; i < 4; ++i) {
            const Sample5 smp = make_sample(rng, cfg);
            sx[i] = smp.s.x;
            sy[i] = smp.s.y;
            u[i] = smp.uv.x;
            v[i] = smp.uv.y;
            t[i] = smp.t;
            if (float_samples)
                for (double* value : {&sx[i], &sy[i], &u[i], &v[i], &t[i]}) *value = double(float(*value));
        }
        double depth[4], scalar_depth[4];
        const std::uint32_t lanes = frontend::covers4(tri, sx, sy, u, v, t, cfg.near, depth);
        const std::uint32_t scalar = frontend::covers4_scalar(tri, sx, sy, u, v, t, cfg.near, scalar_depth);
        for (int i = 0; i < 4; ++i) {
            double z = 0.0;
            const bool covered = kerneld::covers(tri, kerneld::vec2(sx[i], sy[i]), kerneld::vec2(u[i], v[i]), t[i],
                                                 cfg.near, z);
            ++tally.samples;
            tally.covered += covered;
            const bool lane = (lanes >> i) & 1u, one = (scalar >> i) & 1u;
            if (lane != covered || one != covered) ++tally.disagreements;
            if (covered && lane && (!same_bits(depth[i], z) || !same_bits(scalar_depth[i], z))) ++tally.depth_mismatches;
        }
    }
}

}  // namespace

TEST_CASE("four-lane exact test: covers' verdicts and depths bit for bit on the property generators") {
    std::printf("four-lane exact test runs on: %s\n", frontend::exact_lanes_isa());
    const int configs = static_cast<int>(1500 * property_scale());
    Tally total;
    for (bool float_samples : {false, true}) {
        for (Family family : all_families()) {
            Rng rng(0xe7acull * 131 + static_cast<std::uint64_t>(family) * 17 + (float_samples ? 3 : 0));
            Tally tally;
            for (int c = 0; c < configs; ++c) run_config(make_config(rng, family), rng, float_samples, tally);
            std::printf("exact4 %-13s samples %-6s %8llu covered %8llu disagreements %llu depth mismatches %llu\n",
                        family_name(family), float_samples ? "float" : "double",
                        static_cast<unsigned long long>(tally.samples),
                        static_cast<unsigned long long>(tally.covered),
                        static_cast<unsigned long long>(tally.disagreements),
                        static_cast<unsigned long long>(tally.depth_mismatches));
            CHECK_MESSAGE(tally.disagreements == 0, family_name(family));
            CHECK_MESSAGE(tally.depth_mismatches == 0, family_name(family));
            total.samples += tally.samples;
            total.covered += tally.covered;
        }
    }
    // Not vacuous: both verdicts occur often.
    CHECK(total.covered > total.samples / 20);
    CHECK(total.covered < total.samples - total.samples / 20);
}

TEST_CASE("four-lane exact test: edge-on, behind the eye, NaN and near-plane lanes") {
    kerneld::MovingTriangle tri{};
    tri.p[0] = kerneld::vec3(-1.0, -1.0, 2.0);
    tri.p[1] = kerneld::vec3(1.0, -1.0, 2.0);
    tri.p[2] = kerneld::vec3(-1.0, 1.0, 2.0);
    for (int i = 0; i < 3; ++i) tri.p[i + 3] = tri.p[i];
    const double sx[4] = {-0.2, 0.9, -0.3, std::nan("")}, sy[4] = {-0.2, 0.9, -0.1, 0.0};
    const double u[4] = {0, 0, 0, 0}, v[4] = {0, 0, 0, 0}, t[4] = {0.5, 0.5, 0.5, 0.5};
    double depth[4];
    // Inside, outside, inside, NaN; near 1: the inside lanes hit at depth 2.
    CHECK(frontend::covers4(tri, sx, sy, u, v, t, 1.0, depth) == 0x5u);
    CHECK(depth[0] == doctest::Approx(2.0));
    // Near 3: nothing in front of the near plane.
    CHECK(frontend::covers4(tri, sx, sy, u, v, t, 3.0, depth) == 0u);
    // Mirrored winding (negative determinant): the same hits.
    std::swap(tri.p[1], tri.p[2]);
    std::swap(tri.p[4], tri.p[5]);
    CHECK(frontend::covers4(tri, sx, sy, u, v, t, 1.0, depth) == 0x5u);
    // Edge-on (all vertices on one line): zero determinant, no hit.
    tri.p[2] = kerneld::vec3(-1.0, 0.0, 2.0);
    tri.p[5] = tri.p[2];
    CHECK(frontend::covers4(tri, sx, sy, u, v, t, 1.0, depth) == 0u);
}

// covers_hit takes its edges sheared up to bc_shear_limit (2^42 in double)
// and unsheared beyond: lanes on both sides in one group, against covers.
// A triangle near the eye seen along rays far off-screen (screen positions
// up to 2^60), tilted so that the two forms round differently.
TEST_CASE("four-lane exact test: lanes on both sides of the shear limit") {
    const double limit = kerneld::bc_shear_limit();
    Rng rng(0x5ea7);
    std::uint64_t covered = 0, straddling = 0, disagreements = 0;
    for (int c = 0; c < 4000; ++c) {
        // A triangle whose projection reaches near the limit's screen positions: vertices with tiny w.
        kerneld::MovingTriangle tri{};
        const double w = std::ldexp(1.0, -40 - rng.below(8));
        for (int i = 0; i < 3; ++i) {
            tri.p[i] = kerneld::vec3(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), w * rng.uniform(0.5, 4.0));
            tri.p[i + 3] = tri.p[i] + kerneld::vec3(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), 0.0);
        }
        double sx[4], sy[4], u[4] = {0, 0, 0, 0}, v[4] = {0, 0, 0, 0}, t[4];
        int beyond = 0;
        for (int i = 0; i < 4; ++i) {
            t[i] = rng.uniform();
            // A point of the triangle at t, projected: covered or on its edges, near the limit.
            const double b0 = rng.uniform(), b1 = rng.uniform() * (1.0 - b0);
            const kerneld::vec3 q = kerneld::vertex_at(tri, 0, t[i], kerneld::vec2(0.0)) * b0 +
                                    kerneld::vertex_at(tri, 1, t[i], kerneld::vec2(0.0)) * b1 +
                                    kerneld::vertex_at(tri, 2, t[i], kerneld::vec2(0.0)) * (1.0 - b0 - b1);
            sx[i] = q.x / q.z;
            sy[i] = q.y / q.z;
            beyond += std::max(std::abs(sx[i]), std::abs(sy[i])) > limit;
        }
        straddling += beyond > 0 && beyond < 4;
        double depth[4], scalar_depth[4];
        const std::uint32_t lanes = frontend::covers4(tri, sx, sy, u, v, t, 0.0, depth);
        const std::uint32_t scalar = frontend::covers4_scalar(tri, sx, sy, u, v, t, 0.0, scalar_depth);
        for (int i = 0; i < 4; ++i) {
            double z = 0.0;
            const bool hit = kerneld::covers(tri, kerneld::vec2(sx[i], sy[i]), kerneld::vec2(u[i], v[i]), t[i], 0.0, z);
            covered += hit;
            if (((lanes >> i) & 1u) != hit || ((scalar >> i) & 1u) != hit) ++disagreements;
            if (hit && (!same_bits(depth[i], z) || !same_bits(scalar_depth[i], z))) ++disagreements;
        }
    }
    MESSAGE(covered, " covered lanes, ", straddling, " groups straddling the limit");
    CHECK(disagreements == 0);
    CHECK(straddling > 100);
    CHECK(covered > 1000);
}
