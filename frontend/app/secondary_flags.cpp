#include "app/secondary_flags.hpp"

#include <stdexcept>
#include <string>

namespace blurcull::frontend {

void SecondaryFlags::add_options(CLI::App& app) {
    dof_secondary_options = {
        app.add_option("--secondary-layers", dof_secondary.layers,
                       "dof-secondary: depth-peeled layers per cluster view")
            ->check(CLI::Range(1, 8))->capture_default_str(),
        app.add_option("--clusters-per-facet", dof_secondary.clusters_per_facet,
                       "dof-secondary: k-means clusters per dodecahedron facet at most")
            ->check(CLI::Range(1, 3))->capture_default_str(),
        app.add_option("--secondary-fov", dof_secondary.fov_degrees,
                       "dof-secondary: field of view of a cluster's virtual view, degrees")
            ->check(CLI::Range(1.0f, 179.0f))->capture_default_str(),
        app.add_option("--layer-size", dof_secondary.layer_size, "dof-secondary: texels per side of a cluster's layers")
            ->check(CLI::Range(16, 4096))->capture_default_str(),
        app.add_option("--lens-parts", dof_secondary.lens_parts,
                       "dof-secondary: lens parts with a depth interval each (1, 4 or 16)")
            ->check(CLI::IsMember({1, 4, 16}))->capture_default_str(),
        app.add_option("--secondary-bounces", secondary_bounces,
                       "dof-secondary: image-space (the method), exact (every bounce against every triangle: the "
                       "reference) or environment (the primary-only image)")
            ->check(CLI::IsMember({"image-space", "exact", "environment"}))->capture_default_str(),
        app.add_option("--bounce-time-slices", time_slices,
                       "dof-secondary: shutter slices, each bounced in the scene at its middle (1 to 64), or auto "
                       "(1 for a scene that does not move, else " +
                           std::to_string(auto_time_slices_moving) + ")")
            ->check(CLI::IsMember({"auto"}) | CLI::Range(1, 64))->capture_default_str(),
    };
}

SecondaryOptions SecondaryFlags::secondary_options() const {
    SecondaryOptions options = dof_secondary;
    options.bounces = secondary_bounces == "exact"         ? SecondaryBounces::exact
                      : secondary_bounces == "environment" ? SecondaryBounces::environment_only
                                                           : SecondaryBounces::image_space;
    options.time_slices = time_slices == "auto" ? 0 : std::stoi(time_slices);
    return options;
}

void SecondaryFlags::refuse_secondary_flags(RenderMethod method) const {
    if (method == RenderMethod::dof_secondary) return;
    for (const CLI::Option* option : dof_secondary_options) {
        if (option->count() > 0) {
            throw std::invalid_argument(option->get_name() + ": only --method dof-secondary takes it (method " +
                                        to_string(method) + ")");
        }
    }
}

}  // namespace blurcull::frontend
