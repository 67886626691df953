#include "render/gl/shader_stages.hpp"

#include "render/gl/render_glsl.hpp"

#include <blurcull/glsl/kernel_glsl.hpp>

#include <string>

namespace blurcull::gl {

std::string_view embedded_source(std::string_view name) {
    const std::string_view text = glsl::render_shader_source(name);
    if (text.empty()) throw GlError("gl: shader '" + std::string(name) + "' was not embedded at build time");
    return text;
}

ShaderStage shader_stage(GLenum type, std::string_view main_name, Prelude prelude) {
    ShaderStage stage{type, {glsl::kernel_source()}};
    auto add = [&](std::string_view name) { stage.sources.push_back(embedded_source(name)); };
    switch (prelude) {
        case Prelude::render:
        case Prelude::render_masked:
            add("gpu_layout_shared.h");
            add("render_common.glsl");
            if (prelude == Prelude::render_masked) {
                add("surface_shared.h");
                add("render_mask.glsl");
            }
            break;
        case Prelude::layers:
        case Prelude::layer_fragments:
            add("gpu_layout_shared.h");
            add("layer_raster_shared.h");
            add("gl_layer_shared.h");
            if (prelude == Prelude::layer_fragments) add("render_layers_fragment.glsl");
            break;
        case Prelude::secondary:
        case Prelude::clusters:
            add("gpu_layout_shared.h");
            add("bounce_shared.h");
            add("render_secondary_common.glsl");
            if (prelude == Prelude::clusters) add("gl_cluster_shared.h");
            break;
        case Prelude::resolve:
            add("gpu_layout_shared.h");
            add("gl_cluster_shared.h");
            add("optics_shared.h");
            add("resolve_shared.h");
            break;
    }
    add(main_name);
    return stage;
}

}  // namespace blurcull::gl
