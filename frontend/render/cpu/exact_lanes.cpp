#include "render/cpu/exact_lanes.hpp"

#include "render/common/cpu_features.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define BLURCULL_EXACT_X86 1
#else
#define BLURCULL_EXACT_X86 0
#endif

namespace blurcull::frontend {

std::uint32_t covers4_scalar(const kerneld::MovingTriangle& tri, const double* sx, const double* sy, const double* u,
                             const double* v, const double* t, double near, double* depth) {
    std::uint32_t covered = 0;
    for (int i = 0; i < 4; ++i) {
        if (kerneld::covers(tri, kerneld::vec2(sx[i], sy[i]), kerneld::vec2(u[i], v[i]), t[i], near, depth[i]))
            covered |= 1u << i;
    }
    return covered;
}

namespace {

#if BLURCULL_EXACT_X86
const bool has_avx = cpu_has_avx();

// A sheared vertex on four lanes, as vertex_at computes it.
struct Vertex4 {
    __m256d x, y, w;
};

// (1 - t) a + t b: vertex_at's interpolation, a product each, then the sum.
__attribute__((target("avx"))) inline __m256d lerp4(__m256d one_minus_t, __m256d t, double a, double b) {
    return _mm256_add_pd(_mm256_mul_pd(one_minus_t, _mm256_set1_pd(a)), _mm256_mul_pd(t, _mm256_set1_pd(b)));
}

// vertex_at(tri, i, t, (u, v)): (p.x + u c.x, p.y + v c.y, p.z).
__attribute__((target("avx"))) inline Vertex4 vertex4(const kerneld::MovingTriangle& tri, int i, __m256d one_minus_t,
                                                      __m256d t, __m256d u, __m256d v) {
    const glm::dvec3& p0 = tri.p[i];
    const glm::dvec3& p1 = tri.p[i + 3];
    const glm::dvec2& c0 = tri.c[i];
    const glm::dvec2& c1 = tri.c[i + 3];
    const __m256d cx = lerp4(one_minus_t, t, c0.x, c1.x), cy = lerp4(one_minus_t, t, c0.y, c1.y);
    return Vertex4{_mm256_add_pd(lerp4(one_minus_t, t, p0.x, p1.x), _mm256_mul_pd(u, cx)),
                   _mm256_add_pd(lerp4(one_minus_t, t, p0.y, p1.y), _mm256_mul_pd(v, cy)),
                   lerp4(one_minus_t, t, p0.z, p1.z)};
}

// GLM's cross(a, b): (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y).
__attribute__((target("avx"))) inline Vertex4 cross4(const Vertex4& a, const Vertex4& b) {
    return Vertex4{_mm256_sub_pd(_mm256_mul_pd(a.y, b.w), _mm256_mul_pd(b.y, a.w)),
                   _mm256_sub_pd(_mm256_mul_pd(a.w, b.x), _mm256_mul_pd(b.w, a.x)),
                   _mm256_sub_pd(_mm256_mul_pd(a.x, b.y), _mm256_mul_pd(b.x, a.y))};
}

// bc_dot3(a, b), summed left to right.
__attribute__((target("avx"))) inline __m256d dot4(const Vertex4& a, __m256d bx, __m256d by, __m256d bz) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a.x, bx), _mm256_mul_pd(a.y, by)), _mm256_mul_pd(a.w, bz));
}

// p q + r s: a pair of bc_det_terms' products, then their sum.
__attribute__((target("avx"))) inline __m256d pair4(__m256d p, __m256d q, __m256d r, __m256d s) {
    return _mm256_add_pd(_mm256_mul_pd(p, q), _mm256_mul_pd(r, s));
}

// a - b.
__attribute__((target("avx"))) inline Vertex4 sub4(const Vertex4& a, const Vertex4& b) {
    return Vertex4{_mm256_sub_pd(a.x, b.x), _mm256_sub_pd(a.y, b.y), _mm256_sub_pd(a.w, b.w)};
}

// |x| + |y| + |w| (sign: -0.0 on every lane), as bc_oracle_pivot sums it.
__attribute__((target("avx"))) inline __m256d l1_norm4(const Vertex4& a, __m256d sign) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_andnot_pd(sign, a.x), _mm256_andnot_pd(sign, a.y)),
                         _mm256_andnot_pd(sign, a.w));
}

// b on the lanes where mask is set, a elsewhere.
__attribute__((target("avx"))) inline Vertex4 select4(const Vertex4& a, const Vertex4& b, __m256d mask) {
    return Vertex4{_mm256_blendv_pd(a.x, b.x, mask), _mm256_blendv_pd(a.y, b.y, mask),
                   _mm256_blendv_pd(a.w, b.w, mask)};
}

