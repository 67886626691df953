#include "render/common/backend.hpp"

#include <stdexcept>

namespace blurcull::frontend {
namespace {

constexpr Backend every_backend[] = {Backend::cpu, Backend::embree, Backend::gl};

}  // namespace

const char* to_string(Backend backend) {
    switch (backend) {
        case Backend::cpu: return "cpu";
        case Backend::embree: return "embree";
        case Backend::gl: return "gl";
    }
    return "unknown";
}

bool backend_built(Backend backend) {
    switch (backend) {
        case Backend::cpu: return true;
        case Backend::embree: return BLURCULL_HAVE_EMBREE != 0;
        case Backend::gl: return BLURCULL_HAVE_GL != 0;
    }
    return false;
}

std::string backend_missing_reason(Backend backend) {
    if (backend_built(backend)) return "";
    if (backend == Backend::embree) return "this blurcull was built without Embree 3 (libembree-dev not found, or BLURCULL_WITH_EMBREE=OFF, when it "
               "was configured)";
    return "this blurcull was built without OpenGL (the headers of libegl-dev, libgl-dev and libosmesa6-dev not "
           "found, or BLURCULL_WITH_GL=OFF, when it was configured)";
}

std::vector<std::string> backend_names() {
    std::vector<std::string> names;
    for (Backend backend : every_backend) names.emplace_back(to_string(backend));
    return names;
}

Backend parse_backend(const std::string& name) {
    for (Backend backend : every_backend) {
        if (name == to_string(backend)) return backend;
    }
    std::string valid;
    for (Backend backend : every_backend) valid += (valid.empty() ? "" : ", ") + std::string(to_string(backend));
    throw std::invalid_argument("unknown backend '" + name + "' (valid: " + valid + ")");
}

std::string describe_backends(BackendSet set) {
    std::vector<std::string> names;
    for (Backend backend : every_backend) {
        if (takes(set, backend)) names.emplace_back(to_string(backend));
    }
    std::string text = "the ";
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) text += i + 1 == names.size() ? " and " : ", ";
        text += names[i];
    }
    return text + (names.size() == 1 ? " backend" : " backends");
}

std::string only_backends_take_it(BackendSet set) {
    const bool one = set != 0 && (set & (set - 1)) == 0;
    return "only " + describe_backends(set) + (one ? " takes it" : " take it");
}

}  // namespace blurcull::frontend
