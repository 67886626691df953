#include "render/cpu/sample_chain.hpp"

#include "render/common/cpu_features.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

#include "render/cpu/edge_plane_lanes.hpp"
#define BLURCULL_CHAIN_X86 1
#else
#define BLURCULL_CHAIN_X86 0
#endif

namespace blurcull::frontend {

SampleLanes::SampleLanes(std::size_t size)
    : dsx_(size + 32), dsy_(size + 32), du_(size + 32), dv_(size + 32), dt_(size + 32), fsx_(size + 32),
      fsy_(size + 32), fu_(size + 32), fv_(size + 32), ft_(size + 32) {}

template <class Real>
std::uint32_t samples_passing_scalar(const typename kernel<Real>::ScreenBound& screen, bool check_screen,
                                     const typename kernel<Real>::SampleBounds& bounds, const SampleLanes& lanes,
                                     std::size_t first, int count) {
    using K = kernel<Real>;
    std::uint32_t passed = 0;
    for (int i = 0; i < count; ++i) {
        const std::size_t k = first + static_cast<std::size_t>(i);
        const typename K::vec2 ndc(static_cast<Real>(lanes.sx()[k]), static_cast<Real>(lanes.sy()[k]));
        const typename K::vec2 lens(static_cast<Real>(lanes.u()[k]), static_cast<Real>(lanes.v()[k]));
        if (!K::sample_culled(screen, check_screen, bounds, ndc, lens, static_cast<Real>(lanes.t()[k])))
            passed |= 1u << i;
    }
    return passed;
}

namespace {

#if BLURCULL_CHAIN_X86
const bool has_avx = cpu_has_avx();

// One time line of kernel::sample_passes over four lanes: rejected where
// t < a + b l or t > c + d l (line = (a, b, c, d)), each side a product
// then a sum, as the kernel rounds it. "avx" only: no FMA, so nothing is fused.
__attribute__((target("avx"))) inline __m256d time_line_rejects(const glm::dvec4& line, __m256d t, __m256d lens) {
    const __m256d lo = _mm256_add_pd(_mm256_set1_pd(line.x), _mm256_mul_pd(_mm256_set1_pd(line.y), lens));
    const __m256d hi = _mm256_add_pd(_mm256_set1_pd(line.z), _mm256_mul_pd(_mm256_set1_pd(line.w), lens));
    return _mm256_or_pd(_mm256_cmp_pd(t, lo, _CMP_LT_OQ), _mm256_cmp_pd(t, hi, _CMP_GT_OQ));
}

// Rejected where x < lo or x > hi (a NaN is not rejected, as in the kernel).
__attribute__((target("avx"))) inline __m256d outside(__m256d x, double lo, double hi) {
    return _mm256_or_pd(_mm256_cmp_pd(x, _mm256_set1_pd(lo), _CMP_LT_OQ),
                        _mm256_cmp_pd(x, _mm256_set1_pd(hi), _CMP_GT_OQ));
}

// kernel<double>::sample_culled (sample_passes_at, then screen_contains) on
// four lanes: the lanes culled, as a 4-bit mask. check_bounds false:
// sample_passes is known to pass every lane; check_edges: the bounds carry
// edge planes (edge_plane_lanes.hpp), tested on the lanes still open.
__attribute__((target("avx"))) inline int culled4(const kernel<double>::ScreenBound& screen, bool check_screen,
                                                  bool check_bounds, bool check_edges,
                                                  const kernel<double>::SampleBounds& b, const SampleLanes& lanes,
                                                  std::size_t k) {
    __m256d culled = _mm256_setzero_pd();
    if (check_bounds) {
        const __m256d u = _mm256_loadu_pd(lanes.u() + k), v = _mm256_loadu_pd(lanes.v() + k);
        const __m256d t = _mm256_loadu_pd(lanes.t() + k);
        culled = _mm256_or_pd(outside(u, b.u_range.x, b.u_range.y), outside(v, b.v_range.x, b.v_range.y));
        culled = _mm256_or_pd(culled, time_line_rejects(b.u_time_a, t, u));
        culled = _mm256_or_pd(culled, time_line_rejects(b.v_time_a, t, v));
        culled = _mm256_or_pd(culled, time_line_rejects(b.u_time_b, t, u));
        culled = _mm256_or_pd(culled, time_line_rejects(b.v_time_b, t, v));
    }
    if (check_screen) {
        const __m256d sx = _mm256_loadu_pd(lanes.sx() + k), sy = _mm256_loadu_pd(lanes.sy() + k);
        culled = _mm256_or_pd(culled, outside(sx, screen.lo.x, screen.hi.x));
        culled = _mm256_or_pd(culled, outside(sy, screen.lo.y, screen.hi.y));
        for (int e = 0; e < screen.hull_count; ++e) {
            const glm::dvec3& edge = screen.hull_edge[e];
            const __m256d value = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(edge.x), sx),
                                                              _mm256_mul_pd(_mm256_set1_pd(edge.y), sy)),
                                                _mm256_set1_pd(edge.z));
            culled = _mm256_or_pd(culled, _mm256_cmp_pd(value, _mm256_setzero_pd(), _CMP_LT_OQ));
        }
    }
    if (check_edges && _mm256_movemask_pd(culled) != 0xf) {
        const edge_lanes::Lanes5 at{_mm256_loadu_pd(lanes.sx() + k), _mm256_loadu_pd(lanes.sy() + k),
                                    _mm256_loadu_pd(lanes.u() + k), _mm256_loadu_pd(lanes.v() + k),
                                    _mm256_loadu_pd(lanes.t() + k)};
        culled = edge_lanes::culled_by_edges(b.edges, at, culled);
    }
    return _mm256_movemask_pd(culled);
}

