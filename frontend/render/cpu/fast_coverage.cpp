#include "render/cpu/fast_coverage.hpp"

#include "render/common/cpu_features.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define BLURCULL_HAS_X86 1
#else
#define BLURCULL_HAS_X86 0
#endif

namespace blurcull::frontend {
namespace {

// ---- the guard band: a forward error bound -------------------------------
//
// Every quantity of both evaluations (this file's float one and the oracle's)
// is tracked as a Bound: |exact value| <= m and |computed - exact| <= e, over
// every sample the setup allows. A rounded operation adds eps (|r| + e) + tiny
// (tiny: the absolute error of a result in the subnormal range).
// docs/cpu-renderer.md, "The fast coverage test", derives the rules.
struct Bound {
    double m, e;
};

struct Rounding {
    double eps, tiny;
    Bound round(double m, double e) const { return Bound{m, e + eps * (m + e) + tiny}; }
    Bound mul(Bound a, Bound b) const { return round(a.m * b.m, a.m * b.e + b.m * a.e + a.e * b.e); }
    Bound add(Bound a, Bound b) const { return round(a.m + b.m, a.e + b.e); }
    Bound fma(Bound a, Bound b, Bound c) const { return round(a.m * b.m + c.m, a.m * b.e + b.m * a.e + a.e * b.e + c.e); }
    // A value of magnitude m rounded once to this precision.
    Bound input(double m) const { return round(m, 0.0); }
};

constexpr Rounding float_rounding{0x1.0p-24, 0x1.0p-149};

template <class Real>
constexpr Rounding oracle_rounding() {
    return Rounding{std::numeric_limits<Real>::epsilon() / 2, std::numeric_limits<Real>::denorm_min()};
}

struct VertexBounds {
    Bound x, y, w;
};

// A value computed in double at setup, and a bound on its distance from the
// exact value it stands for.
struct Computed {
    double value, err;
    Bound bound() const { return Bound{std::abs(value) + err, err}; }
};

constexpr Rounding double_rounding = oracle_rounding<double>();

// p - s0 w in double (the shift to the setup's sample centre).
[[gnu::always_inline]] inline Computed shifted(double p, double w, double s0) {
    const double product = s0 * w;
    const double value = p - product;
    const double product_err = double_rounding.eps * std::abs(product) * 2 + double_rounding.tiny;
    return Computed{value, product_err + double_rounding.eps * std::abs(value) * 2 + double_rounding.tiny};
}

// b - a in double.
[[gnu::always_inline]] inline Computed difference(const Computed& a, const Computed& b) {
    const double value = b.value - a.value;
    return Computed{value, a.err + b.err + double_rounding.eps * std::abs(value) * 2 + double_rounding.tiny};
}

// The float evaluation of one sheared coordinate, fma(l, fma(t, dc, c),
// fma(t, dp, p)), from its float inputs. Skipped terms are exact zeros, so
// the "both" bound covers every variant.
[[gnu::always_inline]] inline Bound fast_coordinate(Bound p, Bound dp, Bound c, Bound dc, Bound t, Bound lens) {
    const Rounding& f = float_rounding;
    return f.fma(lens, f.fma(t, dc, c), f.fma(t, dp, p));
}

// A value computed in double, then rounded to float.
[[gnu::always_inline]] inline Bound float_input(const Computed& value) {
    const Bound exact = value.bound();
    return float_rounding.round(exact.m, exact.e);
}

// Magnitudes of one vertex coordinate's oracle inputs: both ends, CoC at both ends.
struct CoordinateMagnitude {
    double p0, p1, c0, c1;
};

// The oracle's evaluation (vertex_at): ((1 - t) p0 + t p1) + l ((1 - t) c0 + t c1),
// each operation rounded in Real.
[[gnu::always_inline]] inline Bound oracle_coordinate(const CoordinateMagnitude& q, Bound t, Bound lens, const Rounding& r) {
    const Bound one_minus_t = r.round(1.0, 0.0);
    const Bound p = r.add(r.mul(one_minus_t, Bound{q.p0, 0.0}), r.mul(t, Bound{q.p1, 0.0}));
    const Bound c = r.add(r.mul(one_minus_t, Bound{q.c0, 0.0}), r.mul(t, Bound{q.c1, 0.0}));
    return r.add(p, r.mul(lens, c));
}

// Edge (a, b): (V_a x V_b) . (sx, sy, 1). Float: fma for the cross
// product's components and the dot product, on the shifted vertices and
// sample; oracle: GLM's cross and bc_dot3, every product and sum rounded.
// The shift is a shear of determinant 1, so both stand for the same exact
// edge value.
[[gnu::always_inline]] inline Bound fast_edge(const VertexBounds& a, const VertexBounds& b, Bound s) {
    const Rounding& f = float_rounding;
    auto component = [&](Bound p, Bound q, Bound r, Bound o) { return f.fma(p, q, f.mul(r, o)); };
    const Bound nx = component(a.y, b.w, a.w, b.y);
    const Bound ny = component(a.w, b.x, a.x, b.w);
    const Bound nz = component(a.x, b.y, a.y, b.x);
    return f.fma(nx, s, f.fma(ny, s, nz));
}

// a - b, each coordinate rounded (the oracle's vertex differences).
inline VertexBounds vertex_difference(const VertexBounds& a, const VertexBounds& b, const Rounding& r) {
    return VertexBounds{r.add(a.x, b.x), r.add(a.y, b.y), r.add(a.w, b.w)};
}

// The oracle's edge values (covers_hit) with v[0] as its pivot: d1 = v1 - v0,
// d2 = v2 - v0, then in the frame sheared by the sample the pivot's offset
// p = (x0 - sx w0, y0 - sy w0) and the edges a_i = d_i.x - sx d_i.w,
// b_i = d_i.y - sy d_i.w:
//   e1 = a2 p.y - b2 p.x,   e2 = p.x b1 - p.y a1,
//   e0 = (b2 - b1) p.x - (a2 - a1) p.y + (a1 b2 - b1 a2),
// every difference, product and sum rounded. Equal to (V_a x V_b) . (sx, sy, 1)
// in exact arithmetic, so the bound is on the oracle's distance from that
// value. Edge k is opposite vertex k.
[[gnu::always_inline]] inline Bound oracle_edge_sheared(const VertexBounds v[3], int k, Bound s, const Rounding& r) {
    auto sheared = [&](Bound c, Bound w) { return r.add(c, r.mul(s, w)); };
    auto cross_z = [&](Bound ax, Bound ay, Bound bx, Bound by) { return r.add(r.mul(ax, by), r.mul(ay, bx)); };
    const VertexBounds d1 = vertex_difference(v[1], v[0], r), d2 = vertex_difference(v[2], v[0], r);
    const Bound px = sheared(v[0].x, v[0].w), py = sheared(v[0].y, v[0].w);
    const Bound a1 = sheared(d1.x, d1.w), b1 = sheared(d1.y, d1.w);
    const Bound a2 = sheared(d2.x, d2.w), b2 = sheared(d2.y, d2.w);
    if (k == 1) return cross_z(a2, b2, px, py);
    if (k == 2) return cross_z(px, py, a1, b1);
    return r.add(cross_z(r.add(a2, a1), r.add(b2, b1), px, py), cross_z(a1, b1, a2, b2));
}

// Beyond bc_shear_limit (|sx| or |sy|) the oracle's edges unsheared: with
// q = (sx, sy, 1) x v0 and n = d1 x d2,
//   e0 = (d2 - d1) . q + n . (sx, sy, 1),   e1 = -d2 . q,   e2 = d1 . q.
[[gnu::always_inline]] inline Bound oracle_edge_unsheared(const VertexBounds v[3], int k, Bound s, const Rounding& r) {
    auto cross = [&](const VertexBounds& a, const VertexBounds& b) {
        auto component = [&](Bound p, Bound q, Bound u, Bound o) { return r.add(r.mul(p, q), r.mul(u, o)); };
        return VertexBounds{component(a.y, b.w, b.y, a.w), component(a.w, b.x, b.w, a.x), component(a.x, b.y, b.x, a.y)};
    };
    auto dot = [&](const VertexBounds& a, const VertexBounds& b) {
        return r.add(r.add(r.mul(a.x, b.x), r.mul(a.y, b.y)), r.mul(a.w, b.w));
    };
    const VertexBounds ray{s, s, Bound{1.0, 0.0}};
    const VertexBounds d1 = vertex_difference(v[1], v[0], r), d2 = vertex_difference(v[2], v[0], r);
    const VertexBounds q = cross(ray, v[0]);
    if (k == 1) return dot(d2, q);
    if (k == 2) return dot(d1, q);
    return r.add(dot(vertex_difference(d2, d1, r), q), dot(cross(d1, d2), ray));
}

// The oracle's error on edge k whichever vertex it pivots on (it picks the
// smallest per sample, bc_oracle_pivot: with pivot p it sees the vertices
// from v[p] on, and edge k as its edge k - p) and whichever form its edges
// take (sheared or not, by the sample's |s|).
inline double oracle_edge_error(const VertexBounds v[3], int k, Bound s, const Rounding& r) {
    double e = 0.0;
    for (int p = 0; p < 3; ++p) {
        const VertexBounds from_pivot[3] = {v[p], v[(p + 1) % 3], v[(p + 2) % 3]};
        const int edge = (k - p + 3) % 3;
        e = std::max({e, oracle_edge_sheared(from_pivot, edge, s, r).e, oracle_edge_unsheared(from_pivot, edge, s, r).e});
    }
    return e;
}

// Rounds a non-negative double up to a float no smaller than it.
float round_up_to_float(double value) {
    if (!(value < double(std::numeric_limits<float>::max()))) return std::numeric_limits<float>::infinity();
    float f = static_cast<float>(value);
    if (double(f) < value) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

// ---- the evaluation, written once for one lane ---------------------------

template <CoverageVariant V>
inline float coordinate_at(float base, float delta, float coc, float coc_delta, float t, float lens) {
    constexpr bool moves = V == CoverageVariant::motion || V == CoverageVariant::both;
    constexpr bool sheared = V == CoverageVariant::defocus || V == CoverageVariant::both;
    const float position = moves ? std::fma(t, delta, base) : base;
    if (!sheared) return position;
    const float circle = moves ? std::fma(t, coc_delta, coc) : coc;
    return std::fma(lens, circle, position);
}

template <CoverageVariant V>
inline bool may_cover_lane(const CoverageSetup& s, float sx, float sy, float u, float v, float t) {
    const float dsx = sx - s.centre_x, dsy = sy - s.centre_y;
    float X[3], Y[3], W[3];
    for (int i = 0; i < 3; ++i) {
        const CoverageVertex& q = s.vertex[i];
        X[i] = coordinate_at<V>(q.x, q.dx, q.cx, q.dcx, t, u);
        Y[i] = coordinate_at<V>(q.y, q.dy, q.cy, q.dcy, t, v);
        W[i] = V == CoverageVariant::motion || V == CoverageVariant::both ? std::fma(t, q.dw, q.w) : q.w;
    }
    bool positive = false, negative = false;
    for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const float nx = std::fma(Y[a], W[b], -(W[a] * Y[b]));
        const float ny = std::fma(W[a], X[b], -(X[a] * W[b]));
        const float nz = std::fma(X[a], Y[b], -(Y[a] * X[b]));
        const float e = std::fma(nx, dsx, std::fma(ny, dsy, nz));
        positive = positive || e > s.band[k];
        negative = negative || e < -s.band[k];
    }
    return !(positive && negative);
}

template <CoverageVariant V>
std::uint32_t may_cover32_lanes(const CoverageSetup& s, const float* sx, const float* sy, const float* u,
                                const float* v, const float* t, std::uint32_t wanted) {
    std::uint32_t bits = 0;
    for (int b = 0; b < 32; b += 8) {
        if (((wanted >> b) & 0xFFu) == 0) continue;
        for (int i = b; i < b + 8; ++i) {
            if (may_cover_lane<V>(s, sx[i], sy[i], u[i], v[i], t[i])) bits |= 1u << i;
        }
    }
    return bits;
}

template <class Evaluate>
auto by_variant(CoverageVariant variant, Evaluate evaluate) {
    switch (variant) {
        case CoverageVariant::fixed: return evaluate(std::integral_constant<CoverageVariant, CoverageVariant::fixed>{});
        case CoverageVariant::motion: return evaluate(std::integral_constant<CoverageVariant, CoverageVariant::motion>{});
        case CoverageVariant::defocus: return evaluate(std::integral_constant<CoverageVariant, CoverageVariant::defocus>{});
        case CoverageVariant::both: break;
    }
    return evaluate(std::integral_constant<CoverageVariant, CoverageVariant::both>{});
}

#if BLURCULL_HAS_X86
// coordinate_at on eight lanes.
template <CoverageVariant V>
__attribute__((target("avx2,fma"))) inline __m256 coordinate8(float base, float delta, float coc, float coc_delta,
                                                              __m256 t, __m256 lens) {
    constexpr bool moves = V == CoverageVariant::motion || V == CoverageVariant::both;
    constexpr bool sheared = V == CoverageVariant::defocus || V == CoverageVariant::both;
    const __m256 position =
        moves ? _mm256_fmadd_ps(t, _mm256_set1_ps(delta), _mm256_set1_ps(base)) : _mm256_set1_ps(base);
    if (!sheared) return position;
    const __m256 circle =
        moves ? _mm256_fmadd_ps(t, _mm256_set1_ps(coc_delta), _mm256_set1_ps(coc)) : _mm256_set1_ps(coc);
    return _mm256_fmadd_ps(lens, circle, position);
}

// may_cover_lane's operations in the same order on eight lanes; FMA rounds
// once in both, so every lane's decision equals may_cover_lane's. Out of
// line and broadcasting the setup itself: hoisted out of a loop over
// batches, the 36 broadcasts spill to the stack, which costs more per call
// than it saves at 16 spp (two batches a pixel).
template <CoverageVariant V>
[[gnu::noinline]] __attribute__((target("avx2,fma"))) std::uint32_t may_cover8_avx2(const CoverageSetup& s, const float* sx,
                                                                  const float* sy, const float* u, const float* v,
                                                                  const float* t) {
    constexpr bool moves = V == CoverageVariant::motion || V == CoverageVariant::both;
    const __m256 T = _mm256_loadu_ps(t), U = _mm256_loadu_ps(u), Vl = _mm256_loadu_ps(v);
    const __m256 SX = _mm256_sub_ps(_mm256_loadu_ps(sx), _mm256_set1_ps(s.centre_x));
    const __m256 SY = _mm256_sub_ps(_mm256_loadu_ps(sy), _mm256_set1_ps(s.centre_y));
    __m256 X[3], Y[3], W[3];
    for (int i = 0; i < 3; ++i) {
        const CoverageVertex& q = s.vertex[i];
        X[i] = coordinate8<V>(q.x, q.dx, q.cx, q.dcx, T, U);
        Y[i] = coordinate8<V>(q.y, q.dy, q.cy, q.dcy, T, Vl);
        W[i] = moves ? _mm256_fmadd_ps(T, _mm256_set1_ps(q.dw), _mm256_set1_ps(q.w)) : _mm256_set1_ps(q.w);
    }
    __m256 positive = _mm256_setzero_ps(), negative = _mm256_setzero_ps();
    for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const __m256 nx = _mm256_fmsub_ps(Y[a], W[b], _mm256_mul_ps(W[a], Y[b]));
        const __m256 ny = _mm256_fmsub_ps(W[a], X[b], _mm256_mul_ps(X[a], W[b]));
        const __m256 nz = _mm256_fmsub_ps(X[a], Y[b], _mm256_mul_ps(Y[a], X[b]));
        const __m256 e = _mm256_fmadd_ps(nx, SX, _mm256_fmadd_ps(ny, SY, nz));
        const __m256 band = _mm256_set1_ps(s.band[k]);
        positive = _mm256_or_ps(positive, _mm256_cmp_ps(e, band, _CMP_GT_OQ));
        negative = _mm256_or_ps(negative, _mm256_cmp_ps(e, _mm256_sub_ps(_mm256_setzero_ps(), band), _CMP_LT_OQ));
    }
    const int rejected = _mm256_movemask_ps(_mm256_and_ps(positive, negative));
    return ~static_cast<std::uint32_t>(rejected) & 0xFFu;
}

// Up to four batches of eight, those with a wanted lane.
template <CoverageVariant V>
std::uint32_t may_cover32_avx2(const CoverageSetup& s, const float* sx, const float* sy, const float* u,
                               const float* v, const float* t, std::uint32_t wanted) {
    std::uint32_t bits = 0;
    for (int b = 0; b < 32; b += 8) {
        if (((wanted >> b) & 0xFFu) == 0) continue;
        bits |= may_cover8_avx2<V>(s, sx + b, sy + b, u + b, v + b, t + b) << b;
    }
    return bits;
}

// One sample with the hardware FMA inlined (std::fma is a library call
// where the compiler may not assume the instruction).
template <CoverageVariant V>
__attribute__((target("avx2,fma"))) bool may_cover_fma(const CoverageSetup& s, float sx, float sy, float u, float v,
                                                       float t) {
    return may_cover_lane<V>(s, sx, sy, u, v, t);
}

#endif

const bool has_avx2 = cpu_has_avx2() && cpu_has_fma();

bool keep_one(const CoverageSetup&, float, float, float, float, float) { return true; }
std::uint32_t keep_all(const CoverageSetup&, const float*, const float*, const float*, const float*, const float*,
                       std::uint32_t wanted) {
    return wanted;
}

// The evaluations for a variant on this CPU.
template <CoverageVariant V>
void choose_evaluations(CoverageSetup& setup) {
#if BLURCULL_HAS_X86
    if (has_avx2) {
        setup.one = &may_cover_fma<V>;
        setup.lanes = &may_cover32_avx2<V>;
        return;
    }
#endif
    setup.one = &may_cover_lane<V>;
    setup.lanes = &may_cover32_lanes<V>;
}

}  // namespace

