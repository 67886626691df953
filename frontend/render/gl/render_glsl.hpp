// The GL backend's shader mains (frontend/render/gl/shaders/render_*),
// embedded at configure time by frontend/render/gl/CMakeLists.txt into
// blurcull_gl. Each is compiled after the kernel's kernel_source().
#pragma once

#include <string_view>

namespace blurcull::glsl {

// The text of frontend/render/gl/shaders/<name> (e.g. "render_setup.comp"),
// or of frontend/render/gl/gpu_layout_shared.h for "gpu_layout_shared.h";
// empty when there is no such file.
std::string_view render_shader_source(std::string_view name);

}  // namespace blurcull::glsl