// (x - sx w, y - sy w, w): sheared so that the sample's ray is the w axis.
__attribute__((target("avx"))) inline Vertex4 shear4(const Vertex4& a, __m256d sx, __m256d sy) {
    return Vertex4{_mm256_sub_pd(a.x, _mm256_mul_pd(sx, a.w)), _mm256_sub_pd(a.y, _mm256_mul_pd(sy, a.w)), a.w};
}

// a.x b.y - a.y b.x.
__attribute__((target("avx"))) inline __m256d cross_z4(const Vertex4& a, const Vertex4& b) {
    return _mm256_sub_pd(_mm256_mul_pd(a.x, b.y), _mm256_mul_pd(a.y, b.x));
}

struct Edges4 {
    __m256d e0, e1, e2;
};

// covers_hit's edge values in the frame sheared by the sample: the pivot's
// offset from the ray p and the edges (a, b), then e0, e1, e2 in its order.
__attribute__((target("avx"))) inline Edges4 sheared_edges4(const Vertex4& p0, const Vertex4& d1, const Vertex4& d2,
                                                            __m256d sx, __m256d sy) {
    const Vertex4 p = shear4(p0, sx, sy), s1 = shear4(d1, sx, sy), s2 = shear4(d2, sx, sy);
    return Edges4{_mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(_mm256_sub_pd(s2.y, s1.y), p.x),
                                              _mm256_mul_pd(_mm256_sub_pd(s2.x, s1.x), p.y)),
                                cross_z4(s1, s2)),
                  cross_z4(s2, p), cross_z4(p, s1)};
}

// Beyond bc_shear_limit: q = ray x p0, e0 = (d2 - d1) . q + n . ray,
// e1 = -d2 . q, e2 = d1 . q.
__attribute__((target("avx"))) inline Edges4 unsheared_edges4(const Vertex4& p0, const Vertex4& d1, const Vertex4& d2,
                                                              const Vertex4& n, __m256d sx, __m256d sy, __m256d one) {
    const Vertex4 ray{sx, sy, one};
    const Vertex4 q = cross4(ray, p0);
    const Vertex4 d21 = sub4(d2, d1);
    return Edges4{_mm256_add_pd(dot4(d21, q.x, q.y, q.w), dot4(n, sx, sy, one)),
                  _mm256_xor_pd(dot4(d2, q.x, q.y, q.w), _mm256_set1_pd(-0.0)), dot4(d1, q.x, q.y, q.w)};
}

