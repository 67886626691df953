// The exact coverage test (kernel<double>::covers, the oracle) for four
// samples at once, for the hits the fast coverage test keeps: the same
// operations in the same order as covers (vertex_at, GLM's cross, bc_dot3,
// the sign flip, the depth), four double lanes with AVX where the CPU has
// it. AVX has no FMA, so nothing is fused and every lane rounds as covers
// does: verdict and depth are covers' bit for bit (the scalar path calls
// covers itself). docs/cpu-renderer.md, "The exact test on four lanes".
#pragma once

#include <blurcull/kernel.hpp>

#include <cstdint>

namespace blurcull::frontend {

// Bit i (i < 4) set when kerneld::covers(tri, (sx[i], sy[i]), (u[i], v[i]),
// t[i], near, depth) is true; depth[i] is then its depth (unspecified
// where the bit is clear).
std::uint32_t covers4(const kerneld::MovingTriangle& tri, const double* sx, const double* sy, const double* u,
                      const double* v, const double* t, double near, double* depth);

// covers4 through kerneld::covers one lane at a time whatever the CPU (the
// reference the four-lane path is tested against).
std::uint32_t covers4_scalar(const kerneld::MovingTriangle& tri, const double* sx, const double* sy, const double* u,
                             const double* v, const double* t, double near, double* depth);

// "avx" or "scalar": the code covers4 runs on this CPU.
const char* exact_lanes_isa();

}  // namespace blurcull::frontend
