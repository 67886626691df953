#include "render/common/render_method.hpp"

#include <stdexcept>

namespace blurcull::frontend {

const std::vector<RenderMethodInfo>& render_methods() {
    static const BackendSet rasterizers = backend_bit(Backend::cpu) | backend_bit(Backend::gl);
    static const std::vector<RenderMethodInfo> methods = {
        {RenderMethod::stochastic, "stochastic", {}, "culled stochastic rasterization", true, 0.0, all_backends},
        {RenderMethod::interleave, "interleave", {}, "interleaved sampling, tiles of (u, v, t) tuples", false, 12.0,
         rasterizers},
        {RenderMethod::interval, "interval", {}, "one sample per shutter stratum, a screen box per stratum", false,
         12.0, rasterizers},
        {RenderMethod::accum, "accum", {}, "the accumulation buffer, one pinhole pass per sample", false, 4.0,
         rasterizers},
        // The stochastic rasterizer's samples (culled) with one bounce on
        // mirrors and glass traced through clusters' layered images
        // (docs/secondary-rays.md); per sample: the winning id and colour.
        {RenderMethod::dof_secondary, "dof-secondary", {"secondary"},
         "stochastic rasterization plus one bounce on mirrors and glass traced in image space (clusters, virtual "
         "views, layered images)",
         true, 16.0, rasterizers},
    };
    return methods;
}

const RenderMethodInfo& render_method_info(RenderMethod method) {
    return render_methods()[static_cast<std::size_t>(method)];
}

const char* to_string(RenderMethod method) { return render_method_info(method).name; }

std::vector<std::string> render_method_names() {
    std::vector<std::string> names;
    for (const RenderMethodInfo& info : render_methods()) names.emplace_back(info.name);
    return names;
}

std::vector<std::string> render_method_names_and_aliases() {
    std::vector<std::string> names;
    for (const RenderMethodInfo& info : render_methods()) {
        names.emplace_back(info.name);
        names.insert(names.end(), info.aliases.begin(), info.aliases.end());
    }
    return names;
}

RenderMethod parse_render_method(const std::string& name) {
    std::string valid;
    for (const RenderMethodInfo& info : render_methods()) {
        if (name == info.name) return info.method;
        for (const std::string& alias : info.aliases) {
            if (name == alias) return info.method;
        }
        valid += (valid.empty() ? "" : ", ") + std::string(info.name);
    }
    throw std::invalid_argument("unknown render method '" + name + "' (valid: " + valid + ")");
}

std::string render_method_help() {
    std::string text;
    for (const RenderMethodInfo& info : render_methods()) {
        if (!text.empty()) text += "; ";
        text += std::string(info.name) + ": " + info.help + " (" + describe_backends(info.backends) + ")";
    }
    return text;
}

}  // namespace blurcull::frontend
