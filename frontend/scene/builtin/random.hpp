// The built-in scenes' random numbers: splitmix64, tiny, well mixed and the
// same on every platform and library version (std:: distributions are not),
// so the scenes are reproducible.
#pragma once

#include <cstdint>

namespace blurcull::frontend::builtin {

class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}

    // The next 64 random bits.
    std::uint64_t next() {
        state_ += 0x9E3779B97F4A7C15ull;
        std::uint64_t z = state_;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // 24 random bits: every value is exactly representable in [0, 1).
    float unit() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
    // Uniform in [low, high).
    float uniform(float low, float high) { return low + (high - low) * unit(); }

private:
    std::uint64_t state_;
};

}  // namespace blurcull::frontend::builtin
