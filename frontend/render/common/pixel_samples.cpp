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

// Eight samples of a Sobol pattern from index `first`: the coordinates on
// eight lanes, then the kernel's own lens mapping per sample.
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
        out[i].lens = P::bc_lens_of(glm::vec2(u[i], v[i]));
    }
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