// Whether `b` is no_sample_bounds() (bitwise, -0 aside): then sample_passes
// holds for every lens in [-1, 1]^2 and time in [0, 1], since t < 0 + 0 u
// and t > 1 + 0 u are false there, as are the range tests.
bool passes_unit_range(const kernel<double>::SampleBounds& b) {
    // Built once: no_sample_bounds() fills a large struct, and this runs per 32 samples.
    static const kernel<double>::SampleBounds none = kernel<double>::no_sample_bounds();
    return !b.empty && b.u_range == none.u_range && b.v_range == none.v_range && b.u_time_a == none.u_time_a &&
           b.u_time_b == none.u_time_b && b.v_time_a == none.v_time_a && b.v_time_b == none.v_time_b;
}

// check_bounds false: `bounds` is known to pass every lane (passes_unit_range).
__attribute__((target("avx"))) std::uint32_t passing_avx(const kernel<double>::ScreenBound& screen, bool check_screen,
                          bool check_bounds, const kernel<double>::SampleBounds& bounds, const SampleLanes& lanes,
                          std::size_t first, int count) {
    const std::uint32_t wanted = count >= 32 ? ~0u : (1u << count) - 1u;
    const bool check_edges = kernel<double>::plane_pieces(bounds) > 0;
    if (!check_bounds && !check_screen && !check_edges) return wanted;
    std::uint32_t culled = 0;
    for (int i = 0; i < count; i += 4) {
        const std::size_t k = first + static_cast<std::size_t>(i);
        culled |= static_cast<std::uint32_t>(culled4(screen, check_screen, check_bounds, check_edges, bounds, lanes, k))
                  << i;
    }
    return ~culled & wanted;
}
#endif

}  // namespace

template <class Real>
std::uint32_t samples_passing(const typename kernel<Real>::ScreenBound& screen, bool check_screen,
                              const typename kernel<Real>::SampleBounds& bounds, const SampleLanes& lanes,
                              std::size_t first, int count) {
    if (bounds.empty || (check_screen && screen.empty)) return 0;
#if BLURCULL_CHAIN_X86
    if constexpr (std::is_same_v<Real, double>) {
        if (has_avx) {
            const bool check_bounds = !(lanes.in_unit_range() && passes_unit_range(bounds));
            return passing_avx(screen, check_screen, check_bounds, bounds, lanes, first, count);
        }
    }
#endif
    return samples_passing_scalar<Real>(screen, check_screen, bounds, lanes, first, count);
}

template <class Real>
std::uint32_t samples_passing_screen(const typename kernel<Real>::ScreenBound& screen, bool check_screen,
                                     const SampleLanes& lanes, std::size_t first, int count) {
#if BLURCULL_CHAIN_X86
    if constexpr (std::is_same_v<Real, double>) {
        if (has_avx && !(check_screen && screen.empty)) {
            static const kernel<double>::SampleBounds none = kernel<double>::no_sample_bounds();
            return passing_avx(screen, check_screen, !lanes.in_unit_range(), none, lanes, first, count);
        }
    }
#endif
    return samples_passing<Real>(screen, check_screen, kernel<Real>::no_sample_bounds(), lanes, first, count);
}

template std::uint32_t samples_passing_screen<float>(const kernel<float>::ScreenBound&, bool, const SampleLanes&,
                                                     std::size_t, int);
template std::uint32_t samples_passing_screen<double>(const kernel<double>::ScreenBound&, bool, const SampleLanes&,
                                                      std::size_t, int);

template std::uint32_t samples_passing<float>(const kernel<float>::ScreenBound&, bool,
                                              const kernel<float>::SampleBounds&, const SampleLanes&, std::size_t,
                                              int);
template std::uint32_t samples_passing<double>(const kernel<double>::ScreenBound&, bool,
                                               const kernel<double>::SampleBounds&, const SampleLanes&,
                                               std::size_t, int);
template std::uint32_t samples_passing_scalar<float>(const kernel<float>::ScreenBound&, bool,
                                                     const kernel<float>::SampleBounds&, const SampleLanes&,
                                                     std::size_t, int);
template std::uint32_t samples_passing_scalar<double>(const kernel<double>::ScreenBound&, bool,
                                                      const kernel<double>::SampleBounds&, const SampleLanes&,
                                                      std::size_t, int);

}  // namespace blurcull::frontend
