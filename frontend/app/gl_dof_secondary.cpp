#include "app/gl_dof_secondary.hpp"

#include <cstdint>
#include <vector>

namespace blurcull::frontend {
namespace {

// The context, made current: the trace pass compiles on it.
const gl::HeadlessContext& made_current(const gl::HeadlessContext& context) {
    context.make_current();
    return context;
}

}  // namespace

GlDofSecondary::GlDofSecondary(GlRenderer& rasterizer, const gl::HeadlessContext& trace_context)
    : rasterizer_(&rasterizer), trace_context_(&trace_context), tracer_(made_current(trace_context)) {}

RenderResult GlDofSecondary::render(const Scene& scene, const RenderSettings& settings, const GlOptions& gl_options,
                                    const SecondaryOptions& options, SecondaryStats* stats) const {
    const PrimaryPass primary = [&](const RenderSettings& primary_settings, std::vector<std::uint32_t>& ids) {
        GlOptions rasterizer_options = gl_options;
        rasterizer_options.keep_sample_ids = true;
        return rasterizer_->render(scene, primary_settings, rasterizer_options, &ids);
    };
    const LayerTracer tracer = [&](const kernelf::LayerView& view, const std::vector<float>& depth, int layers,
                                   float thickness, const std::vector<kernelf::LayerSegment>& segments) {
        trace_context_->make_current();
        return tracer_.trace(view, depth, layers, thickness, segments);
    };
    return render_dof_secondary(scene, settings, options, stats, &tracer, &primary);
}

}  // namespace blurcull::frontend
