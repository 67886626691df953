// A cheap, exact-by-construction coverage test for the CPU rasterizer: a
// per-triangle setup in float after which rejecting a 5D sample (screen
// position, lens position, time) costs a few dozen multiply-adds, eight
// samples at a time with AVX2 (chosen at run time) or one at a time.
//
// It never decides alone. It rejects a sample only when two of the
// triangle's edge functions have opposite signs by more than a guard band
// that bounds the float evaluation's error plus the oracle's own rounding
// (docs/cpu-renderer.md, "The fast coverage test"): the oracle
// (kernel<Real>::covers) then rejects the sample too. Every other sample
// goes to the oracle, which also gives the hit depth. So covers() after a
// "maybe" decides exactly as covers() alone.
#pragma once

#include <blurcull/kernel.hpp>

#include <cstdint>

namespace blurcull::frontend {

// Which terms a triangle's vertices have, on the float-rounded setup: the
// evaluation skips the ones that are exactly zero (skipping them is exact).
enum class CoverageVariant : std::uint8_t {
    fixed,    // static and in focus: the vertices do not depend on the sample
    motion,   // moving, no lens shear
    defocus,  // static, sheared by the lens
    both,     // moving and sheared
};

// One vertex coordinate as the per-sample evaluation sees it: at time t and
// lens coordinate l, value = (base + t delta) + l (coc + t coc_delta).
struct CoverageVertex {
    float x, dx, cx, dcx;  // clip x and its CoC, with their changes over the shutter
    float y, dy, cy, dcy;
    float w, dw;
};

// The screen box (NDC) the samples given to a setup lie in.
struct SampleBox {
    double x0, y0, x1, y1;
};

struct CoverageSetup;

// The evaluations a setup runs (chosen once per setup, for its variant and the CPU).
using CoverageOne = bool (*)(const CoverageSetup&, float sx, float sy, float u, float v, float t);
using CoverageLanes = std::uint32_t (*)(const CoverageSetup&, const float* sx, const float* sy, const float* u,
                                        const float* v, const float* t, std::uint32_t wanted);

// The per-triangle setup. Vertices and samples are taken relative to a
// centre near the triangle, so the edge values are not the small
// differences of large products that they are in absolute screen
// coordinates (the guard band shrinks with the box). `usable` false: the float evaluation could
// overflow or the bound is not finite; may_cover then keeps every sample.
struct CoverageSetup {
    CoverageVertex vertex[3];
    float band[3];  // guard band of edge k (the edge opposite vertex k)
    float centre_x = 0.0f, centre_y = 0.0f;
    CoverageVariant variant = CoverageVariant::both;
    bool usable = false;
    CoverageOne one = nullptr;
    CoverageLanes lanes = nullptr;
};

// The setup for `tri`, for samples with screen position in `box`, lens
// coordinates in [-1, 1] and time in [0, 1]. The guard bands bound the
// difference between the float evaluation and kernel<Real>::covers's own
// edge values (Real = float or double).
template <class Real>
CoverageSetup make_coverage_setup(const typename kernel<Real>::MovingTriangle& tri, const SampleBox& box);

// False only if kernel<Real>::covers(tri, s, uv, t, ...) is false for the
// triangle of `setup` (for samples inside the setup's box). Sample coordinates are rounded to float (exact for
// the CPU backend's samples).
inline bool may_cover(const CoverageSetup& setup, float sx, float sy, float u, float v, float t) {
    return setup.one(setup, sx, sy, u, v, t);
}

// Up to 32 samples (sx[i], sy[i], u[i], v[i], t[i]), i < 32: bit i of the
// result is may_cover for sample i, for every bit i set in `wanted` (the
// others are unspecified; the arrays must hold the eight-sample batches
// that have a wanted bit). Eight at a time with AVX2 where the CPU has it.
inline std::uint32_t may_cover32(const CoverageSetup& setup, const float* sx, const float* sy, const float* u,
                                 const float* v, const float* t, std::uint32_t wanted) {
    return setup.lanes(setup, sx, sy, u, v, t, wanted);
}

// may_cover32 on the scalar path whatever the CPU (to compare the two).
std::uint32_t may_cover32_scalar(const CoverageSetup& setup, const float* sx, const float* sy, const float* u,
                                 const float* v, const float* t, std::uint32_t wanted);

// "avx2" or "scalar": the code may_cover32 runs on this CPU.
const char* fast_coverage_isa();

}  // namespace blurcull::frontend
