#include "render/common/pixel_samples.hpp"

#include "render/common/cpu_features.hpp"

#include <algorithm>
#include <array>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define BLURCULL_SAMPLES_X86 1
#else
#define BLURCULL_SAMPLES_X86 0
#endif

namespace blurcull::frontend {

void pixel_samples_scalar(const patternsf::SamplerSetup& setup, std::uint32_t first, std::uint32_t count,
                          kernelf::PixelSample* out, LensSamples lens) {
    for (std::uint32_t i = 0; i < count; ++i) {
        out[i] = patternsf::sampler_sample(setup, first + i);
        if (lens == LensSamples::skipped) out[i].lens = glm::vec2(0.0f);
    }
}

namespace {

using P = patternsf;

// Sobol dimension d's direction numbers, bits reversed (bc_sobol_reversed of
// a single bit: the Sobol point of an index is the xor of those of its bits).
struct DirectionNumbers {
    std::array<std::array<std::uint32_t, 32>, 5> r{};
    DirectionNumbers() {
        for (int d = 0; d < 5; ++d)
            for (int k = 0; k < 32; ++k)
                r[static_cast<std::size_t>(d)][static_cast<std::size_t>(k)] = P::bc_sobol_reversed(1u << k, d);
    }
};

#if BLURCULL_SAMPLES_X86
const bool has_avx2 = cpu_has_avx2();

// The kernel's integer functions on eight lanes, the same operations (integer
// arithmetic is exact, so every lane equals the scalar result).
struct Lanes8 {
    template <int shift>
    __attribute__((target("avx2"))) static __m256i swap_bits(__m256i x, int mask) {
        const __m256i m = _mm256_set1_epi32(mask);
        return _mm256_or_si256(_mm256_and_si256(_mm256_srli_epi32(x, shift), m),
                               _mm256_slli_epi32(_mm256_and_si256(x, m), shift));
    }
    // bc_reverse_bits.
    __attribute__((target("avx2"))) static __m256i reverse_bits(__m256i x) {
        x = swap_bits<1>(x, 0x55555555);
        x = swap_bits<2>(x, 0x33333333);
        x = swap_bits<4>(x, 0x0f0f0f0f);
        x = swap_bits<8>(x, 0x00ff00ff);
        return _mm256_or_si256(_mm256_srli_epi32(x, 16), _mm256_slli_epi32(x, 16));
    }
    __attribute__((target("avx2"))) static __m256i times(__m256i x, std::uint32_t c) {
        return _mm256_mullo_epi32(x, _mm256_set1_epi32(static_cast<int>(c)));
    }
    // bc_lk_permute.
    __attribute__((target("avx2"))) static __m256i lk_permute(__m256i x, std::uint32_t seed) {
        x = _mm256_xor_si256(x, times(x, 0x3d20adeau));
        x = _mm256_add_epi32(x, _mm256_set1_epi32(static_cast<int>(seed)));
        x = times(x, (seed >> 16u) | 1u);
        x = _mm256_xor_si256(x, times(x, 0x05526c56u));
        x = _mm256_xor_si256(x, times(x, 0x53a22864u));
        return x;
    }
    // bc_sobol_shuffle.
    __attribute__((target("avx2"))) static __m256i shuffle(__m256i index, std::uint32_t key, std::uint32_t mask) {
        const __m256i scrambled = reverse_bits(lk_permute(reverse_bits(index), key));
        return _mm256_and_si256(scrambled, _mm256_set1_epi32(static_cast<int>(mask)));
    }
    // bc_sobol_reversed for indices <= mask (2^bits - 1).
    __attribute__((target("avx2"))) static __m256i sobol_reversed(__m256i index, int dim, int bits,
                                                                  const DirectionNumbers& numbers) {
        if (dim <= 0) return index;
        __m256i result = _mm256_setzero_si256();
        __m256i rest = index;  // bit k of index is bit 0 of rest at step k
        for (int k = 0; k < bits; ++k) {
            const __m256i bit = _mm256_and_si256(rest, _mm256_set1_epi32(1));
            const __m256i all = _mm256_sub_epi32(_mm256_setzero_si256(), bit);
            const __m256i number = _mm256_set1_epi32(static_cast<int>(numbers.r[static_cast<std::size_t>(dim)][static_cast<std::size_t>(k)]));
            result = _mm256_xor_si256(result, _mm256_and_si256(all, number));
            rest = _mm256_srli_epi32(rest, 1);
        }
        return result;
    }
    // bc_sobol_unit: bc_unit's 24 bits times 2^-24 (exact in float).
    __attribute__((target("avx2"))) static void unit(__m256i shuffled, int dim, std::uint32_t key, int bits,
                                                     const DirectionNumbers& numbers, float* out) {
        const __m256i h = reverse_bits(lk_permute(sobol_reversed(shuffled, dim, bits, numbers), key));
        const __m256 value =
            _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_srli_epi32(h, 8)), _mm256_set1_ps(5.9604644775390625e-8f));
        _mm256_storeu_ps(out, value);
    }
};

