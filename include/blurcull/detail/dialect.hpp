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
#define BC_FN static inline
// Parameter passing: const reference / out / inout.
#define BC_IN(T) const T&
#define BC_OUT(T) T&
#define BC_INOUT(T) T&
// Keeps the compiler from reassociating or fusing the expression that
// initialises a variable: GLSL's `precise`, nothing in C++ (which does
// neither without -ffast-math / fp-contract).
#define BC_PRECISE
