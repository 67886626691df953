// blurcull::patterns<Real>: sample patterns (random, jittered, Owen-scrambled
// Sobol) and the per-sample part of interleaved sampling, in the shared
// C++/GLSL dialect (detail/patterns_body.inl), and, host only, the texture a
// GPU can read instead of evaluating a pattern. The names of the patterns are
// in pattern_names.hpp, the construction of the interleaved tile set in
// interleaved_tiles.hpp. docs/sampling.md explains the patterns.
#pragma once

#include "kernel.hpp"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace blurcull {

// The shared text needs the names kernel<Real> defines (the GLSL built-ins,
// bc_hash, PixelSample, pixel_sample, ...); a derived class template sees
// them only through these using-declarations.
template <class Real>
struct patterns : kernel<Real> {
    using base = kernel<Real>;
    using real = typename base::real;
    using vec2 = typename base::vec2;
    using vec3 = typename base::vec3;
    using vec4 = typename base::vec4;
    using uint = typename base::uint;
    using PixelSample = typename base::PixelSample;
    using PixelSampleSetup = typename base::PixelSampleSetup;
    using base::abs;
    using base::bc_cos_sin_quarter_pi;
    using base::bc_div;
    using base::bc_sqrt;
    using base::bc_epsilon;
    using base::bc_hash;
    using base::bc_hash3;
    using base::bc_square_to_disk;
    using base::bc_unit;
    using base::clamp;
    using base::floor;
    using base::cos;
    using base::max;
    using base::min;
    using base::pixel_sample;
    using base::pixel_sample_from;
    using base::pixel_sample_setup;
    using base::sin;
    using base::sqrt;

#include "detail/patterns_body.inl"
};

using patternsf = patterns<float>;
using patternsd = patterns<double>;

// ---- host side: the pattern as a texture ----------------------------------------

// The texture a GPU can read instead of evaluating the pattern: sample j of
// pixel (px, py) of the pattern tiled every `tile` pixels is element
// ((py % tile) * tile + px % tile) * spp + j (= patternsf::pattern_sample_tiled).
// Throws std::invalid_argument for an unknown pattern, tile < 1 or spp < 1.
inline std::vector<kernelf::PixelSample> make_pattern_tile(int pattern, int tile, int spp, std::uint32_t seed) {
    if (pattern < BC_PATTERN_HASHED || pattern >= BC_PATTERN_COUNT) {
        throw std::invalid_argument("unknown sample pattern id " + std::to_string(pattern));
    }
    if (tile < 1 || tile > 4096) throw std::invalid_argument("pattern tile size must be in [1, 4096], got " + std::to_string(tile));
    if (spp < 1 || spp > 65536) throw std::invalid_argument("samples per pixel must be in [1, 65536], got " + std::to_string(spp));
    std::vector<kernelf::PixelSample> texels;
    texels.reserve(static_cast<std::size_t>(tile) * static_cast<std::size_t>(tile) * static_cast<std::size_t>(spp));
    const auto side = static_cast<std::uint32_t>(tile);
    const auto count = static_cast<std::uint32_t>(spp);
    for (std::uint32_t py = 0; py < side; ++py) {
        for (std::uint32_t px = 0; px < side; ++px) {
            for (std::uint32_t j = 0; j < count; ++j) texels.push_back(patternsf::pattern_sample(pattern, px, py, j, count, seed));
        }
    }
    return texels;
}

}  // namespace blurcull
