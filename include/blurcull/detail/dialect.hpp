// The dialect shared by C++ and GLSL.
//
// Every formula that both the host and the shaders run lives in a *_body.inl
// file written in a subset of C++ that is also GLSL 4.50: plain functions on
// GLM vector types, no references, pointers, exceptions, recursion, allocation
// or overloading on precision. The C++ side includes those bodies inside a
// class template (blurcull::kernel<Real>) so that `real`, `vec2`, ... name the
// float or double types; the GLSL side puts a prelude in front that defines
// the same names and the macros below (see shaders/ and docs/kernel.md).
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include <cstdint>
#include <limits>

// Function definitions: static members of kernel<Real> in C++.
// Names: the bodies define and call a public function by its plain name
// (covers), which is its C++ member name (kerneld::covers); the GLSL prelude
// renames each one to bc_<name> with `#define covers bc_covers`, and the
// emitted library #undefs those after the last body (docs/glsl.md, "Names"),
// so C++ needs no macro for it. Internal helpers are named bc_* in both.
#define BC_FN static inline
// Parameter passing: const reference / out / inout.
#define BC_IN(T) const T&
#define BC_OUT(T) T&
#define BC_INOUT(T) T&
// Keeps the compiler from reassociating or fusing the expression that
// initialises a variable: GLSL's `precise`, nothing in C++ (which does
// neither without -ffast-math / fp-contract).
#define BC_PRECISE
