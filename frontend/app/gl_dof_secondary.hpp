// dof-secondary on the gl backend (docs/secondary-rays.md, "What the gl
// backend runs"): the GL rasterizer's per-sample winners for the primary
// visibility, and on a second headless context the clusters' layered images
// and pyramids (GlLayerBuilder) and the image-space traces (GlLayerTracer);
// clustering, views, interval clipping and shading on the host. Header-only
// so the tests wire the same passes as `blurcull render`.
#pragma once

#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_layer_images.hpp"
#include "render/gl/gl_layer_trace.hpp"
#include "render/secondary/dof_secondary.hpp"

#include <utility>

namespace blurcull::frontend {

// render/secondary's layers from the GL build's read-back, its counts added to `stats`.
inline ClusterLayers to_cluster_layers(GlClusterLayers&& built, LayerStats& stats) {
    stats.fragments += built.counts.fragments;
    stats.culled_near += built.counts.culled_near;
    stats.culled_in_front += built.counts.culled_in_front;
    stats.culled_normal += built.counts.culled_normal;
    stats.dropped += built.counts.dropped;
    LayerImages images;
    images.size = built.size;
    images.layers = built.layers;
    images.depth = std::move(built.depth);
    images.triangle = std::move(built.triangle);
    DepthPyramid pyramid = DepthPyramid::from_levels(built.size, built.pyramid);
    return ClusterLayers{std::move(images), std::move(pyramid)};
}

class GlDofSecondary {
public:
    // Makes the rasterizer's context and the passes' context; throws
    // gl::GlError when either cannot be made or a pass does not compile.
    GlDofSecondary() : context_(gl::HeadlessContext::create()), tracer_(context_), builder_(context_) {}

    // The GL layer build as render_dof_secondary takes it.
    LayerBuilder layer_builder() const {
        return [this](const WorldTriangles& world, const kernelf::LayerView& view, int layers,
                      const ClusterCulls& culls, LayerStats& stats) {
            context_.make_current();
            const GlLayerInput input{&world.vertices, &world.normals, &culls.own, &culls.origins,
                                     culls.normal_threshold};
            return to_cluster_layers(builder_.build(view, layers, input), stats);
        };
    }

    // The GL trace pass as render_dof_secondary takes it.
    LayerTracer layer_tracer() const {
        return [this](const kernelf::LayerView& view, const std::vector<float>& depth, int layers, float thickness,
                      const std::vector<kernelf::LayerSegment>& segments) {
            context_.make_current();
            return tracer_.trace(view, depth, layers, thickness, segments);
        };
    }

    // The primary pass: the GL rasterizer's image and sample ids.
    PrimaryPass primary_pass(const Scene& scene, const GlOptions& gl_options) {
        return [this, &scene, gl_options](const RenderSettings& settings, std::vector<std::uint32_t>& ids) {
            GlOptions options = gl_options;
            options.keep_sample_ids = true;
            return rasterizer_.render(scene, settings, options, &ids);
        };
    }

    // render_dof_secondary with the GL passes, the layers where `layers_on` says.
    RenderResult render(const Scene& scene, const RenderSettings& settings, const SecondaryOptions& options,
                        const GlOptions& gl_options = {}, LayerImagesOn layers_on = LayerImagesOn::gl,
                        SecondaryStats* stats = nullptr) {
        const PrimaryPass primary = primary_pass(scene, gl_options);
        const LayerTracer tracer = layer_tracer();
        const LayerBuilder builder = layer_builder();
        return render_dof_secondary(scene, settings, options, stats, &tracer, &primary,
                                    layers_on == LayerImagesOn::gl ? &builder : nullptr);
    }

private:
    GlRenderer rasterizer_;
    gl::HeadlessContext context_;
    GlLayerTracer tracer_;
    GlLayerBuilder builder_;
};

}  // namespace blurcull::frontend