// bc_lens_of (kernel's bc_square_to_disk with bc_div and
// bc_cos_sin_quarter_pi, sampling_body.inl) on eight lanes: the same float
// operations in the same order, no FMA, so every lane equals the scalar
// result bit for bit (the test of pixel_samples compares them). The scalar
// form's latency chain (frexp, Newton steps, the exact residual, two
// polynomials) costs more than the cos/sin it replaced; eight lanes at once
// keep the sampler's time.
// One Horner step c + t2 acc.
__attribute__((target("avx2"))) inline __m256 step(__m256 acc, __m256 t2, float c) {
    return _mm256_add_ps(_mm256_set1_ps(c), _mm256_mul_ps(t2, acc));
}

__attribute__((target("avx2"))) void lens8(const float* u, const float* v, kernelf::PixelSample* out) {
    const __m256 one = _mm256_set1_ps(1.0f);
    const __m256 two = _mm256_set1_ps(2.0f);
    const __m256 magnitude = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    const __m256 sign = _mm256_castsi256_ps(_mm256_set1_epi32(static_cast<int>(0x80000000u)));
    const __m256 ax = _mm256_sub_ps(_mm256_mul_ps(two, _mm256_loadu_ps(u)), one);
    const __m256 ay = _mm256_sub_ps(_mm256_mul_ps(two, _mm256_loadu_ps(v)), one);
    // abs(a.x) > abs(a.y): r = a.x, ratio a.y / a.x; else r = a.y, ratio a.x / a.y.
    const __m256 x_sector = _mm256_cmp_ps(_mm256_and_ps(ax, magnitude), _mm256_and_ps(ay, magnitude), _CMP_GT_OQ);
    const __m256 num = _mm256_blendv_ps(ax, ay, x_sector);
    const __m256 den = _mm256_blendv_ps(ay, ax, x_sector);
    // bc_div(num, den); den is a nonzero multiple of 2^-23 in [-1, 1] (normal)
    // wherever the result is used: frexp and ldexp on the bits.
    const __m256i bits = _mm256_castps_si256(den);
    const __m256i biased = _mm256_and_si256(_mm256_srli_epi32(bits, 23), _mm256_set1_epi32(0xff));
    const __m256 m = _mm256_castsi256_ps(_mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi32(static_cast<int>(0x807fffffu))),
                                                          _mm256_set1_epi32(126 << 23)));
    // 2^-e with e = biased - 126: exponent field 127 - e = 253 - biased.
    const __m256 scale = _mm256_castsi256_ps(_mm256_slli_epi32(_mm256_sub_epi32(_mm256_set1_epi32(253), biased), 23));
    const __m256 n = _mm256_mul_ps(num, scale);
    const __m256 am = _mm256_and_ps(m, magnitude);
    __m256 y = _mm256_sub_ps(_mm256_set1_ps(2.8235294818878173828125f),
                             _mm256_mul_ps(_mm256_set1_ps(1.88235294818878173828125f), am));
    for (int k = 0; k < 3; ++k) y = _mm256_add_ps(y, _mm256_mul_ps(y, _mm256_sub_ps(one, _mm256_mul_ps(am, y))));
    y = _mm256_xor_ps(y, _mm256_and_ps(m, sign));  // m < 0: -y
    const __m256 q = _mm256_mul_ps(n, y);
    // bc_two_product(q, m) with Veltkamp's split (factor 4097).
    const __m256 p = _mm256_mul_ps(q, m);
    const __m256 factor = _mm256_set1_ps(4097.0f);
    const __m256 cq = _mm256_mul_ps(factor, q);
    const __m256 q_hi = _mm256_sub_ps(cq, _mm256_sub_ps(cq, q));
    const __m256 q_lo = _mm256_sub_ps(q, q_hi);
    const __m256 cm = _mm256_mul_ps(factor, m);
    const __m256 m_hi = _mm256_sub_ps(cm, _mm256_sub_ps(cm, m));
    const __m256 m_lo = _mm256_sub_ps(m, m_hi);
    __m256 err = _mm256_sub_ps(_mm256_mul_ps(q_hi, m_hi), p);
    err = _mm256_add_ps(err, _mm256_mul_ps(q_hi, m_lo));
    err = _mm256_add_ps(err, _mm256_mul_ps(q_lo, m_hi));
    err = _mm256_add_ps(err, _mm256_mul_ps(q_lo, m_lo));
    const __m256 r = _mm256_sub_ps(_mm256_sub_ps(n, p), err);
    __m256 t = _mm256_blendv_ps(_mm256_add_ps(q, _mm256_mul_ps(r, y)), q, _mm256_cmp_ps(r, _mm256_setzero_ps(), _CMP_EQ_OQ));
    // A power of two: 2 n, -2 n.
    t = _mm256_blendv_ps(t, _mm256_mul_ps(two, n), _mm256_cmp_ps(m, _mm256_set1_ps(0.5f), _CMP_EQ_OQ));
    t = _mm256_blendv_ps(t, _mm256_mul_ps(_mm256_set1_ps(-2.0f), n), _mm256_cmp_ps(m, _mm256_set1_ps(-0.5f), _CMP_EQ_OQ));
    // bc_cos_sin_quarter_pi(t), float's series.
    const __m256 t2 = _mm256_mul_ps(t, t);
    __m256 c = _mm256_set1_ps(-0.0000000246113689428284487803466618061065673828125f);
    c = step(c, t2, 0.000003590860387703287415206432342529296875f);
    c = step(c, t2, -0.000325991888530552387237548828125f);
    c = step(c, t2, 0.01585434377193450927734375f);
    c = step(c, t2, -0.308425128459930419921875f);
    c = step(c, t2, 1.0f);
    __m256 sn = _mm256_set1_ps(0.00000031336168149209697730839252471923828125f);
    sn = step(sn, t2, -0.0000365762025467120110988616943359375f);
    sn = step(sn, t2, 0.00249039451591670513153076171875f);
    sn = step(sn, t2, -0.080745510756969451904296875f);
    sn = step(sn, t2, 0.785398185253143310546875f);
    sn = _mm256_mul_ps(t, sn);
    // (r cos, r sin) around the x axis, (r sin, r cos) around the y axis; 0 at the centre.
    __m256 lx = _mm256_mul_ps(den, _mm256_blendv_ps(sn, c, x_sector));
    __m256 ly = _mm256_mul_ps(den, _mm256_blendv_ps(c, sn, x_sector));
    const __m256 centre = _mm256_and_ps(_mm256_cmp_ps(ax, _mm256_setzero_ps(), _CMP_EQ_OQ),
                                        _mm256_cmp_ps(ay, _mm256_setzero_ps(), _CMP_EQ_OQ));
    lx = _mm256_andnot_ps(centre, lx);
    ly = _mm256_andnot_ps(centre, ly);
    // bc_lens_of's clamp to [-1, 1].
    const __m256 minus_one = _mm256_set1_ps(-1.0f);
    lx = _mm256_min_ps(_mm256_max_ps(lx, minus_one), one);
    ly = _mm256_min_ps(_mm256_max_ps(ly, minus_one), one);
    alignas(32) float xs[8], ys[8];
    _mm256_store_ps(xs, lx);
    _mm256_store_ps(ys, ly);
    for (int i = 0; i < 8; ++i) out[i].lens = glm::vec2(xs[i], ys[i]);
}

