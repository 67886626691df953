#include "render/common/cull_method.hpp"

#include <blurcull/kernel.hpp>

#include <stdexcept>
#include <utility>

namespace blurcull::frontend {

namespace {

// A registry entry; what the method needs comes from the kernel's record
// (kernel cull_traits), so that no list of methods is written twice.
CullMethodInfo entry(CullMethod method, const char* name, std::vector<std::string> aliases, const char* help,
                     int kernel_method, BackendSet backends) {
    CullMethodInfo info{method, name, std::move(aliases), help, kernel_method, backends, 0, false};
    info.traits = kernelf::cull_traits(kernel_method);
    info.bounds_samples = (info.traits & BC_CULL_BOUNDS_SAMPLES) != 0;
    return info;
}

}  // namespace

const std::vector<CullMethodInfo>& cull_methods() {
    static const BackendSet rasterizers = backend_bit(Backend::cpu) | backend_bit(Backend::gl);
    // Each entry's formula (docs/architecture.md, "hop test"): the kernel's
    // sample_bounds (include/blurcull/detail/sample_bounds_body.inl) runs
    // screen_bound (screen_bound_body.inl: bbox, hull) and, for the methods
    // that bound samples, dual_space_body.inl or two_stage_body.inl (and for
    // edges edge_bounds_body.inl after it, for hyperplane hyperplane_body.inl),
    // as the kernel's cull_traits of the method say.
    static const std::vector<CullMethodInfo> methods = {
        entry(CullMethod::bbox, "bbox", {}, "the clipped screen box of the triangle over shutter and lens", BC_CULL_BBOX,
              rasterizers),
        entry(CullMethod::hull, "hull", {}, "the screen box and the convex hull", BC_CULL_HULL, rasterizers),
        entry(CullMethod::dualspace, "dualspace", {},
              "the screen box, then lens and time bounds per footprint (Laine et al. 2011)", BC_CULL_DUALSPACE,
              rasterizers),
        entry(CullMethod::two_stage, "twostage", {"clip2"},
              "the hull, then lens and time bounds per footprint in two stages", BC_CULL_TWO_STAGE, rasterizers),
        // The GL backend's per-cell bounds carry the two-stage part, not the edge planes.
        entry(CullMethod::edges, "edges", {}, "two-stage, then a plane per triangle edge in lens and time per footprint",
              BC_CULL_EDGES, rasterizers),
        // Munkberg and Akenine-Moller 2012 (hyperplane_body.inl); on GL its planes cull whole cells only.
        entry(CullMethod::hyperplane, "hyperplane", {},
              "two-stage, then one hyperplane per triangle edge per tile in (x, y, u, v, t) (Munkberg and "
              "Akenine-Moller 2012)",
              BC_CULL_HYPERPLANE, rasterizers),
    };
    return methods;
}

const CullMethodInfo& cull_method_info(CullMethod method) {
    return cull_methods()[static_cast<std::size_t>(method)];
}

const char* to_string(CullMethod method) { return cull_method_info(method).name; }

int kernel_cull_method(CullMethod method) { return cull_method_info(method).kernel_method; }

CullMethod parse_cull_method(const std::string& name) {
    std::string valid;
    for (const CullMethodInfo& info : cull_methods()) {
        if (name == info.name) return info.method;
        for (const std::string& alias : info.aliases) {
            if (name == alias) return info.method;
        }
        valid += (valid.empty() ? "" : ", ") + std::string(info.name);
    }
    throw std::invalid_argument("unknown cull method '" + name + "' (valid: " + valid + ")");
}

std::vector<std::string> cull_method_names_and_aliases() {
    std::vector<std::string> names;
    for (const CullMethodInfo& info : cull_methods()) {
        names.emplace_back(info.name);
        names.insert(names.end(), info.aliases.begin(), info.aliases.end());
    }
    return names;
}

std::string cull_method_help() {
    std::string text;
    for (const CullMethodInfo& info : cull_methods()) {
        if (!text.empty()) text += "; ";
        text += std::string(info.name) + ": " + info.help;
        for (const std::string& alias : info.aliases) text += " (alias " + alias + ")";
    }
    return text;
}

}  // namespace blurcull::frontend
