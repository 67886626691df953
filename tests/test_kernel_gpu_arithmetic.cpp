// The kernel under the GPU arithmetic model (issue 22; docs/glsl.md): every
// bound a backend uses, computed by kernel<gpu_float> (tests/gpu_float.hpp:
// + - * correctly rounded, division within 2.5 ULP and sqrt within 4 ULP picked
// adversarially, denormals flushed at random), must keep every sample that
// kernel<gpu_float>::covers itself accepts. That is the GPU's own test: a GLSL
// bound that culls a sample the GLSL covers accepts drops a visible hit.
//
// Judged per sample that covers accepts, for all six cull methods:
//   screen      screen_contains(screen_bound) (box and hull edges)
//   footprint   screen_footprint(screen_bound, footprint) != OUTSIDE
//   at          sample_passes_at(sample_bounds of the footprint)
//   anywhere    sample_passes(the same bounds)
//   in_tile     sample_passes_at(sample_bounds_in_tile(the quarter of the
//               footprint holding the sample, the footprint as its tile))
//   stratum     stratum_screen_box of the sample's shutter/lens stratum
// and, for every method alike, the depth floor: covers' depth >= depth_floor.
// A false cull is a culled sample that covers accepts: asserted 0. They are
// counted apart by what the double covers on the same float inputs says:
// covered there too (the triangle really covers the sample), or covered by
// the float covers' rounding only (an edge value within its rounding
// error), with the largest |s| among those; both kinds must be 0, since the
// GPU draws what its own covers accepts (docs/kernel.md, "Under the GPU
// arithmetic model").
// Families: the property families (kernel_generators.hpp), the stress
// families (stress_generators.hpp) and the fuzz seed corpus (fuzz/corpus/kernel,
// decoded as fuzz_kernel.cpp does). The rounding mode cycles per
// configuration: random, random, always-low, always-high.
// BLURCULL_PROPERTY_SCALE=k multiplies the counts (CI's sanitizer run: 0.05).
#include "gpu_float.hpp"  // first: its glm overloads must precede kernel.hpp
#include "stress_generators.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace blurcull;
using namespace blurcull::testing;

namespace {

using G = gpu_float;
using K = kernel<G>;
using Kf = kernel<float>;

enum Check { kScreen, kFootprint, kAt, kAnywhere, kInTile, kStratum, kCheckCount };
const char* check_name(int c) {
    static const char* names[] = {"screen", "footprint", "at", "anywhere", "in_tile", "stratum"};
    return names[c];
}

struct Tally {
    std::uint64_t configs = 0;
    std::uint64_t samples = 0;
    std::uint64_t covered = 0;  // covered samples, each judged by every method and check
    // Of those, the ones that only the float covers' rounding covers: the
    // double covers on the same (float) inputs says not covered.
    std::uint64_t rounding_only = 0;
    // Culled samples that covers accepts, per method and check (printed).
    std::uint64_t false_culls[method_count][kCheckCount] = {};
    // The same per sample and method, split: covered by float rounding only
    // (the double covers says no; reported, with the largest |s| among
    // them), and covered for the double covers too (asserted 0).
    std::uint64_t rounding_only_culls[method_count] = {};
    std::uint64_t exact_culls[method_count] = {};
    double rounding_cull_reach = 0.0;
    std::uint64_t floored = 0;  // covered samples with a depth floor above 0
    std::uint64_t below_floor = 0;