// Eight samples of a Sobol pattern from index `first`: the coordinates on
// eight lanes, then the kernel's own lens mapping, on eight lanes too.
__attribute__((target("avx2"))) void sobol8(const P::SamplerSetup& setup, std::uint32_t first,
                                            kernelf::PixelSample* out, LensSamples lens) {
    static const DirectionNumbers numbers;
    const P::SobolSetup& p = setup.sobol;
    int bits = 0;
    while (bits < 32 && (p.index_mask >> bits) != 0u) ++bits;
    const __m256i index = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(first)),
                                           _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    const __m256i position = Lanes8::shuffle(index, p.index_key, p.index_mask);
    // Padded Sobol: (u, v, t) from an index shuffle of their own, Sobol dimensions 0..2.
    const bool padded = setup.pattern == BC_PATTERN_PADDED_SOBOL;
    const __m256i lens_time = padded ? Lanes8::shuffle(index, p.index_key2, p.index_mask) : position;
    alignas(32) float x[8], y[8], t[8], u[8], v[8];
    Lanes8::unit(position, 0, p.dim_key0, bits, numbers, x);
    Lanes8::unit(position, 1, p.dim_key1, bits, numbers, y);
    Lanes8::unit(lens_time, 2, p.dim_key2, bits, numbers, t);
    if (lens == LensSamples::skipped) {
        for (int i = 0; i < 8; ++i) {
            out[i].offset = glm::vec2(x[i], y[i]);
            out[i].time = t[i];
            out[i].lens = glm::vec2(0.0f);
        }
        return;
    }
    Lanes8::unit(lens_time, padded ? 0 : 3, p.dim_key3, bits, numbers, u);
    Lanes8::unit(lens_time, padded ? 1 : 4, p.dim_key4, bits, numbers, v);
    for (int i = 0; i < 8; ++i) {
        out[i].offset = glm::vec2(x[i], y[i]);
        out[i].time = t[i];
    }
    lens8(u, v, out);
}
#endif

}  // namespace

void pixel_samples(const patternsf::SamplerSetup& setup, std::uint32_t first, std::uint32_t count,
                   kernelf::PixelSample* out, LensSamples lens) {
#if BLURCULL_SAMPLES_X86
    if (has_avx2 && (setup.pattern == BC_PATTERN_SOBOL || setup.pattern == BC_PATTERN_PADDED_SOBOL)) {
        std::uint32_t done = 0;
        for (; done + 8 <= count; done += 8) sobol8(setup, first + done, out + done, lens);
        if (done < count) {
            kernelf::PixelSample rest[8];
            sobol8(setup, first + done, rest, lens);
            std::copy(rest, rest + (count - done), out + done);
        }
        return;
    }
#endif
    pixel_samples_scalar(setup, first, count, out, lens);
}

const char* pixel_samples_isa() {
#if BLURCULL_SAMPLES_X86
    return has_avx2 ? "avx2" : "scalar";
#else
    return "scalar";
#endif
}

}  // namespace blurcull::frontend