// covers_hit's verdict and depth on four lanes. Where covers returns early
// (seen edge-on within rounding or NaN, an edge value negative, the sum not
// positive) the lane's mask is cleared instead; the values computed on such
// lanes are discarded.
__attribute__((target("avx"))) std::uint32_t covers4_avx(const kerneld::MovingTriangle& tri, const double* sx,
                                                         const double* sy, const double* u, const double* v,
                                                         const double* t, double near, double* depth) {
    const __m256d T = _mm256_loadu_pd(t), U = _mm256_loadu_pd(u), V = _mm256_loadu_pd(v);
    const __m256d SX = _mm256_loadu_pd(sx), SY = _mm256_loadu_pd(sy), one = _mm256_set1_pd(1.0);
    const __m256d one_minus_t = _mm256_sub_pd(one, T);
    const Vertex4 v0 = vertex4(tri, 0, one_minus_t, T, U, V);
    const Vertex4 v1 = vertex4(tri, 1, one_minus_t, T, U, V);
    const Vertex4 v2 = vertex4(tri, 2, one_minus_t, T, U, V);
    const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
    // bc_oracle_pivot per lane (the smallest vertex in the L1 norm, the
    // lowest index on a tie) and the vertices in cyclic order from it; then
    // covers_hit's values relative to the pivot p0, in the body's order: d1,
    // d2, n = d1 x d2, det = p0 . n and its bound 32 eps bc_det_terms(|p0|,
    // |d1|, |d2|) (|det| > bound ordered, so NaN is rejected as in C++), then
    // the edge values in the frame sheared by the sample. The edge values
    // stay in the pivot's order: only their sum and the verdict leave.
    const __m256d m0 = l1_norm4(v0, sign), m1 = l1_norm4(v1, sign), m2 = l1_norm4(v2, sign);
    const __m256d pivot1 = _mm256_cmp_pd(m1, m0, _CMP_LT_OQ);
    const __m256d pivot2 = _mm256_cmp_pd(m2, _mm256_blendv_pd(m0, m1, pivot1), _CMP_LT_OQ);
    const Vertex4 p0 = select4(select4(v0, v1, pivot1), v2, pivot2);
    const Vertex4 p1 = select4(select4(v1, v2, pivot1), v0, pivot2);
    const Vertex4 p2 = select4(select4(v2, v0, pivot1), v1, pivot2);
    const Vertex4 d1 = sub4(p1, p0), d2 = sub4(p2, p0);
    const Vertex4 n = cross4(d1, d2);
    __m256d det = dot4(p0, n.x, n.y, n.w);
    const Vertex4 a0{_mm256_andnot_pd(sign, p0.x), _mm256_andnot_pd(sign, p0.y), _mm256_andnot_pd(sign, p0.w)};
    const Vertex4 a1{_mm256_andnot_pd(sign, d1.x), _mm256_andnot_pd(sign, d1.y), _mm256_andnot_pd(sign, d1.w)};
    const Vertex4 a2{_mm256_andnot_pd(sign, d2.x), _mm256_andnot_pd(sign, d2.y), _mm256_andnot_pd(sign, d2.w)};
    const __m256d terms = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a0.x, pair4(a1.y, a2.w, a2.y, a1.w)),
                                                      _mm256_mul_pd(a0.y, pair4(a1.w, a2.x, a2.w, a1.x))),
                                        _mm256_mul_pd(a0.w, pair4(a1.x, a2.y, a2.x, a1.y)));
    const __m256d bound = _mm256_mul_pd(_mm256_set1_pd(32.0 * kerneld::bc_epsilon()), terms);
    __m256d ok = _mm256_cmp_pd(_mm256_andnot_pd(sign, det), bound, _CMP_GT_OQ);
    // The edges sheared where max(|sx|, |sy|) <= bc_shear_limit, else
    // unsheared; both (and a blend) only for a group that straddles it.
    // (max_pd(a, b) is a > b ? a : b; this order gives glm::max(|sx|, |sy|)'s NaN answer.)
    const __m256d reach = _mm256_max_pd(_mm256_andnot_pd(sign, SY), _mm256_andnot_pd(sign, SX));
    const __m256d sheared = _mm256_cmp_pd(reach, _mm256_set1_pd(kerneld::bc_shear_limit()), _CMP_LE_OQ);
    const int sheared_lanes = _mm256_movemask_pd(sheared);
    Edges4 e{};
    if (sheared_lanes != 0) e = sheared_edges4(p0, d1, d2, SX, SY);
    if (sheared_lanes != 0xF) {
        const Edges4 far = unsheared_edges4(p0, d1, d2, n, SX, SY, one);
        e = Edges4{_mm256_blendv_pd(far.e0, e.e0, sheared), _mm256_blendv_pd(far.e1, e.e1, sheared),
                   _mm256_blendv_pd(far.e2, e.e2, sheared)};
    }
    __m256d e0 = e.e0, e1 = e.e1, e2 = e.e2;
    // det < 0: all four negated (a sign flip, exact).
    const __m256d flip = _mm256_and_pd(_mm256_cmp_pd(det, zero, _CMP_LT_OQ), sign);
    e0 = _mm256_xor_pd(e0, flip);
    e1 = _mm256_xor_pd(e1, flip);
    e2 = _mm256_xor_pd(e2, flip);
    det = _mm256_xor_pd(det, flip);
    ok = _mm256_and_pd(ok, _mm256_cmp_pd(e0, zero, _CMP_GE_OQ));
    ok = _mm256_and_pd(ok, _mm256_cmp_pd(e1, zero, _CMP_GE_OQ));
    ok = _mm256_and_pd(ok, _mm256_cmp_pd(e2, zero, _CMP_GE_OQ));
    const __m256d sum = _mm256_add_pd(_mm256_add_pd(e0, e1), e2);
    ok = _mm256_and_pd(ok, _mm256_cmp_pd(sum, zero, _CMP_GT_OQ));
    const __m256d z = _mm256_div_pd(det, sum);
    ok = _mm256_and_pd(ok, _mm256_cmp_pd(z, _mm256_set1_pd(near), _CMP_GE_OQ));
    _mm256_storeu_pd(depth, z);
    return static_cast<std::uint32_t>(_mm256_movemask_pd(ok));
}
#endif

}  // namespace

std::uint32_t covers4(const kerneld::MovingTriangle& tri, const double* sx, const double* sy, const double* u,
                      const double* v, const double* t, double near, double* depth) {
#if BLURCULL_EXACT_X86
    if (has_avx) return covers4_avx(tri, sx, sy, u, v, t, near, depth);
#endif
    return covers4_scalar(tri, sx, sy, u, v, t, near, depth);
}

const char* exact_lanes_isa() {
#if BLURCULL_EXACT_X86
    if (has_avx) return "avx";
#endif
    return "scalar";
}

}  // namespace blurcull::frontend
