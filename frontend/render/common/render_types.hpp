// Types every backend shares: the render settings (with the cull and render
// methods of their registries) and what a render returns (the image, its
// statistics and its warnings).
#pragma once

#include "render/common/cull_method.hpp"
#include "render/common/image.hpp"
#include "render/common/render_method.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/pattern_names.hpp>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace blurcull::frontend {

struct RenderSettings {
    int width = 1024;
    int height = 768;
    int spp = 16;  // samples per pixel
    std::uint32_t seed = 1;
    // bbox: on the CPU backend the fastest cull (with its shutter strata,
    // CpuOptions::time_strata), and every cull gives the same image.
    CullMethod cull = CullMethod::bbox;
    int threads = 0;  // 0 = std::thread::hardware_concurrency()
    bool progress = true;  // report progress on stderr when a render is slow
    // Which renderer: stochastic (render_cpu), interleave, interval or accum
    // (render/cpu/methods.hpp, docs/sampling.md).
    RenderMethod method = RenderMethod::stochastic;
    // The stochastic renderers' sample pattern (BC_PATTERN_*, --sampler),
    // drawn through kernel sampler_setup / sampler_sample by every backend
    // (docs/sampling.md, "The sampler": sobol has the lowest error on every
    // built-in scene; hashed, the default before, is what the golden renders
    // pin). The interleave, interval and accum methods have their own samples.
    int sampler = BC_PATTERN_SOBOL;
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
    if (settings.sampler < 0 || settings.sampler >= BC_PATTERN_COUNT) {
        throw std::invalid_argument("unknown sampler id " + std::to_string(settings.sampler) +
                                    " (valid: " + sample_pattern_list() + ")");
    }
    if (settings.threads < 0) {
        throw std::invalid_argument("thread count must be >= 0 (0 = all cores), got " +
                                    std::to_string(settings.threads));
    }
}

struct RenderStats {
    std::uint64_t samples_tested = 0;  // (sample, triangle) tests, or rays for a ray tracer
    std::uint64_t samples_hit = 0;     // tests that found coverage
    // (sample, triangle) pairs a method looked at to decide whether to test
    // (cpu only; 0 elsewhere): every sample of a bounded footprint, or only
    // those in its shutter interval when samples are visited in time order.
    std::uint64_t samples_visited = 0;
    std::uint64_t bounds_computed = 0; // per-footprint sample bounds set up (cpu: blocks and footprints)
    std::uint64_t bounds_empty = 0;    // of those, how many proved the footprint empty
    std::uint64_t secondary_rays = 0;  // rays bounced off mirrors and dielectrics (embree --secondary bounce)
    double ms_total = 0;
    std::vector<std::pair<std::string, double>> ms_per_phase;  // in the order they ran
    // A method's own counts (dof-secondary: clusters, trace steps, culls), in
    // the JSON summary as "counters".
    std::vector<std::pair<std::string, double>> counters;
    std::size_t triangles = 0;

    // Sample test efficiency: hits / tests (0 when nothing was tested).
    double ste() const {
        return samples_tested == 0 ? 0.0 : static_cast<double>(samples_hit) / static_cast<double>(samples_tested);
    }

    // Adds the statistics of more work on the same scene (a progressive
    // render's next pass, a method's later stage): every count and ms_total
    // summed; ms_per_phase and counters summed by name, a name these lack
    // appended in other's order; triangles, the scene's size and not work,
    // the larger. The one way RenderStats are summed, so a field added here
    // is summed everywhere (a sum that skipped counters lost samples_occluded).
    void add(const RenderStats& other) {
        samples_tested += other.samples_tested;
        samples_hit += other.samples_hit;
        samples_visited += other.samples_visited;
        bounds_computed += other.bounds_computed;
        bounds_empty += other.bounds_empty;
        secondary_rays += other.secondary_rays;
        ms_total += other.ms_total;
        add_by_name(ms_per_phase, other.ms_per_phase);
        add_by_name(counters, other.counters);
        if (other.triangles > triangles) triangles = other.triangles;
    }

private:
    static void add_by_name(std::vector<std::pair<std::string, double>>& into,
                            const std::vector<std::pair<std::string, double>>& from) {
        for (const auto& [name, value] : from) {
            auto it = into.begin();
            while (it != into.end() && it->first != name) ++it;
            if (it == into.end()) {
                into.emplace_back(name, value);
            } else {
                it->second += value;
            }
        }
    }
};

struct RenderResult {
    Image image;
    RenderStats stats;
    // One line each, for the caller to show ("cpu: skipped 3 triangles ..."):
    // the render layer prints nothing but its progress.
    std::vector<std::string> warnings;
};

}  // namespace blurcull::frontend