    std::uint64_t method_false_culls(int m) const {
        std::uint64_t n = 0;
        for (int c = 0; c < kCheckCount; ++c) n += false_culls[m][c];
        return n;
    }
    void add(const Tally& o) {
        configs += o.configs;
        samples += o.samples;
        covered += o.covered;
        rounding_only += o.rounding_only;
        rounding_cull_reach = std::max(rounding_cull_reach, o.rounding_cull_reach);
        floored += o.floored;
        below_floor += o.below_floor;
        for (int m = 0; m < method_count; ++m) {
            rounding_only_culls[m] += o.rounding_only_culls[m];
            exact_culls[m] += o.exact_culls[m];
            for (int c = 0; c < kCheckCount; ++c) false_culls[m][c] += o.false_culls[m][c];
        }
    }
};

const char* mode_name(GpuRounding m) {
    switch (m) {
        case GpuRounding::nearest: return "nearest";
        case GpuRounding::random: return "random";
        case GpuRounding::low: return "low";
        case GpuRounding::high: return "high";
    }
    return "?";
}

K::MovingTriangle to_gpu(const Kf::MovingTriangle& tri) {
    K::MovingTriangle out;
    for (int j = 0; j < 6; ++j) {
        out.p[j] = K::vec3(G(tri.p[j].x), G(tri.p[j].y), G(tri.p[j].z));
        out.c[j] = K::vec2(G(tri.c[j].x), G(tri.c[j].y));
    }
    return out;
}

// One triangle's bounds, computed once, judged on many samples; the
// per-quarter and per-stratum bounds on demand (only covered samples need them).
class Judge {
public:
    Judge(const K::MovingTriangle& tri, G near, K::vec2 lo, K::vec2 hi, int time_parts, int lens_parts,
          const char* family, Tally& tally)
        : tri_(tri), tri_d_(to_double_tri(tri)), near_(near), lo_(lo), hi_(hi), time_parts_(time_parts), lens_parts_(lens_parts),
          family_(family), tally_(tally) {
        for (int m : all_methods) {
            screen_[m] = K::screen_bound(tri, near, m);
            bounds_[m] = K::sample_bounds(tri, lo, hi, m);
            footprint_[m] = K::screen_footprint(screen_[m], lo, hi);
        }
        mid_ = lo + (hi - lo) * G(0.5);
        const float extent = std::max({1.0f, std::abs(lo.x.v), std::abs(lo.y.v), std::abs(hi.x.v), std::abs(hi.y.v)});
        extent_ = G(extent);
        floor_scale_ = K::depth_floor_scale(tri, K::vec2(G(0), G(1)), K::vec2(G(-1), G(1)), K::vec2(G(-1), G(1)),
                                            extent_);
        ++tally_.configs;
    }

    void sample(K::vec2 s, K::vec2 uv, G t) {
        ++tally_.samples;
        G depth(0);
        if (!K::covers(tri_, s, uv, t, near_, depth)) return;
        ++tally_.covered;
        double depth_d = 0.0;
        const bool exact = Kd::covers(tri_d_, Kd::vec2(double(s.x.v), double(s.y.v)),
                                      Kd::vec2(double(uv.x.v), double(uv.y.v)), double(t.v), double(near_.v), depth_d);
        if (!exact) ++tally_.rounding_only;
        const int ti = part(t.v, 0.0f, 1.0f, time_parts_);
        const int ui = part(uv.x.v, -1.0f, 1.0f, lens_parts_);
        const int vi = part(uv.y.v, -1.0f, 1.0f, lens_parts_);
        const int stratum = (ti * lens_parts_ + ui) * lens_parts_ + vi;
        const int quarter = (s.x <= mid_.x ? 0 : 1) + (s.y <= mid_.y ? 0 : 2);
        for (int m : all_methods) {
            bool pass[kCheckCount];
            pass[kScreen] = K::screen_contains(screen_[m], s);
            pass[kFootprint] = footprint_[m] != BC_FOOTPRINT_OUTSIDE;
            pass[kAt] = K::sample_passes_at(bounds_[m], s, uv, t);
            pass[kAnywhere] = K::sample_passes(bounds_[m], uv, t);
            pass[kInTile] = K::sample_passes_at(quarter_bounds(m, quarter), s, uv, t);
            const K::vec4 box = stratum_box(m, stratum, ti, ui, vi);
            pass[kStratum] = s.x >= box.x && s.x <= box.z && s.y >= box.y && s.y <= box.w;
            bool culled = false;
            for (int c = 0; c < kCheckCount; ++c) {
                if (pass[c]) continue;  // culled and covered by the GPU's covers: a false cull, rounding or not
                if (tally_.method_false_culls(m) < 3) report(m, c, s, uv, t, depth);
                ++tally_.false_culls[m][c];
            }
            for (int c = 0; c < kCheckCount; ++c) culled = culled || !pass[c];
            if (culled && !exact) {
                ++tally_.rounding_only_culls[m];
                tally_.rounding_cull_reach =
                    std::max({tally_.rounding_cull_reach, double(std::abs(s.x.v)), double(std::abs(s.y.v))});
            }
            if (culled && exact) ++tally_.exact_culls[m];
        }
        if (std::isfinite(extent_.v) && std::abs(s.x.v) <= extent_.v && std::abs(s.y.v) <= extent_.v) {
            const G floor = K::depth_floor(tri_, time_range(ti), floor_scale_);
            if (floor > G(0)) ++tally_.floored;
            if (depth < floor) {
                if (tally_.below_floor < 3)
                    std::printf("GPU DEPTH BELOW FLOOR [%s] depth %a floor %a\n", family_, double(depth.v),
                                double(floor.v));
                ++tally_.below_floor;
            }
        }
    }

private:
    static int part(float x, float lo, float hi, int parts) {
        int k = int((x - lo) / (hi - lo) * float(parts));
        return std::clamp(k, 0, parts - 1);
    }
    // Ranges with power-of-two ends (exact), as the CPU backend's strata.
    K::vec2 range(int k, float lo, float hi, int parts) const {
        const float step = (hi - lo) / float(parts);
        return K::vec2(G(lo + step * float(k)), G(lo + step * float(k + 1)));
    }
    K::vec2 time_range(int k) const { return range(k, 0.0f, 1.0f, time_parts_); }

