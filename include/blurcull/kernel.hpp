// blurcull::kernel<Real>: every shared formula, instantiated for float or double.
//
// The bodies in detail/*_body.inl are the single source of each formula; the
// GLSL build step emits the same text for the shaders. Here they become static
// member functions of a class template whose member types play the role of
// GLSL's float, vec2, vec3, ... (the pattern of pbrt-v4, Blender and
// nvpro-samples for host/device shared code).
#pragma once

#include "detail/dialect.hpp"

namespace blurcull {

template <class Real>
struct kernel {
    static_assert(std::numeric_limits<Real>::is_iec559, "kernel<Real> needs IEEE float or double");

    using real = Real;
    using vec2 = glm::vec<2, Real, glm::defaultp>;
    using vec3 = glm::vec<3, Real, glm::defaultp>;
    using vec4 = glm::vec<4, Real, glm::defaultp>;
    using uint = std::uint32_t;

    // GLSL built-ins the shared text uses, forwarded to GLM (whose names follow GLSL).
    template <class X> static X min(X a, X b) { return glm::min(a, b); }
    template <class X> static X max(X a, X b) { return glm::max(a, b); }
    template <class X> static X abs(X a) { return glm::abs(a); }
    template <class X> static X clamp(X a, X lo, X hi) { return glm::clamp(a, lo, hi); }
    template <class X> static X sqrt(X a) { return glm::sqrt(a); }
    template <class X> static X floor(X a) { return glm::floor(a); }
    template <class X> static X ceil(X a) { return glm::ceil(a); }
    template <class X> static X cos(X a) { return glm::cos(a); }
    template <class X> static X sin(X a) { return glm::sin(a); }
    static bool isnan(real a) { return a != a; }
    static bool isinf(real a) { return a == std::numeric_limits<real>::infinity() || a == -std::numeric_limits<real>::infinity(); }
    static real dot(vec2 a, vec2 b) { return glm::dot(a, b); }
    static real dot(vec3 a, vec3 b) { return glm::dot(a, b); }
    static vec3 cross(vec3 a, vec3 b) { return glm::cross(a, b); }
    // Machine epsilon and the largest finite value of `real` (GLSL prelude: constants).
    static constexpr real bc_epsilon() { return std::numeric_limits<real>::epsilon(); }
    static constexpr real bc_huge() { return std::numeric_limits<real>::max(); }
    // The smallest normal value: below it, rounding errors are absolute.
    static constexpr real bc_tiny() { return std::numeric_limits<real>::min(); }

#include "detail/sampling_body.inl"
#include "detail/kernel_body.inl"
#include "detail/edge_bounds_body.inl"
#include "detail/sample_bounds_body.inl"
};

using kernelf = kernel<float>;
using kerneld = kernel<double>;

}  // namespace blurcull