template <class Real>
CoverageSetup make_coverage_setup(const typename kernel<Real>::MovingTriangle& tri, const SampleBox& box) {
    CoverageSetup setup;
    // The centre the vertices and samples are shifted to (a float, so the
    // per-sample subtraction is one rounding), and the largest offset from it.
    setup.centre_x = static_cast<float>(0.5 * (box.x0 + box.x1));
    setup.centre_y = static_cast<float>(0.5 * (box.y0 + box.y1));
    const double reach = std::max({box.x1 - setup.centre_x, setup.centre_x - box.x0, box.y1 - setup.centre_y,
                                   setup.centre_y - box.y0, 0.0}) *
                         (1.0 + 0x1.0p-40);
    const double extent = std::max({std::abs(box.x0), std::abs(box.x1), std::abs(box.y0), std::abs(box.y1)});
    bool moves = false, sheared = false;
    VertexBounds fast[3], oracle[3];
    const Rounding r = oracle_rounding<Real>();
    const Rounding& f = float_rounding;
    const Bound t_fast = f.input(1.0), lens_fast = f.input(1.0);
    const Bound t_oracle{1.0, 0.0}, lens_oracle{1.0, 0.0};
    double largest = 0.0;  // of the float coordinates' magnitude bounds
    for (int i = 0; i < 3; ++i) {
        const double x0 = double(tri.p[i].x), y0 = double(tri.p[i].y), w0 = double(tri.p[i].z);
        const double x1 = double(tri.p[i + 3].x), y1 = double(tri.p[i + 3].y), w1 = double(tri.p[i + 3].z);
        const double cx0 = double(tri.c[i].x), cy0 = double(tri.c[i].y);
        const double cx1 = double(tri.c[i + 3].x), cy1 = double(tri.c[i + 3].y);
        const Computed px0 = shifted(x0, w0, setup.centre_x), px1 = shifted(x1, w1, setup.centre_x);
        const Computed py0 = shifted(y0, w0, setup.centre_y), py1 = shifted(y1, w1, setup.centre_y);
        const Computed pw0{w0, 0.0}, pw1{w1, 0.0};
        const Computed qx0{cx0, 0.0}, qx1{cx1, 0.0}, qy0{cy0, 0.0}, qy1{cy1, 0.0};
        const Computed dx = difference(px0, px1), dy = difference(py0, py1), dw = difference(pw0, pw1);
        const Computed dcx = difference(qx0, qx1), dcy = difference(qy0, qy1);
        auto to_float = [](const Computed& c) { return static_cast<float>(c.value); };
        CoverageVertex& q = setup.vertex[i];
        q = CoverageVertex{to_float(px0), to_float(dx), to_float(qx0), to_float(dcx), to_float(py0),
                           to_float(dy),  to_float(qy0), to_float(dcy), to_float(pw0), to_float(dw)};
        moves = moves || q.dx != 0.0f || q.dy != 0.0f || q.dw != 0.0f || q.dcx != 0.0f || q.dcy != 0.0f;
        sheared = sheared || q.cx != 0.0f || q.cy != 0.0f || q.dcx != 0.0f || q.dcy != 0.0f;
        fast[i] = VertexBounds{
            fast_coordinate(float_input(px0), float_input(dx), float_input(qx0), float_input(dcx), t_fast, lens_fast),
            fast_coordinate(float_input(py0), float_input(dy), float_input(qy0), float_input(dcy), t_fast, lens_fast),
            fast_coordinate(float_input(pw0), float_input(dw), Bound{0.0, 0.0}, Bound{0.0, 0.0}, t_fast,
                            lens_fast)};
        largest = std::max({largest, fast[i].x.m, fast[i].y.m, fast[i].w.m});
        const CoordinateMagnitude mx{std::abs(x0), std::abs(x1), std::abs(cx0), std::abs(cx1)};
        const CoordinateMagnitude my{std::abs(y0), std::abs(y1), std::abs(cy0), std::abs(cy1)};
        const CoordinateMagnitude mw{std::abs(w0), std::abs(w1), 0.0, 0.0};
        oracle[i] = VertexBounds{oracle_coordinate(mx, t_oracle, lens_oracle, r),
                                 oracle_coordinate(my, t_oracle, lens_oracle, r),
                                 oracle_coordinate(mw, t_oracle, lens_oracle, r)};
    }
    setup.variant = moves ? (sheared ? CoverageVariant::both : CoverageVariant::motion)
                          : (sheared ? CoverageVariant::defocus : CoverageVariant::fixed);
    // The sample as the float path sees it: rounded to float, then shifted.
    const Bound s_fast = f.round(reach, f.eps * extent + f.tiny), s_oracle{extent, 0.0};
    // Margin for the bound's own rounding: a few dozen roundings of positive
    // terms, each relative 2^-53.
    constexpr double slack = 1.0 + 0x1.0p-40;
    // Float never overflows while every magnitude bound stays below this
    // (coordinates below its square root keep the cross products below it).
    constexpr double float_safe = 0x1.0p120;
    setup.usable = std::isfinite(extent) && largest < 0x1.0p60;
    for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const Bound fe = fast_edge(fast[a], fast[b], s_fast);
        const double oe = oracle_edge_error(oracle, k, s_oracle, r);
        setup.band[k] = round_up_to_float((fe.e + oe) * slack);
        setup.usable = setup.usable && fe.m < float_safe && std::isfinite(setup.band[k]);
    }
    if (setup.usable) {
        by_variant(setup.variant, [&](auto variant) {
            choose_evaluations<decltype(variant)::value>(setup);
            return 0;
        });
    } else {
        setup.one = &keep_one;
        setup.lanes = &keep_all;
    }
    return setup;
}

template CoverageSetup make_coverage_setup<float>(const kernel<float>::MovingTriangle&, const SampleBox&);
template CoverageSetup make_coverage_setup<double>(const kernel<double>::MovingTriangle&, const SampleBox&);

std::uint32_t may_cover32_scalar(const CoverageSetup& setup, const float* sx, const float* sy, const float* u,
                                 const float* v, const float* t, std::uint32_t wanted) {
    if (!setup.usable) return wanted;
    return by_variant(setup.variant, [&](auto variant) {
        return may_cover32_lanes<decltype(variant)::value>(setup, sx, sy, u, v, t, wanted);
    });
}

const char* fast_coverage_isa() {
    return has_avx2 ? "avx2" : "scalar";
}

}  // namespace blurcull::frontend