    const K::SampleBounds& quarter_bounds(int m, int q) {
        if (!quarter_done_[m][q]) {
            const K::vec2 q_lo((q & 1) ? mid_.x : lo_.x, (q & 2) ? mid_.y : lo_.y);
            const K::vec2 q_hi((q & 1) ? hi_.x : mid_.x, (q & 2) ? hi_.y : mid_.y);
            quarter_[m][q] = K::sample_bounds_in_tile(tri_, q_lo, q_hi, m, bounds_[m]);
            quarter_done_[m][q] = true;
        }
        return quarter_[m][q];
    }
    K::vec4 stratum_box(int m, int stratum, int ti, int ui, int vi) {
        if (!stratum_done_[m][stratum]) {
            stratum_[m][stratum] = K::stratum_screen_box(tri_, near_, screen_[m], time_range(ti),
                                                         range(ui, -1.0f, 1.0f, lens_parts_),
                                                         range(vi, -1.0f, 1.0f, lens_parts_));
            stratum_done_[m][stratum] = true;
        }
        return stratum_[m][stratum];
    }

    void report(int m, int c, K::vec2 s, K::vec2 uv, G t, G depth) const {
        std::printf("GPU FALSE CULL [%s, %s, %s, mode %s]\n", family_, method_name(m), check_name(c),
                    mode_name(gpu_arithmetic().mode));
        for (int j = 0; j < 6; ++j)
            std::printf("  p[%d] = (%a, %a, %a)  c = (%a, %a)\n", j, double(tri_.p[j].x.v), double(tri_.p[j].y.v),
                        double(tri_.p[j].z.v), double(tri_.c[j].x.v), double(tri_.c[j].y.v));
        std::printf("  near %a footprint (%a, %a)-(%a, %a) strata %d x %d^2\n", double(near_.v), double(lo_.x.v),
                    double(lo_.y.v), double(hi_.x.v), double(hi_.y.v), time_parts_, lens_parts_);
        std::printf("  sample s (%a, %a) uv (%a, %a) t %a depth %a\n", double(s.x.v), double(s.y.v), double(uv.x.v),
                    double(uv.y.v), double(t.v), double(depth.v));
    }

    static Kd::MovingTriangle to_double_tri(const K::MovingTriangle& t) {
        Kd::MovingTriangle out;
        for (int j = 0; j < 6; ++j) {
            out.p[j] = Kd::vec3(double(t.p[j].x.v), double(t.p[j].y.v), double(t.p[j].z.v));
            out.c[j] = Kd::vec2(double(t.c[j].x.v), double(t.c[j].y.v));
        }
        return out;
    }

