// --method dof-secondary on the gl backend: the GL rasterizer's per-sample
// winners as the primary pass, then per cluster the layered images and
// pyramid (GlLayerBuilder: scanned by the GL rasterizer, or in compute with
// the compute pipeline), the groups' interval
// clipping, the image-space traces and the hits' surfaces in compute passes
// (GlLayerTracer::bounce) on the layers where they were built: only each
// ray's surface comes back. With the compute pipeline the rays are
// clustered in compute passes too (GlClustering, the host's clusters
// exactly). Handed to render_dof_secondary (views and shading on the host). `blurcull render --backend gl` and
// `blurcull view` both render through it (docs/secondary-rays.md, "What the
// gl backend runs").
#pragma once

#include "render/common/camera_model.hpp"
#include "render/common/render_types.hpp"
#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_clustering.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/gl_layer_images.hpp"
#include "render/gl/gl_layer_trace.hpp"
#include "render/gl/gl_secondary_resolve.hpp"
#include "render/secondary/dof_secondary.hpp"
#include "render/secondary/secondary_options.hpp"
#include "scene/scene.hpp"

#include <memory>

namespace blurcull::frontend {

// render/secondary's layers from the GL build's read-back, its counts added to `stats`.
ClusterLayers to_cluster_layers(GlClusterLayers&& built, LayerStats& stats);

// What GlSecondaryResolve needs to resolve `scene`'s samples as
// resolve_primary does with `model`, `settings` and `lens_parts`: the
// camera's constants, each vertex's view positions (the model's) and world
// ones, each triangle's material and shade() colour, the views' inverses in
// double.
GlResolveInput resolve_input(const Scene& scene, const CameraModel& model, const RenderSettings& settings,
                             int lens_parts);

class GlDofSecondary {
public:
    // `rasterizer` renders the primary samples on its own context (made
    // current by its render), `trace_context` runs the layer and trace passes
    // (made current here, compiling them); both may be one window's context,
    // and the caller keeps both alive while this object is used.
    GlDofSecondary(GlRenderer& rasterizer, const gl::HeadlessContext& trace_context);

    // render_dof_secondary of `scene` with the GL passes, the layers built
    // where `layers_on` says; `gl_options` are the rasterizer's (sample ids
    // are kept whatever they say), and with its compute pipeline the layers
    // are scanned in compute too (GlLayerRaster::compute), else by the GL
    // rasterizer. Throws as render_dof_secondary and GlRenderer::render do.
    RenderResult render(const Scene& scene, const RenderSettings& settings, const GlOptions& gl_options,
                        const SecondaryOptions& options, SecondaryStats* stats = nullptr,
                        LayerImagesOn layers_on = LayerImagesOn::gl) const;

    // The passes as render_dof_secondary takes them (for tests that wrap
    // them): render() uses the primary pass and, with the layers on gl, the
    // cluster bouncer (the GPU-resident bounce); with them on the host, the
    // host's layers, clipping and surfaces and the GL trace pass.
    // layer_builder reads each cluster's GL layers back for the host's bounce.
    PrimaryPass primary_pass(const Scene& scene, const GlOptions& gl_options) const;
    LayerTracer layer_tracer() const;
    LayerBuilder layer_builder(GlLayerRaster raster = GlLayerRaster::graphics) const;
    // The bouncer resolves the primary samples (GlSecondaryResolve) and
    // clusters the rays (GlClustering) in compute passes too unless
    // `clusters_on` says host. render() does with the compute pipeline,
    // not with the fragment pipeline.
    enum class ClustersOn { gl, host };
    std::unique_ptr<ClusterBouncer> cluster_bouncer(GlLayerRaster raster = GlLayerRaster::graphics,
                                                    ClustersOn clusters_on = ClustersOn::gl) const;

private:
    GlRenderer* rasterizer_;
    const gl::HeadlessContext* trace_context_;
    GlLayerTracer tracer_;
    GlLayerBuilder builder_;
    GlClustering clustering_;
    GlSecondaryResolve resolve_;
};

}  // namespace blurcull::frontend
