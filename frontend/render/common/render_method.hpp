// The render methods: which renderer turns the scene into samples
// (docs/sampling.md). The registry below is the one list of their names; the
// command's --method check and help, its summaries and memory budget, and the
// backends all read it.
#pragma once

#include "render/common/backend.hpp"

#include <string>
#include <vector>

namespace blurcull::frontend {

enum class RenderMethod { stochastic, interleave, interval, accum, dof_secondary };

struct RenderMethodInfo {
    RenderMethod method;
    const char* name;                  // what the command takes and prints
    std::vector<std::string> aliases;  // other names accepted
    const char* help;                  // one line
    // Whether the cull method applies (only the stochastic rasterizer culls;
    // the others bound each pass by a box).
    bool culls;
    // Bytes per sample of the buffers the CPU renderer keeps for the whole
    // frame (interleave, interval: a double depth and a uint32 hit; accum: the
    // hit), for the command's memory budget.
    double bytes_per_sample;
    BackendSet backends;               // the backends that take it
};

// Every render method, in the order of the enum.
const std::vector<RenderMethodInfo>& render_methods();

// The registry entry of `method`.
const RenderMethodInfo& render_method_info(RenderMethod method);

// "stochastic", "interleave", "interval", "accum", "dof-secondary".
const char* to_string(RenderMethod method);

// The names of render_methods(), in order.
std::vector<std::string> render_method_names();

// Every name and alias parse_render_method takes.
std::vector<std::string> render_method_names_and_aliases();

// The method named `name`; throws std::invalid_argument("unknown render method
// 'x' (valid: stochastic, interleave, interval, accum)") otherwise.
RenderMethod parse_render_method(const std::string& name);

// "stochastic: ...; interleave: ..." for a --help text.
std::string render_method_help();

}  // namespace blurcull::frontend
