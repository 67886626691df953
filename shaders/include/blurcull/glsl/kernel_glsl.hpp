// The kernel's GLSL, embedded at build time (target blurcull_glsl; the
// definitions are generated from include/blurcull/detail/*_body.inl by
// shaders/CMakeLists.txt and checked with glslangValidator).
#pragma once

#include <string_view>

namespace blurcull::glsl {

// The whole of blurcull_kernel.glsl: "#version 450 core", the prelude (real,
// BC_FN, BC_IN/BC_OUT/BC_INOUT, bc_epsilon, bc_huge), then every shared
// formula; no main. Pass it as the first string of glShaderSource, then the
// shader's own code.
std::string_view kernel_source();

// The same text without its first line (the #version line), for a shader that
// writes its own #version and #extension lines first.
std::string_view kernel_source_without_version();

}  // namespace blurcull::glsl
