// The numerical stress families of test_kernel_stress.cpp (float limits,
// denormals, tiny w, extreme lenses, range ends, NaN/Inf), shared with
// test_kernel_gpu_arithmetic.cpp, which runs them under the GPU arithmetic
// emulation.
#pragma once

#include "kernel_generators.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace blurcull::testing {

enum class Stress {
    flt_max,        // whole configuration scaled towards FLT_MAX
    one_huge,       // one vertex end at 1e30..FLT_MAX, the rest ordinary
    denormal,       // whole configuration scaled into float's denormal range
    tiny_w,         // some w of 1e-30, or denormal w, with a tinier near plane
    tiny_w_sweep,   // some w from 1e-25 to 1e-5: the shear/position ratio across the fallback's threshold
    tiny_w_lens,    // tiny w with a thin-lens CoC c(w) = a + b w (so c ~ a)
    focus_at_near,  // focal plane on (or a hair beyond) the near plane
    lens_zero,      // lens radius exactly 0 (signed-zero CoCs), with motion
    lens_huge,      // lens radius 1e20..1e30
    lens_sweep,     // lens radius 1e3..1e22: across the fallback's threshold
    range_ends,     // ordinary triangles, samples only at range ends
    flat,           // collinear, coincident, all w = 0, all zero
    dbl_huge,       // scaled to 1e300: infinite in float, near DBL_MAX in double
    nonfinite,      // a NaN or an Inf somewhere: the documented fallback
};

inline const char* stress_name(Stress s) {
    switch (s) {
        case Stress::flt_max: return "flt_max";
        case Stress::one_huge: return "one_huge";
        case Stress::denormal: return "denormal";
        case Stress::tiny_w: return "tiny_w";
        case Stress::tiny_w_sweep: return "tiny_w_sweep";
        case Stress::tiny_w_lens: return "tiny_w_lens";
        case Stress::focus_at_near: return "focus_at_near";
        case Stress::lens_zero: return "lens_zero";
        case Stress::lens_huge: return "lens_huge";
        case Stress::lens_sweep: return "lens_sweep";
        case Stress::range_ends: return "range_ends";
        case Stress::flat: return "flat";
        case Stress::dbl_huge: return "dbl_huge";
        case Stress::nonfinite: return "nonfinite";
    }
    return "?";
}

// New families go last: each family's seed is its position, so the others keep their configurations.
inline constexpr Stress all_stress[] = {Stress::flt_max,      Stress::one_huge,   Stress::denormal,   Stress::tiny_w,
                                 Stress::focus_at_near, Stress::lens_zero, Stress::lens_huge, Stress::range_ends,
                                 Stress::flat,         Stress::dbl_huge,   Stress::nonfinite,  Stress::tiny_w_sweep,
                                 Stress::tiny_w_lens,  Stress::lens_sweep};

inline double max_abs(const Kd::MovingTriangle& tri) {
    double m = 0.0;
    for (int j = 0; j < 6; ++j) {
        m = std::max({m, std::abs(tri.p[j].x), std::abs(tri.p[j].y), std::abs(tri.p[j].z), std::abs(tri.c[j].x),
                      std::abs(tri.c[j].y)});
    }
    return m;
}

inline void scale_config(Config& cfg, double scale) {
    // Clip space is homogeneous: scaling (x, y, w), the CoCs and the near
    // plane together changes no coverage, only the magnitudes.
    for (int j = 0; j < 6; ++j) {
        cfg.tri.p[j] *= scale;
        cfg.tri.c[j] *= scale;
    }
    cfg.near *= scale;
}

// A thin lens of radius `radius` focused at `focus` on an existing triangle.
inline void set_lens(Config& cfg, double radius, double focus) {
    Kd::vec2 ab = Kd::thin_lens_coc(1.5, radius, focus);
    for (int j = 0; j < 6; ++j) {
        double c = Kd::coc_at(ab, cfg.tri.p[j].z);
        cfg.tri.c[j] = Kd::vec2(0.75 * c, c);
    }
}

