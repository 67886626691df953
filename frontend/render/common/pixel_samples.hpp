// A pixel's stochastic samples in one call, for the host renderers that draw
// every sample of a pixel (cpu, embree): the kernel's sampler_sample, bit for
// bit, with the Owen-scrambled Sobol pattern's integer work (index shuffle,
// Sobol sums, hashing, bit reversal) done eight samples at a time with AVX2
// where the CPU has it, and the lens mapping (the kernel's own division and
// cos/sin from + - *) eight at a time too (lens8), in the kernel's order, so
// every value is the one sampler_sample returns
// (tests/test_frontend_pixel_samples.cpp).
#pragma once

#include <blurcull/patterns.hpp>

#include <cstdint>

namespace blurcull::frontend {

// Whether the renderer uses the samples' lens positions. A pinhole camera
// (lens_radius 0) does not: every circle of confusion is exactly 0 and the
// ray origins are the eye, whatever (u, v), so their cos/sin mapping and two
// of the five Sobol dimensions are skipped and the lens is (0, 0).
enum class LensSamples : bool { skipped = false, drawn = true };

// Samples first .. first + count - 1 of the pixel of `setup` into out[0 ..
// count - 1]: out[i] == patternsf::sampler_sample(setup, first + i), with
// out[i].lens = (0, 0) when `lens` is skipped.
void pixel_samples(const patternsf::SamplerSetup& setup, std::uint32_t first, std::uint32_t count,
                   kernelf::PixelSample* out, LensSamples lens = LensSamples::drawn);

// pixel_samples one sample at a time through the kernel, whatever the CPU
// (what the eight-lane path is tested against).
void pixel_samples_scalar(const patternsf::SamplerSetup& setup, std::uint32_t first, std::uint32_t count,
                          kernelf::PixelSample* out, LensSamples lens = LensSamples::drawn);

// The lens samples a camera of aperture radius `lens_radius` needs.
inline LensSamples lens_samples_for(float lens_radius) {
    return lens_radius > 0.0f ? LensSamples::drawn : LensSamples::skipped;
}

// "avx2" or "scalar": what pixel_samples runs for the Sobol pattern on this CPU.
const char* pixel_samples_isa();

}  // namespace blurcull::frontend