    K::MovingTriangle tri_;
    Kd::MovingTriangle tri_d_;
    G near_;
    K::vec2 lo_, hi_, mid_;
    int time_parts_, lens_parts_;
    const char* family_;
    Tally& tally_;
    K::ScreenBound screen_[method_count];
    K::SampleBounds bounds_[method_count];
    int footprint_[method_count];
    K::SampleBounds quarter_[method_count][4];
    bool quarter_done_[method_count][4] = {};
    K::vec4 stratum_[method_count][32];
    bool stratum_done_[method_count][32] = {};
    G extent_, floor_scale_;
};

// BLURCULL_GPU_MODE=nearest|random|low|high pins the mode (nearest with no
// flushing is the host's float: kernel<float> against its own float covers).
void set_mode(std::uint64_t config) {
    static const GpuRounding cycle[] = {GpuRounding::random, GpuRounding::random, GpuRounding::low, GpuRounding::high};
    gpu_arithmetic().mode = cycle[config % 4];
    if (const char* env = std::getenv("BLURCULL_GPU_MODE")) {
        const std::string m = env;
        gpu_arithmetic().mode = m == "nearest" ? GpuRounding::nearest
                                : m == "low"   ? GpuRounding::low
                                : m == "high"  ? GpuRounding::high
                                               : GpuRounding::random;
        if (m == "nearest") gpu_arithmetic().flush_chance = 0.0;
    }
}

// A random point of the triangle in barycentrics (b0, b1), a quarter of them
// on an edge, and where it is at (uv, t) in clip space.
struct TrianglePoint {
    double b0, b1;
    explicit TrianglePoint(Rng& rng) : b0(rng.uniform()), b1(rng.uniform() * (1.0 - b0)) {
        if (rng.chance(0.25)) b1 = 1.0 - b0;  // on an edge
    }
    Kd::vec3 at(const Kd::MovingTriangle& tri_d, Kd::vec2 uv, double t) const {
        return Kd::vertex_at(tri_d, 0, t, uv) * b0 + Kd::vertex_at(tri_d, 1, t, uv) * b1 +
               Kd::vertex_at(tri_d, 2, t, uv) * (1.0 - b0 - b1);
    }
};

// A point of the (float-rounded) triangle at (uv, t), projected: samples on
// and near the triangle, where the bounds are tightest.
Kd::vec2 triangle_point(Rng& rng, const Kd::MovingTriangle& tri_d, Kd::vec2 uv, double t, Kd::vec2 fallback) {
    const Kd::vec3 q = TrianglePoint(rng).at(tri_d, uv, t);
    if (q.z > 0.0 && std::isfinite(q.x / q.z) && std::isfinite(q.y / q.z)) return Kd::vec2(q.x / q.z, q.y / q.z);
    return fallback;
}

// For a triangle that sweeps past the footprint in a sliver of the shutter
// (huge_motion: 10 to 5,000 screen widths): a point of the triangle at lens
// uv and at the time its projection crosses a random line of the footprint
// along the axis it moves most on. The point q(t) of fixed barycentrics is
// linear in t, so q.x(t) = X q.w(t) is solved in closed form. Without it
// about 1.5% of that family's samples were covered.
Kd::vec2 crossing_point(Rng& rng, const Kd::MovingTriangle& tri_d, Kd::vec2 uv, Kd::vec2 lo, Kd::vec2 hi,
                        double& t, Kd::vec2 fallback) {
    const TrianglePoint point(rng);
    const Kd::vec3 q0 = point.at(tri_d, uv, 0.0), q1 = point.at(tri_d, uv, 1.0);
    if (!(q0.z > 0.0 && q1.z > 0.0)) return fallback;
    const int axis = std::abs(q1.x / q1.z - q0.x / q0.z) >= std::abs(q1.y / q1.z - q0.y / q0.z) ? 0 : 1;
    const double target = rng.uniform(lo[axis], hi[axis]);
    // (q0 + t dq)[axis] = target (q0 + t dq).w
    const Kd::vec3 dq = q1 - q0;
    const double denominator = dq[axis] - target * dq.z;
    if (!(std::abs(denominator) > 0.0)) return fallback;
    const double at = (target * q0.z - q0[axis]) / denominator;
    if (!(at >= 0.0 && at <= 1.0)) return fallback;
    const Kd::vec3 q = point.at(tri_d, uv, at);
    if (!(q.z > 0.0)) return fallback;
    t = at;
    return Kd::vec2(q.x / q.z, q.y / q.z);
}

void run_config(const Config& cfg, Rng& rng, int samples, bool range_ends, const char* family, Tally& tally) {
    const Kf::MovingTriangle tri_f = to_real<float>(cfg.tri);
    const Kd::MovingTriangle tri_d = to_double<float>(tri_f);
    const K::MovingTriangle tri = to_gpu(tri_f);
    const K::vec2 lo(G(float(cfg.s_lo.x)), G(float(cfg.s_lo.y))), hi(G(float(cfg.s_hi.x)), G(float(cfg.s_hi.y)));
    if (!(lo.x <= hi.x) || !(lo.y <= hi.y)) return;
    set_mode(tally.configs);
    const int time_parts = 1 << rng.below(4);
    const int lens_parts = 1 << rng.below(2);
    Judge judge(tri, G(float(cfg.near)), lo, hi, time_parts, lens_parts, family, tally);
    const bool sweeps = std::strcmp(family, family_name(Family::huge_motion)) == 0;
    for (int n = 0; n < samples; ++n) {
        Sample5 smp = make_sample(rng, cfg);
        if (range_ends) {
            smp.uv = Kd::vec2(rng.chance(0.5) ? -1.0 : 1.0, rng.chance(0.5) ? -1.0 : 1.0);
            smp.t = rng.chance(0.5) ? 0.0 : 1.0;
        }
        if (sweeps && n % 2 == 1) smp.s = crossing_point(rng, tri_d, smp.uv, cfg.s_lo, cfg.s_hi, smp.t, smp.s);
        const double t = double(float(smp.t));
        const Kd::vec2 uv = Kd::vec2(glm::vec2(smp.uv));
        if (!sweeps && n % 2 == 1) smp.s = triangle_point(rng, tri_d, uv, t, smp.s);
        const float sx = std::clamp(float(smp.s.x), lo.x.v, hi.x.v), sy = std::clamp(float(smp.s.y), lo.y.v, hi.y.v);
        judge.sample(K::vec2(G(sx), G(sy)), K::vec2(G(float(uv.x)), G(float(uv.y))), G(float(t)));
    }
}

void print_row(const char* kind, const char* family, const Tally& t, double seconds) {
    std::printf("%-9s %-14s %8" PRIu64 " configs %11" PRIu64 " samples %11" PRIu64 " covered (per method) %6.1f s",
                kind, family, t.configs, t.samples, t.covered, seconds);
    for (int m : all_methods) {
        std::printf(" | %s %" PRIu64 " fc", method_name(m), t.method_false_culls(m));
        for (int c = 0; c < kCheckCount; ++c)
            if (t.false_culls[m][c]) std::printf(" (%s %" PRIu64 ")", check_name(c), t.false_culls[m][c]);
    }
    std::printf(" | depth floor: %" PRIu64 " floored, %" PRIu64 " below", t.floored, t.below_floor);
    std::printf(" | covered by float rounding only: %" PRIu64 ", culled by", t.rounding_only);
    for (int m : all_methods) std::printf(" %s %" PRIu64, method_name(m), t.rounding_only_culls[m]);
    if (t.rounding_cull_reach > 0.0) std::printf(" (at |s| up to %g)", t.rounding_cull_reach);
    std::printf("\n");
    std::fflush(stdout);
}

// No false cull: neither of a sample that the double covers accepts too,
// nor of one that the float covers' rounding alone accepts.
void check_tally(const Tally& t) {
    for (int m : all_methods) {
        INFO("method ", std::string(method_name(m)));
        CHECK(t.exact_culls[m] == 0);
        CHECK(t.rounding_only_culls[m] == 0);
    }
    CHECK(t.below_floor == 0);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}


Tally run_property_family(Family family, std::uint64_t target, std::uint64_t seed, bool fuse = false) {
    GpuArithmeticScope arithmetic(GpuRounding::random, seed * 0x9e3779b97f4a7c15ull, fuse);
    const auto start = std::chrono::steady_clock::now();
    Tally t;
    Rng rng(seed);
    while (t.covered < target && t.configs < target / 8 + 1000) {
        run_config(make_config(rng, family), rng, 1024, false, family_name(family), t);
    }
    print_row(fuse ? "fused" : "property", family_name(family), t, seconds_since(start));
    MESSAGE(std::string(family_name(family)), ": ", t.covered, " covered samples per method, ", t.configs,
            " configurations");
    return t;
}

Tally run_stress_family(Stress stress, int configs, std::uint64_t seed) {
    GpuArithmeticScope arithmetic(GpuRounding::random, seed * 0x9e3779b97f4a7c15ull);
    const auto start = std::chrono::steady_clock::now();
    Tally t;
    Rng rng(seed);
    for (int n = 0; n < configs; ++n) {
        Config cfg = make_stress_config(rng, stress);
        if (rng.chance(0.1)) {
            cfg.s_lo = Kd::vec2(-1.0);
            cfg.s_hi = Kd::vec2(1.0);
        }
        run_config(cfg, rng, 96, stress == Stress::range_ends, stress_name(stress), t);
    }
    print_row("stress", stress_name(stress), t, seconds_since(start));
    MESSAGE(std::string(stress_name(stress)), ": ", t.covered, " covered samples per method");
    return t;
}

// Stress families beyond the range docs/kernel.md promises (|x|, |c| up to
// 1e6, w from 1e-7) where the model finds false culls: one_huge (a vertex w
// near FLT_MAX: a GPU's division by |w| > 2^126 may give 0, M2, so the
// screen and stratum boxes lose that vertex), tiny_w and tiny_w_lens (w of
// 1e-30 or denormal, flushed to 0 by M4: stratum boxes) and tiny_w_sweep (w
// down to 1e-25: covers' products underflow, and a flushed one puts a depth
// below its floor). Run and reported by the "known false culls" case below,
// which may fail (docs/kernel.md, "Under the GPU arithmetic model").
bool known_failing(Stress s) {
    return s == Stress::one_huge || s == Stress::tiny_w || s == Stress::tiny_w_lens || s == Stress::tiny_w_sweep;
}

std::uint64_t family_seed(Family f) { return 0x69707500 + std::uint64_t(f); }
std::uint64_t stress_seed(Stress s) { return 0x69707600 + std::uint64_t(s); }

}  // namespace

