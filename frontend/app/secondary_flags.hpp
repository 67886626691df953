// The dof-secondary flags (--secondary-layers, --clusters-per-facet,
// --secondary-fov, --layer-size, --lens-parts, --secondary-bounces,
// --bounce-time-slices) that `blurcull render` and `blurcull view` share:
// declared, parsed and refused for the other methods in one place
// (docs/secondary-rays.md, "The renderer").
#pragma once

#include "render/common/render_method.hpp"
#include "render/secondary/secondary_options.hpp"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace blurcull::frontend {

struct SecondaryFlags {
    SecondaryOptions dof_secondary;                   // the flags' values (bounces: see secondary_bounces)
    std::string secondary_bounces = "image-space";    // image-space, exact or environment
    std::string time_slices = "auto";                 // --bounce-time-slices: auto or 1 .. 64
    std::vector<CLI::Option*> dof_secondary_options;  // only --method dof-secondary takes them

    // Adds the flags with their ranges and the paper's defaults.
    void add_options(CLI::App& app);

    // The options the flags give, --secondary-bounces parsed.
    SecondaryOptions secondary_options() const;

    // Throws std::invalid_argument naming the first flag given when `method`
    // is not dof-secondary.
    void refuse_secondary_flags(RenderMethod method) const;
};

}  // namespace blurcull::frontend