inline Config make_stress_config(Rng& rng, Stress stress) {
    const Family base = rng.chance(0.5) ? Family::both : (rng.chance(0.5) ? Family::motion : Family::defocus);
    Config cfg = make_config(rng, base);
    switch (stress) {
        case Stress::flt_max: {
            double limit = double(FLT_MAX) / max_abs(cfg.tri);
            scale_config(cfg, rng.chance(0.3) ? limit : rng.log_uniform(1e30, limit));
            break;
        }
        case Stress::one_huge: {
            int j = rng.below(6);
            double big = rng.chance(0.3) ? double(FLT_MAX) : rng.log_uniform(1e30, 1e38);
            Kd::vec3 p = cfg.tri.p[j];
            double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
            cfg.tri.p[j] = p * (big / m);
            if (rng.chance(0.5)) cfg.tri.c[j] = Kd::vec2(rng.signed_unit() * big, rng.signed_unit() * big);
            break;
        }
        case Stress::denormal: {
            // FLT_MIN is 1.2e-38; below it floats lose bits down to 1.4e-45.
            double top = rng.log_uniform(1e-44, 1e-37);
            scale_config(cfg, top / max_abs(cfg.tri));
            break;
        }
        case Stress::tiny_w:
        case Stress::tiny_w_sweep:
        case Stress::tiny_w_lens: {
            double w = stress == Stress::tiny_w_sweep ? rng.log_uniform(1e-25, 1e-5)
                                                      : (rng.chance(0.5) ? 1e-30 : rng.log_uniform(1e-44, 1e-38));
            for (int j = 0; j < 6; ++j) {
                if (rng.chance(0.5)) {
                    double f = w / cfg.tri.p[j].z;
                    cfg.tri.p[j] = Kd::vec3(cfg.tri.p[j].x * f, cfg.tri.p[j].y * f, w);
                }
            }
            cfg.near = w * (rng.chance(0.5) ? 0.5 : rng.uniform(0.01, 2.0));
            // A real thin lens: c(w) = a + b w, so the tiny-w ends get c ~ a.
            if (stress == Stress::tiny_w_lens) set_lens(cfg, rng.log_uniform(1e-4, 0.5), rng.log_uniform(0.5, 40.0));
            break;
        }
        case Stress::focus_at_near: {
            cfg.near = rng.log_uniform(1e-3, 1.0);
            for (int j = 0; j < 6; ++j) {
                double w = cfg.near * rng.uniform(0.5, 3.0);
                double f = w / cfg.tri.p[j].z;
                cfg.tri.p[j] = Kd::vec3(cfg.tri.p[j].x * f, cfg.tri.p[j].y * f, w);
            }
            const double nudge[] = {0.0, 1e-7, 1e-3};
            set_lens(cfg, rng.log_uniform(1e-4, 0.5), cfg.near * (1.0 + nudge[rng.below(3)]));
            break;
        }
        case Stress::lens_zero:
            set_lens(cfg, 0.0, rng.log_uniform(0.5, 40.0));
            break;
        case Stress::lens_huge:
            set_lens(cfg, rng.chance(0.5) ? 1e30 : rng.log_uniform(1e20, 1e30), rng.log_uniform(0.5, 40.0));
            break;
        case Stress::lens_sweep:
            set_lens(cfg, rng.log_uniform(1e3, 1e22), rng.log_uniform(0.5, 40.0));
            break;
        case Stress::range_ends:
            break;
        case Stress::flat: {
            int kind = rng.below(4);
            for (int j = 0; j < 6; ++j) {
                if (kind == 0) cfg.tri.p[j] = cfg.tri.p[j % 3 == 2 ? j - 1 : j];  // two corners coincide
                if (kind == 1) cfg.tri.p[j] = cfg.tri.p[0];                      // a point
                if (kind == 2) cfg.tri.p[j].z = 0.0;                              // through the eye
                if (kind == 3) {
                    cfg.tri.p[j] = Kd::vec3(0.0);
                    cfg.tri.c[j] = Kd::vec2(0.0);
                }
            }
            break;
        }
        case Stress::dbl_huge:
            scale_config(cfg, rng.log_uniform(1e300, 1e306) / max_abs(cfg.tri));
            break;
        case Stress::nonfinite: {
            const double bad[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                  -std::numeric_limits<double>::infinity()};
            double value = bad[rng.below(3)];
            int j = rng.below(6);
            int component = rng.below(5);
            if (component < 3) cfg.tri.p[j][component] = value;
            else cfg.tri.c[j][component - 3] = value;
            break;
        }
    }
    return cfg;
}

}  // namespace blurcull::testing
