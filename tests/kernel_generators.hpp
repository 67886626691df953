// Seeded generators of moving, defocused triangles, pixel footprints and
// samples for the kernel's property tests and micro-benchmarks.
//
// Configurations are built in double; Real = float rounds them once, and the
// double oracle is then run on exactly the rounded values, so a float bound is
// judged on the inputs it saw.
#pragma once

#include <blurcull/blurcull.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace blurcull::testing {

// BLURCULL_PROPERTY_SCALE=k multiplies the sample counts of the property and
// stress tests (long runs; CI's sanitizer run scales them down). Default 1.
inline double property_scale() {
    const char* env = std::getenv("BLURCULL_PROPERTY_SCALE");
    if (!env) return 1.0;
    double k = std::atof(env);
    return k > 0.0 ? k : 1.0;
}

// splitmix64: tiny, seedable, identical on every platform.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0,1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    double signed_unit() { return uniform(-1.0, 1.0); }
    bool chance(double p) { return uniform() < p; }
    int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
    // log-uniform magnitude in [lo, hi]
    double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }

private:
    std::uint64_t state_;
};

enum class Family {
    motion,          // object or camera motion, no defocus
    defocus,         // thin lens, static geometry
    both,            // motion and defocus
    focal_plane,     // a vertex on the focal plane at t=0, or crossing it in the shutter
    near_crossing,   // vertices crossing w = 0 and the near plane
    tiny_w,          // w just above 0
    tiny_coc,        // CoC near 0
    huge_motion,     // motion of thousands of screen widths
    ray_parallel,    // vertex moving along the pixel ray (stage-2 pole inside the lens)
    degenerate,      // zero-area and sliver triangles
    extreme_scale,   // coordinates from 1e-6 to 1e6
    controlled,      // per-vertex controllable defocus (in-focus range, clamp)
};

inline const char* family_name(Family f) {
    switch (f) {
        case Family::motion: return "motion";
        case Family::defocus: return "defocus";
        case Family::both: return "both";
        case Family::focal_plane: return "focal_plane";
        case Family::near_crossing: return "near_crossing";
        case Family::tiny_w: return "tiny_w";
        case Family::tiny_coc: return "tiny_coc";
        case Family::huge_motion: return "huge_motion";
        case Family::ray_parallel: return "ray_parallel";
        case Family::degenerate: return "degenerate";
        case Family::extreme_scale: return "extreme_scale";
        case Family::controlled: return "controlled";
    }
    return "?";
}

inline std::vector<Family> all_families() {
    return {Family::motion,        Family::defocus,     Family::both,     Family::focal_plane,
            Family::near_crossing, Family::tiny_w,      Family::tiny_coc, Family::huge_motion,
            Family::ray_parallel,  Family::degenerate,  Family::extreme_scale, Family::controlled};
}

using Kd = kernel<double>;

// One configuration: a triangle, the near plane, a footprint and samples in it.
struct Config {
    Kd::MovingTriangle tri;
    double near = 0.05;
    Kd::vec2 s_lo, s_hi;  // footprint
    Kd::vec2 anchor;      // a screen position the triangle covers for some (u, v, t), if any
};

struct Sample5 {
    Kd::vec2 s, uv;
    double t;
};

inline Kd::vec2 coc_from_lens(double k, double kr_over_k, double focus, double w) {
    // thin lens with scale k in both axes: c = a + b w
    Kd::vec2 ab = Kd::thin_lens_coc(k, kr_over_k, focus);
    double c = Kd::coc_at(ab, w);
    return Kd::vec2(c, c);
}

