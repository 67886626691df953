// The GL backend's shader mains (shaders/glsl/render_*), embedded at configure
// time by shaders/CMakeLists.txt. Each is compiled after kernel_source().
#pragma once

#include <string_view>

namespace blurcull::glsl {

// The text of shaders/glsl/<name> (e.g. "render_setup.comp"); empty when there
// is no such file.
std::string_view render_shader_source(std::string_view name);

}  // namespace blurcull::glsl