void check_property_families(double millions) {
    const std::uint64_t target = std::uint64_t(millions * 1e6 * property_scale());
    Tally total;
    for (Family family : all_families()) {
        const Tally t = run_property_family(family, target, family_seed(family));
        INFO("family ", std::string(family_name(family)));
        CHECK(t.covered >= target);
        check_tally(t);
        total.add(t);
    }
    print_row("property", "ALL", total, 0.0);
    std::uint64_t worst = 0;
    for (int m : all_methods) worst = std::max(worst, total.rounding_only_culls[m]);
    MESSAGE(total.covered, " covered samples per method, ", total.rounding_only,
            " of them covered by float rounding only (double covers: no), of which up to ", worst,
            " culled by a method");
}

// 10 million covered samples per family (each judged by all six methods) at
// scale 1, CI's Release run: about 12 minutes on one core (docs/kernel.md,
// "Under the GPU arithmetic model").
TEST_CASE("gpu arithmetic: every cull method conservative against the GPU's own covers, property families") {
    check_property_families(10.0);
}

TEST_CASE("gpu arithmetic: the stress families") {
    const int configs = std::max(50, int(4000 * property_scale()));
    Tally total;
    for (Stress stress : all_stress) {
        if (known_failing(stress)) continue;
        const Tally t = run_stress_family(stress, configs, stress_seed(stress));
        INFO("stress family ", std::string(stress_name(stress)));
        check_tally(t);
        total.add(t);
    }
    print_row("stress", "ALL", total, 0.0);
}