// A random configuration of the given family. `footprint_pixels` is the
// footprint's width in pixels of a 1024-wide screen.
inline Config make_config(Rng& rng, Family family) {
    Config cfg;
    const double k = 1.5;  // projection scale
    bool motion = family != Family::defocus;
    bool defocus = family != Family::motion;
    if (family == Family::huge_motion || family == Family::near_crossing || family == Family::tiny_w ||
        family == Family::degenerate || family == Family::extreme_scale)
        defocus = rng.chance(0.6);
    if (family == Family::focal_plane || family == Family::tiny_coc || family == Family::controlled)
        motion = rng.chance(0.6);

    // Screen-space triangle around a centre, at a depth.
    double depth = rng.log_uniform(0.5, 40.0);
    Kd::vec2 centre(rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9));
    double size = rng.log_uniform(0.002, 0.3);
    Kd::vec3 view[6];  // (X, Y, w): screen position and depth, before clip
    for (int i = 0; i < 3; ++i) {
        view[i] = Kd::vec3(centre.x + size * rng.signed_unit(), centre.y + size * rng.signed_unit(),
                           depth * (1.0 + 0.3 * rng.signed_unit()));
    }
    if (family == Family::degenerate) {
        if (rng.chance(0.5)) {
            view[2] = view[0] + (view[1] - view[0]) * rng.uniform();  // collinear: zero area
        } else {
            view[2] = view[0] + (view[1] - view[0]) * rng.uniform() +
                      Kd::vec3(1e-5 * rng.signed_unit(), 1e-5 * rng.signed_unit(), 0.0);  // sliver
        }
        if (rng.chance(0.2)) view[1] = view[0];
    }
    // Motion: a common translation (camera-like) plus per-vertex jitter, depth change.
    Kd::vec3 move(0.0);
    if (motion) {
        double reach = family == Family::huge_motion ? rng.log_uniform(10.0, 5000.0) : rng.log_uniform(0.001, 0.4);
        double angle = rng.uniform(0.0, 6.283185307179586);
        move = Kd::vec3(reach * std::cos(angle), reach * std::sin(angle), 0.0);
    }
    for (int i = 0; i < 3; ++i) {
        Kd::vec3 m = move;
        if (motion) {
            m += Kd::vec3(0.05 * size * rng.signed_unit(), 0.05 * size * rng.signed_unit(),
                          view[i].z * 0.4 * rng.signed_unit());
        }
        view[i + 3] = view[i] + m;
    }
    // Clip space: x = X w.
    for (int j = 0; j < 6; ++j) {
        cfg.tri.p[j] = Kd::vec3(view[j].x * view[j].z, view[j].y * view[j].z, view[j].z);
    }
    if (family == Family::near_crossing) {
        // Move some vertex ends behind the eye or across the near plane.
        for (int j = 0; j < 6; ++j) {
            if (rng.chance(0.4)) {
                double w = rng.uniform(-2.0, 0.2);
                cfg.tri.p[j] = Kd::vec3(cfg.tri.p[j].x, cfg.tri.p[j].y, w);
            }
        }
        cfg.near = rng.log_uniform(1e-3, 0.3);
    }
    if (family == Family::tiny_w) {
        for (int j = 0; j < 6; ++j) {
            if (rng.chance(0.5)) {
                double w = rng.log_uniform(1e-7, 1e-3);
                cfg.tri.p[j] = Kd::vec3(cfg.tri.p[j].x * w / cfg.tri.p[j].z, cfg.tri.p[j].y * w / cfg.tri.p[j].z, w);
            }
        }
        cfg.near = rng.log_uniform(1e-8, 1e-4);
    }
    if (family == Family::ray_parallel) {
        // Vertex 0 slides along its own eye ray: same screen position, other depth.
        double scale = rng.uniform(0.3, 3.0);
        cfg.tri.p[3] = cfg.tri.p[0] * scale;
        if (rng.chance(0.5)) cfg.tri.p[4] = cfg.tri.p[1] * rng.uniform(0.3, 3.0);
    }
    // Lens.
    for (int j = 0; j < 6; ++j) cfg.tri.c[j] = Kd::vec2(0.0);
    if (defocus) {
        double focus = rng.log_uniform(0.5, 40.0);
        double radius = rng.log_uniform(1e-4, 0.2) * std::max(depth, 1.0);
        if (family == Family::focal_plane) {
            // Put the focal plane at a vertex's depth at t = 0, or between its ends.
            int j = rng.below(3);
            focus = rng.chance(0.5) ? cfg.tri.p[j].z
                                    : cfg.tri.p[j].z + rng.uniform() * (cfg.tri.p[j + 3].z - cfg.tri.p[j].z);
            if (!(focus > 0.0)) focus = 1.0;
        }
        if (family == Family::tiny_coc) radius = rng.log_uniform(1e-9, 1e-5);
        double aspect_x = rng.chance(0.5) ? 1.0 : 0.75;
        Kd::vec2 ab = Kd::thin_lens_coc(k, radius, focus);
        double range = family == Family::controlled ? rng.uniform(0.0, 0.3) * focus : 0.0;
        double clamp = family == Family::controlled && rng.chance(0.5) ? rng.uniform(0.0, 0.2) : 1e300;
        for (int j = 0; j < 6; ++j) {
            double c = family == Family::controlled ? Kd::coc_controlled(ab, cfg.tri.p[j].z, range, clamp)
                                                    : Kd::coc_at(ab, cfg.tri.p[j].z);
            cfg.tri.c[j] = Kd::vec2(c * aspect_x, c);
        }
    }
    if (family == Family::extreme_scale) {
        double scale = std::pow(10.0, rng.uniform(-6.0, 6.0));
        for (int j = 0; j < 6; ++j) {
            cfg.tri.p[j] *= scale;
            cfg.tri.c[j] *= scale;
        }
        cfg.near *= scale;
    }
    // Anchor: a point of the triangle seen at some (u, v, t), in front of the near plane.
    cfg.anchor = centre;
    for (int attempt = 0; attempt < 16; ++attempt) {
        double t = rng.uniform();
        Kd::vec2 uv(rng.signed_unit(), rng.signed_unit());
        double b0 = rng.uniform(), b1 = rng.uniform();
        if (b0 + b1 > 1.0) { b0 = 1.0 - b0; b1 = 1.0 - b1; }
        Kd::vec3 q = Kd::vertex_at(cfg.tri, 0, t, uv) * b0 + Kd::vertex_at(cfg.tri, 1, t, uv) * b1 +
                     Kd::vertex_at(cfg.tri, 2, t, uv) * (1.0 - b0 - b1);
        if (q.z >= cfg.near && q.z > 0.0) {
            cfg.anchor = Kd::vec2(q.x / q.z, q.y / q.z);
            break;
        }
    }
    // Footprint: one pixel of a 256..2048-wide screen, or a tile of up to 16 of them.
    double pixel = 2.0 / rng.log_uniform(256.0, 2048.0);
    Kd::vec2 extent(pixel * (rng.chance(0.7) ? 1.0 : double(1 + rng.below(16))),
                    pixel * (rng.chance(0.7) ? 1.0 : double(1 + rng.below(16))));
    Kd::vec2 offset(rng.uniform(), rng.uniform());
    cfg.s_lo = cfg.anchor - offset * extent;
    cfg.s_hi = cfg.s_lo + extent;
    return cfg;
}

