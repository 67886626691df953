// The cull methods: how a rasterizer decides which samples a triangle may
// cover (docs/cpu-renderer.md). The registry below is the one list of their
// names; the command's --cull check and help, its summaries, and the backends
// all read it.
#pragma once

#include "render/common/backend.hpp"

#include <string>
#include <vector>

namespace blurcull::frontend {

enum class CullMethod { bbox, hull, dualspace, two_stage, edges, hyperplane };

struct CullMethodInfo {
    CullMethod method;
    const char* name;                  // what the command takes and prints
    std::vector<std::string> aliases;  // older names still accepted
    const char* help;                  // one line
    int kernel_method;                 // the kernel's BC_CULL_* constant
    BackendSet backends;               // the backends that take it
    // What it needs, from the kernel's record of it (kernel cull_traits:
    // BC_CULL_BUILDS_HULL, BC_CULL_TWO_STAGE_AXES, ...); the backends read
    // these flags, never lists of methods.
    int traits = 0;
    // Whether it bounds lens and time per footprint (kernel::sample_bounds)
    // besides the triangle's screen bound (traits & BC_CULL_BOUNDS_SAMPLES).
    bool bounds_samples = false;
};

// Every cull method, in the order of the enum.
const std::vector<CullMethodInfo>& cull_methods();

// The registry entry of `method`.
const CullMethodInfo& cull_method_info(CullMethod method);

// The method's name: "bbox", "hull", "dualspace", "twostage", "edges", "hyperplane".
const char* to_string(CullMethod method);

// The kernel's BC_CULL_* constant for a method.
int kernel_cull_method(CullMethod method);

// The method named `name` or one of its aliases ("clip2" is twostage);
// throws std::invalid_argument naming the valid methods otherwise.
CullMethod parse_cull_method(const std::string& name);

// Every name and alias parse_cull_method takes.
std::vector<std::string> cull_method_names_and_aliases();

// One line per method for a --help text: "bbox: ...; hull: ...".
std::string cull_method_help();

}  // namespace blurcull::frontend
