// What the GPU/host parity tests (test_frontend_gl_parity.cpp,
// test_frontend_gl_raster_parity.cpp, test_frontend_gl_secondary_parity.cpp) share: host arithmetic without fma
// contraction, the includes for running an emitted-kernel compute shader, and
// a headless context or a reasoned skip.
//
// Include it FIRST: llvmpipe does not fuse a*b+c (design brief, section 8), so
// the host must not contract either, and the pragma below has to come before
// the kernel's functions are instantiated.
#pragma once

#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "frontend_test_helpers.hpp"
#include "kernel_generators.hpp"
#include "render/gl/gl_context.hpp"

#include <blurcull/glsl/kernel_glsl.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

namespace blurcull::frontend::test {

// A headless context (of `kind` when given), or nothing after saying why; a
// failure instead when CI=true.
inline std::optional<gl::HeadlessContext> context_or_skip(std::optional<gl::ContextKind> kind = std::nullopt) {
    try {
        return kind ? gl::HeadlessContext::create(*kind) : gl::HeadlessContext::create();
    } catch (const gl::GlError& e) {
        if (is_ci()) FAIL("no headless OpenGL 4.5 context in CI: " << std::string(e.what()));
        MESSAGE("SKIPPED: no headless OpenGL 4.5 context (" << std::string(e.what()) << "); CI=true makes this a failure");
        return std::nullopt;
    }
}

// A float's bits and back: the parity tests move floats through uint SSBOs
// and compare them bit for bit.
inline std::uint32_t bits_of(float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

inline float float_of(std::uint32_t b) {
    float x;
    std::memcpy(&x, &b, sizeof x);
    return x;
}

// Distance in representable floats; NaN against anything else counts as
// "infinitely" far, two NaNs as equal.
inline std::int64_t ulp_distance(float a, float b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : INT64_MAX;
    auto ordered = [](float x) {
        std::int64_t raw = static_cast<std::int64_t>(bits_of(x));
        return raw & 0x80000000 ? -(raw & 0x7fffffff) : raw;
    };
    std::int64_t d = ordered(a) - ordered(b);
    return d < 0 ? -d : d;
}

}  // namespace blurcull::frontend::test