// Known false culls under the model beyond the documented range (issue 22,
// open): run, printed, asserted, allowed to fail.
TEST_CASE("gpu arithmetic: known false culls beyond the documented range (w > 2^126, w < 1e-25)" *
          doctest::may_fail()) {
    const int configs = std::max(50, int(4000 * property_scale()));
    for (Stress stress : all_stress) {
        if (!known_failing(stress)) continue;
        const Tally t = run_stress_family(stress, configs, stress_seed(stress));
        INFO("stress family ", std::string(stress_name(stress)));
        check_tally(t);
    }
}

// The fuzz seed corpus: each input decoded as fuzz_kernel.cpp decodes it,
// its own samples first, then many more drawn the same way (fold_unit of
// random floats) in its footprint, under every rounding mode.
TEST_CASE("gpu arithmetic: the fuzz seed corpus") {
    const std::string dir = std::string(BLURCULL_SOURCE_DIR) + "/fuzz/corpus/kernel/";
    const char* names[] = {"both_near", "defocus", "motion", "regression-near-plane-rounding"};
    const int extra = std::max(2000, int(100000 * property_scale()));
    Tally total;
    std::uint64_t seed = 0x69707700;
    for (const char* name : names) {
        std::ifstream in(dir + name, std::ios::binary);
        REQUIRE(in.good());
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        REQUIRE(bytes.size() >= 41 * 4);
        std::vector<float> f(bytes.size() / 4);
        std::memcpy(f.data(), bytes.data(), f.size() * 4);
        Kf::MovingTriangle tri_f;
        for (int j = 0; j < 6; ++j) tri_f.p[j] = Kf::vec3(f[3 * j], f[3 * j + 1], f[3 * j + 2]);
        for (int j = 0; j < 6; ++j) tri_f.c[j] = Kf::vec2(f[18 + 2 * j], f[18 + 2 * j + 1]);
        const float near = f[30 + 6];
        Kf::vec2 lo(f[37], f[38]), hi(f[39], f[40]);
        if (!(lo.x <= hi.x) || !(lo.y <= hi.y)) {
            lo = Kf::vec2(-1.0f);
            hi = Kf::vec2(1.0f);
        }
        auto fold_unit = [](float x) {
            if (!std::isfinite(x)) return 0.0f;
            float v = std::fabs(x) - std::floor(std::fabs(x));
            return v >= 0.0f && v <= 1.0f ? v : 0.0f;
        };
        const auto start = std::chrono::steady_clock::now();
        Tally t;
        Rng rng(++seed);
        for (int mode = 0; mode < 4; ++mode) {
            GpuArithmeticScope arithmetic(GpuRounding::random, seed * 0x9e3779b97f4a7c15ull + std::uint64_t(mode));
            const GpuRounding modes[] = {GpuRounding::random, GpuRounding::random, GpuRounding::low, GpuRounding::high};
            gpu_arithmetic().mode = modes[mode];
            const K::MovingTriangle tri = to_gpu(tri_f);
            const K::vec2 glo(G(lo.x), G(lo.y)), ghi(G(hi.x), G(hi.y));
            Judge judge(tri, G(near), glo, ghi, 4, 2, name, t);
            auto sample = [&](float a, float b, float c, float d, float e) {
                const float sx = lo.x + fold_unit(a) * (hi.x - lo.x), sy = lo.y + fold_unit(b) * (hi.y - lo.y);
                if (!std::isfinite(sx) || !std::isfinite(sy) || sx < lo.x || sx > hi.x || sy < lo.y || sy > hi.y)
                    return;
                judge.sample(K::vec2(G(sx), G(sy)), K::vec2(G(2.0f * fold_unit(c) - 1.0f), G(2.0f * fold_unit(d) - 1.0f)),
                             G(fold_unit(e)));
            };
            for (std::size_t at = 41; at + 5 <= f.size(); at += 5) sample(f[at], f[at + 1], f[at + 2], f[at + 3], f[at + 4]);
            const Kd::MovingTriangle tri_d = to_double<float>(tri_f);
            for (int n = 0; n < extra; ++n) {
                auto u = [&] { return float(rng.uniform()); };
                const float a = u(), b = u(), c = u(), d = u(), e = u();
                if (n % 2 == 0) {
                    sample(a, b, c, d, e);
                    continue;
                }
                // A point of the triangle at that lens position and time, as fold values.
                const Kd::vec2 p = triangle_point(rng, tri_d, Kd::vec2(2.0f * c - 1.0f, 2.0f * d - 1.0f), double(e),
                                                  Kd::vec2(lo.x, lo.y));
                const double fx = (p.x - double(lo.x)) / double(hi.x - lo.x), fy = (p.y - double(lo.y)) / double(hi.y - lo.y);
                if (fx >= 0.0 && fx < 1.0 && fy >= 0.0 && fy < 1.0) sample(float(fx), float(fy), c, d, e);
            }
        }
        print_row("corpus", name, t, seconds_since(start));
        MESSAGE(std::string(name), ": ", t.covered, " covered samples per method");
        INFO("corpus input ", std::string(name));
        check_tally(t);
        total.add(t);
    }
    print_row("corpus", "ALL", total, 0.0);
    CHECK(total.covered > 0);
}

// A GPU that ignores `precise` and fuses a*b+c (each product may be folded
// into the + or - that consumes it, at random): outside the model, so only
// reported. The property families at a tenth of their count.
TEST_CASE("gpu arithmetic: fused multiply-add (outside the model: reported, not asserted)") {
    const std::uint64_t target = std::uint64_t(1e5 * property_scale());
    Tally total;
    for (Family family : all_families()) total.add(run_property_family(family, target, family_seed(family) + 0x100, true));
    print_row("fused", "ALL", total, 0.0);
    std::uint64_t exact = 0, rounding = 0;
    for (int m : all_methods) {
        exact += total.exact_culls[m];
        rounding += total.rounding_only_culls[m];
    }
    MESSAGE("fused a*b+c: ", exact, " false culls of samples the double covers accepts too, ", rounding,
            " of samples covered by float rounding only (over all methods), ", total.below_floor,
            " depths below their floor, on ", total.covered, " covered samples");
}
