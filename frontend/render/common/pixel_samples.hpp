// A pixel's stochastic samples in one call, for the host renderers that draw
// every sample of a pixel (cpu, embree): the kernel's sampler_sample, bit for
// bit, with the Owen-scrambled Sobol pattern's integer work (index shuffle,
// Sobol sums, hashing, bit reversal) done eight samples at a time with AVX2
// where the CPU has it. The lens mapping (a division and cos/sin) stays the
// kernel's scalar code, so every value is the one sampler_sample returns
// (tests/test_frontend_pixel_samples.cpp).
#pragma once

#include <blurcull/patterns.hpp>

#include <cstdint>

namespace blurcull::frontend {

// Samples first .. first + count - 1 of the pixel of `setup` into out[0 ..
// count - 1]: out[i] == patternsf::sampler_sample(setup, first + i).
void pixel_samples(const patternsf::SamplerSetup& setup, std::uint32_t first, std::uint32_t count,
                   kernelf::PixelSample* out);

// pixel_samples one sample at a time through the kernel, whatever the CPU
// (what the eight-lane path is tested against).
void pixel_samples_scalar(const patternsf::SamplerSetup& setup, std::uint32_t first, std::uint32_t count,
                          kernelf::PixelSample* out);

// "avx2" or "scalar": what pixel_samples runs for the Sobol pattern on this CPU.
const char* pixel_samples_isa();

}  // namespace blurcull::frontend