// A sub-range of [lo, hi]: one of `parts` equal parts (a power of two, so
// the ends are exact, as the CPU backend's strata), or random ends (the
// stratum-box and depth-floor property tests' time and lens ranges).
inline glm::dvec2 sub_range(Rng& rng, double lo, double hi) {
    if (rng.chance(0.75)) {
        const int parts = 1 << rng.below(4);
        const int k = rng.below(parts);
        return glm::dvec2(lo + (hi - lo) * k / parts, lo + (hi - lo) * (k + 1) / parts);
    }
    const double a = rng.uniform(lo, hi), b = rng.uniform(lo, hi);
    return glm::dvec2(std::min(a, b), std::max(a, b));
}

// A value in [lo, hi]: lo or hi, each with chance 1 / choices, else uniform
// between (the property tests' samples on the ends of a bound's ranges).
inline double value_or_end(Rng& rng, double lo, double hi, int choices) {
    switch (rng.below(choices)) {
        case 0: return lo;
        case 1: return hi;
        default: return rng.uniform(lo, hi);
    }
}

// A sample in the footprint; sometimes exactly on its edges or at the ends of
// the shutter and lens ranges.
inline Sample5 make_sample(Rng& rng, const Config& cfg) {
    Sample5 s;
    auto edge_or = [&](double lo, double hi) {
        int pick = rng.below(64);
        if (pick == 0) return lo;
        if (pick == 1) return hi;
        return rng.uniform(lo, hi);
    };
    s.s = Kd::vec2(edge_or(cfg.s_lo.x, cfg.s_hi.x), edge_or(cfg.s_lo.y, cfg.s_hi.y));
    s.uv = Kd::vec2(edge_or(-1.0, 1.0), edge_or(-1.0, 1.0));
    s.t = edge_or(0.0, 1.0);
    return s;
}

// Rounding to the precision under test.
// Out of line on purpose: inlined into the stress test's run_config<float>,
// GCC 12 at -O2/-O3 (its SLP vectorizer; -fno-tree-slp-vectorize hides it)
// gave to_double(to_real(t)) the unrounded double values of t.p[5].y and .z,
// so the oracle judged float bounds on another triangle than they saw.
template <class Real>
[[gnu::noinline]] typename kernel<Real>::MovingTriangle to_real(const Kd::MovingTriangle& tri) {
    typename kernel<Real>::MovingTriangle out;
    for (int j = 0; j < 6; ++j) {
        out.p[j] = typename kernel<Real>::vec3(tri.p[j]);
        out.c[j] = typename kernel<Real>::vec2(tri.c[j]);
    }
    return out;
}

template <class Real>
[[gnu::noinline]] Kd::MovingTriangle to_double(const typename kernel<Real>::MovingTriangle& tri) {
    Kd::MovingTriangle out;
    for (int j = 0; j < 6; ++j) {
        out.p[j] = Kd::vec3(tri.p[j]);
        out.c[j] = Kd::vec2(tri.c[j]);
    }
    return out;
}

inline const char* method_name(int method) {
    switch (method) {
        case BC_CULL_BBOX: return "bbox";
        case BC_CULL_HULL: return "hull";
        case BC_CULL_DUALSPACE: return "dualspace";
        case BC_CULL_TWO_STAGE: return "clip2";
        case BC_CULL_EDGES: return "edges";
        case BC_CULL_HYPERPLANE: return "hyperplane";
    }
    return "?";
}

constexpr int method_count = 6;  // BC_CULL_* are 0 .. method_count - 1
constexpr std::array<int, method_count> all_methods{BC_CULL_BBOX, BC_CULL_HULL,  BC_CULL_DUALSPACE,
                                                    BC_CULL_TWO_STAGE, BC_CULL_EDGES, BC_CULL_HYPERPLANE};

}  // namespace blurcull::testing
