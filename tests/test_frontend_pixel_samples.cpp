// pixel_samples (render/common/pixel_samples.hpp), the host renderers' way of
// drawing a pixel's samples: bit for bit the kernel's sampler_sample for every
// pattern, pixels near 0 and far out, spp not a power of two and large,
// several seeds and progressive first indices (the Sobol patterns take the
// eight-lane path where the CPU has AVX2; it must not change one bit).
#include "render/common/pixel_samples.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>
#include <vector>

using namespace blurcull;
using namespace blurcull::frontend;

namespace {

bool same_bits(const kernelf::PixelSample& a, const kernelf::PixelSample& b) {
    const float x[5] = {a.offset.x, a.offset.y, a.lens.x, a.lens.y, a.time};
    const float y[5] = {b.offset.x, b.offset.y, b.lens.x, b.lens.y, b.time};
    return std::memcmp(x, y, sizeof x) == 0;
}

}  // namespace

TEST_CASE("pixel_samples draws exactly the kernel's samples for every pattern") {
    std::printf("pixel_samples runs %s\n", pixel_samples_isa());
    std::uint64_t compared = 0, differing = 0;
    for (int pattern = 0; pattern < BC_PATTERN_COUNT; ++pattern) {
        for (std::uint32_t spp : {1u, 3u, 8u, 16u, 17u, 64u, 1000u}) {
            for (std::uint32_t seed : {1u, 7u, 0xdeadbeefu}) {
                for (std::uint32_t py : {0u, 1u, 37u, 4095u}) {
                    for (std::uint32_t px : {0u, 2u, 511u, 70000u}) {
                        const patternsf::SamplerSetup setup = patternsf::sampler_setup(pattern, px, py, spp, seed);
                        for (std::uint32_t first : {0u, 3u, spp / 2}) {
                            if (first >= spp) continue;
                            const std::uint32_t count = spp - first;
                            std::vector<kernelf::PixelSample> fast(count), kernel(count);
                            pixel_samples(setup, first, count, fast.data());
                            for (std::uint32_t i = 0; i < count; ++i) {
                                kernel[i] = patternsf::sampler_sample(setup, first + i);
                                ++compared;
                                if (!same_bits(fast[i], kernel[i])) ++differing;
                            }
                            std::vector<kernelf::PixelSample> scalar(count);
                            pixel_samples_scalar(setup, first, count, scalar.data());
                            for (std::uint32_t i = 0; i < count; ++i) CHECK(same_bits(scalar[i], kernel[i]));
                        }
                    }
                }
            }
        }
    }
    std::printf("pixel_samples: %llu samples compared, %llu differ\n", static_cast<unsigned long long>(compared),
                static_cast<unsigned long long>(differing));
    CHECK(compared > 500000);
    CHECK(differing == 0);
}

TEST_CASE("a pinhole camera's samples: the kernel's offsets and times, the lens (0, 0), on both paths") {
    CHECK(lens_samples_for(0.0f) == LensSamples::skipped);
    CHECK(lens_samples_for(0.07f) == LensSamples::drawn);
    std::uint64_t compared = 0;
    for (int pattern = 0; pattern < BC_PATTERN_COUNT; ++pattern) {
        for (std::uint32_t spp : {1u, 8u, 16u, 17u, 64u}) {
            for (std::uint32_t px : {0u, 5u, 1023u}) {
                const patternsf::SamplerSetup setup = patternsf::sampler_setup(pattern, px, 3u * px + 1u, spp, 7u);
                std::vector<kernelf::PixelSample> fast(spp), scalar(spp);
                pixel_samples(setup, 0, spp, fast.data(), LensSamples::skipped);
                pixel_samples_scalar(setup, 0, spp, scalar.data(), LensSamples::skipped);
                for (std::uint32_t i = 0; i < spp; ++i) {
                    kernelf::PixelSample expected = patternsf::sampler_sample(setup, i);
                    expected.lens = glm::vec2(0.0f);
                    CHECK(same_bits(fast[i], expected));
                    CHECK(same_bits(scalar[i], expected));
                    ++compared;
                }
            }
        }
    }
    CHECK(compared > 1000);
}
