// One way to build the GL backend's shaders: every stage is the kernel's
// emitted GLSL, a fixed prelude of embedded headers, then one main from
// shaders/ (all embedded at configure time by CMakeLists.txt). The binding
// points the stages and the host share are named in gpu_layout_shared.h,
// which every prelude holds. docs/gl-backend.md, "Shaders".
#pragma once

#include "render/gl/gl_context.hpp"

#include <string_view>

namespace blurcull::gl {

// The text of an embedded file: shaders/<name> (e.g. "render_setup.comp") or
// one of the shared headers CMakeLists.txt lists (e.g. "gpu_layout_shared.h").
// Throws GlError naming it when it was not embedded at build time.
std::string_view embedded_source(std::string_view name);

// What a stage holds between the kernel's GLSL and its main.
enum class Prelude {
    // gpu_layout_shared.h and render_common.glsl: the stochastic and method
    // passes (gl_backend.cpp, gl_sampling_methods.cpp).
    render,
    // render's, then surface_shared.h and render_mask.glsl: the fragment
    // stages whose main calls mask_keeps (the alpha mask, gl_alpha_mask.hpp).
    render_masked,
    // gpu_layout_shared.h (for its bindings), layer_raster_shared.h and
    // gl_layer_shared.h: dof-secondary's layer passes (gl_layer_images.cpp).
    layers,
    // layers', then render_layers_fragment.glsl: the two scans of the layer
    // passes that store fragments (render_layers.frag, render_layers_raster.comp).
    layer_fragments,
    // gpu_layout_shared.h, bounce_shared.h and render_secondary_common.glsl:
    // dof-secondary's clip and trace passes (gl_layer_trace.cpp).
    secondary,
    // secondary's, then gl_cluster_shared.h: dof-secondary's clustering
    // pass (gl_clustering.cpp).
    clusters,
    // gpu_layout_shared.h, gl_cluster_shared.h, optics_shared.h and
    // resolve_shared.h: dof-secondary's primary resolve (gl_secondary_resolve.cpp).
    resolve,
};

// A stage of `type` (GL_COMPUTE_SHADER, GL_VERTEX_SHADER, ...): the kernel's
// GLSL, `prelude`'s headers, then shaders/`main_name`; what Program compiles.
// Throws GlError when a piece was not embedded at build time.
ShaderStage shader_stage(GLenum type, std::string_view main_name, Prelude prelude = Prelude::render);

}  // namespace blurcull::gl
