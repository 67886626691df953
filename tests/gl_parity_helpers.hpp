// What the GPU/host parity tests (test_frontend_gl_parity.cpp,
// test_frontend_gl_raster_parity.cpp) share: host arithmetic without fma
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

}  // namespace blurcull::frontend::test
