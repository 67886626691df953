#version 450 core
// blurcull's GLSL prelude: maps the shared C++/GLSL dialect of
// include/blurcull/detail/dialect.hpp and kernel.hpp onto GLSL 4.50
// (docs/glsl.md). The build puts the shared *_body.inl text after it.

// The scalar of every formula: IEEE binary32, like the host's kernel<float>.
#define real float

// Function definitions and parameter passing (C++: static inline, const T&, T&, T&).
#define BC_FN
#define BC_IN(T) in T
#define BC_OUT(T) out T
#define BC_INOUT(T) inout T
// No reassociation or fusion of the initialising expression.
#define BC_PRECISE precise

// std::numeric_limits<float>::epsilon() and max(), exactly (0x34000000, 0x7f7fffff).
float bc_epsilon() { return uintBitsToFloat(0x34000000u); }
float bc_huge() { return uintBitsToFloat(0x7f7fffffu); }
// std::numeric_limits<float>::min(), the smallest normal value (0x00800000).
float bc_tiny() { return uintBitsToFloat(0x00800000u); }
