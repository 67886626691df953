#include "render/cpu/methods.hpp"

#include "render/cpu/cpu_backend.hpp"

namespace blurcull::frontend {

RenderResult render_with_method(const Scene& scene, const RenderSettings& settings) {
    switch (settings.method) {
        case RenderMethod::interleave: return render_interleave(scene, settings);
        case RenderMethod::interval: return render_interval(scene, settings);
        case RenderMethod::accum: return render_accum(scene, settings);
        case RenderMethod::stochastic:
        case RenderMethod::dof_secondary: break;
    }
    return render_cpu(scene, settings);
}

}  // namespace blurcull::frontend
