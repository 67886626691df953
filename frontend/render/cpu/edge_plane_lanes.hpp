// The edge planes of kernel<double>::sample_passes_at (bc_edge_bounds_pass_at
// at each sample's own position, widen 0) on four double lanes, for the
// CPU backend's many-sample chain (sample_chain.cpp). The same operations
// in the same order as the kernel (products then sums, never fused: "avx"
// only, no FMA), and min / max with the kernel's NaN rule, so every lane's
// decision is the kernel's bit for bit (tests/test_frontend_sample_chain.cpp).
#pragma once

#include <blurcull/kernel.hpp>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

namespace blurcull::frontend::edge_lanes {

// The kernel's min(a, b) (glm: (b < a) ? b : a) is MINPD(b, a), NaN included;
// its max(a, b) ((a < b) ? b : a) is MAXPD(b, a).
__attribute__((target("avx"))) inline __m256d kernel_min(__m256d a, __m256d b) { return _mm256_min_pd(b, a); }
__attribute__((target("avx"))) inline __m256d kernel_max(__m256d a, __m256d b) { return _mm256_max_pd(b, a); }

// A sample's position in the five dimensions, four lanes.
struct Lanes5 {
    __m256d sx, sy, u, v, t;
};

// Edge e's plane value du u + dv v + dt t + dx sx + dy sy, summed left to
// right as the kernel's vec3 expression.
__attribute__((target("avx"))) inline __m256d plane_value(const kernel<double>::BcEdgePlanes& p, int e,
                                                          const Lanes5& s) {
    __m256d value = _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(p.du[e]), s.u),
                                  _mm256_mul_pd(_mm256_set1_pd(p.dv[e]), s.v));
    value = _mm256_add_pd(value, _mm256_mul_pd(_mm256_set1_pd(p.dt[e]), s.t));
    value = _mm256_add_pd(value, _mm256_mul_pd(_mm256_set1_pd(p.dx[e]), s.sx));
    return _mm256_add_pd(value, _mm256_mul_pd(_mm256_set1_pd(p.dy[e]), s.sy));
}

// The lanes one piece's planes pass (all-ones per lane). At widen 0 the
// kernel adds reach = 0 * spread = +0 to hi and lo (spread is finite), which
// changes neither, so hi and lo are added as they are.
__attribute__((target("avx"))) inline __m256d piece_passes(const kernel<double>::BcEdgePlanes& p, const Lanes5& s) {
    const __m256d value0 = plane_value(p, 0, s), value1 = plane_value(p, 1, s), value2 = plane_value(p, 2, s);
    const __m256d hi = kernel_min(_mm256_add_pd(value0, _mm256_set1_pd(p.hi[0])),
                                  kernel_min(_mm256_add_pd(value1, _mm256_set1_pd(p.hi[1])),
                                             _mm256_add_pd(value2, _mm256_set1_pd(p.hi[2]))));
    const __m256d pass_hi = _mm256_cmp_pd(hi, _mm256_setzero_pd(), _CMP_GE_OQ);
    if (p.mode == BC_EDGE_ONE_SIDED) return pass_hi;
    const __m256d lo = kernel_max(_mm256_add_pd(value0, _mm256_set1_pd(p.lo[0])),
                                  kernel_max(_mm256_add_pd(value1, _mm256_set1_pd(p.lo[1])),
                                             _mm256_add_pd(value2, _mm256_set1_pd(p.lo[2]))));
    // !(max > 0), as the kernel: a NaN passes.
    const __m256d lo_positive = _mm256_cmp_pd(lo, _mm256_setzero_pd(), _CMP_GT_OQ);
    return _mm256_or_pd(pass_hi, _mm256_andnot_pd(lo_positive, _mm256_castsi256_pd(_mm256_set1_epi64x(-1))));
}

// The lanes the edge planes of `b` cull, OR-ed into `culled` (lanes already
// culled are not looked at again). The piece of a lane is found as
// bc_edge_piece walks: not before the first piece's start, then the first
// piece whose end is not below t, the last one only if t is not past its end;
// a lane in no piece is culled. Pieces no open lane falls in are skipped.
__attribute__((target("avx"))) inline __m256d culled_by_edges(const kernel<double>::BcEdgeBounds& b, const Lanes5& s,
                                                              __m256d culled) {
    if (b.piece[0].mode == BC_EDGE_NONE) return culled;
    const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    __m256d open = _mm256_andnot_pd(culled, all);
    // reached: lanes whose walk got to piece q.
    __m256d reached = _mm256_andnot_pd(_mm256_cmp_pd(s.t, _mm256_set1_pd(b.piece[0].time.x), _CMP_LT_OQ), all);
    culled = _mm256_or_pd(culled, _mm256_andnot_pd(reached, open));
    for (int q = 0; q < b.pieces; ++q) {
        const __m256d end = _mm256_set1_pd(b.piece[q].time.y);
        __m256d here;
        if (q + 1 < b.pieces) {
            const __m256d stops = _mm256_cmp_pd(s.t, end, _CMP_LE_OQ);
            here = _mm256_and_pd(reached, stops);
            reached = _mm256_andnot_pd(stops, reached);
        } else {
            // The last piece: t past its end is in no piece (culled).
            const __m256d past = _mm256_cmp_pd(s.t, end, _CMP_GT_OQ);
            culled = _mm256_or_pd(culled, _mm256_and_pd(_mm256_and_pd(reached, past), open));
            here = _mm256_andnot_pd(past, reached);
        }
        here = _mm256_and_pd(here, open);
        if (_mm256_movemask_pd(here) == 0) continue;
        culled = _mm256_or_pd(culled, _mm256_andnot_pd(piece_passes(b.piece[q], s), here));
    }
    return culled;
}

}  // namespace blurcull::frontend::edge_lanes

#endif
