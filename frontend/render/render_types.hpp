// Types every backend shares: which culling method to use, the render
// settings, and what a render returns (the image plus its statistics).
#pragma once

#include "render/image.hpp"

#include <blurcull/kernel.hpp>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace blurcull::frontend {

// How a rasterizer decides which samples a triangle may cover (see BRIEF.md 3-4).
enum class CullMethod { bbox, hull, dualspace, clip2, edges };

inline const char* to_string(CullMethod method) {
    switch (method) {
        case CullMethod::bbox: return "bbox";
        case CullMethod::hull: return "hull";
        case CullMethod::dualspace: return "dualspace";
        case CullMethod::clip2: return "clip2";
        case CullMethod::edges: return "edges";
    }
    return "unknown";
}

// The kernel's BC_CULL_* constant for a method.
inline int kernel_cull_method(CullMethod method) {
    switch (method) {
        case CullMethod::bbox: return BC_CULL_BBOX;
        case CullMethod::hull: return BC_CULL_HULL;
        case CullMethod::dualspace: return BC_CULL_DUALSPACE;
        case CullMethod::clip2: return BC_CULL_CLIP2;
        case CullMethod::edges: return BC_CULL_EDGES;
    }
    return BC_CULL_BBOX;
}

// Throws std::invalid_argument naming the valid methods when `name` is none of them.
inline CullMethod parse_cull_method(const std::string& name) {
    for (CullMethod method :
         {CullMethod::bbox, CullMethod::hull, CullMethod::dualspace, CullMethod::clip2, CullMethod::edges}) {
        if (name == to_string(method)) return method;
    }
    throw std::invalid_argument("unknown cull method '" + name + "' (valid: bbox, hull, dualspace, clip2, edges)");
}

struct RenderSettings {
    int width = 1024;
    int height = 768;
    int spp = 16;  // samples per pixel
    std::uint32_t seed = 1;
    CullMethod cull = CullMethod::clip2;
    int threads = 0;  // 0 = std::thread::hardware_concurrency()
    bool progress = true;  // report progress on stderr when a render is slow
    // Which renderer: "stochastic" (render_cpu), "interleave", "interval" or
    // "accum" (render/interleaved_backend.hpp, docs/sampling.md).
    std::string method = "stochastic";
};

// Throws std::invalid_argument with a one-line message when a setting is out of range.
inline void validate_settings(const RenderSettings& settings) {
    if (settings.width < 1 || settings.height < 1) {
        throw std::invalid_argument("image size must be at least 1x1, got " + std::to_string(settings.width) + "x" +
                                    std::to_string(settings.height));
    }
    if (settings.width > 65536 || settings.height > 65536) {
        throw std::invalid_argument("image size is limited to 65536x65536, got " + std::to_string(settings.width) +
                                    "x" + std::to_string(settings.height));
    }
    if (settings.spp < 1 || settings.spp > 65536) {
        throw std::invalid_argument("samples per pixel must be in [1, 65536], got " + std::to_string(settings.spp));
    }
    if (settings.threads < 0) {
        throw std::invalid_argument("thread count must be >= 0 (0 = all cores), got " +
                                    std::to_string(settings.threads));
    }
}

struct RenderStats {
    std::uint64_t samples_tested = 0;  // (sample, triangle) tests, or rays for a ray tracer
    std::uint64_t samples_hit = 0;     // tests that found coverage
    std::uint64_t bounds_computed = 0; // per-footprint sample bounds set up (cpu: blocks and footprints)
    std::uint64_t bounds_empty = 0;    // of those, how many proved the footprint empty
    double ms_total = 0;
    std::vector<std::pair<std::string, double>> ms_per_phase;  // in the order they ran
    std::size_t triangles = 0;

    // Sample test efficiency: hits / tests (0 when nothing was tested).
    double ste() const {
        return samples_tested == 0 ? 0.0 : static_cast<double>(samples_hit) / static_cast<double>(samples_tested);
    }
};

struct RenderResult {
    Image image;
    RenderStats stats;
};

}  // namespace blurcull::frontend
