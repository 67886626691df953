#include "app/gl_dof_secondary.hpp"

#include "render/gl/gl_phase_timers.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace blurcull::frontend {
namespace {

// The context, made current: the passes compile on it.
const gl::HeadlessContext& made_current(const gl::HeadlessContext& context) {
    context.make_current();
    return context;
}

// The GL passes' counts added to render/secondary's.
void add_counts(LayerStats& stats, const GlLayerCounts& counts) {
    stats.fragments += counts.fragments;
    stats.culled_near += counts.culled_near;
    stats.culled_in_front += counts.culled_in_front;
    stats.culled_normal += counts.culled_normal;
    stats.dropped += counts.dropped;
}

// ClusterBouncer on the GL passes: the layers built and left on the GPU,
// then clipped, traced and the surfaces picked there, cluster after cluster
// with nothing waited for until finish() reads every hit back.
// With `clustering` the rays are clustered there too, the clusters' views
// fitted (GlClustering), and each cluster's rays and origins (for the
// in-front cull) gathered from there by index instead of uploaded.
// Its phases: gpu_bounce_layers (the layers and pyramid) and
// gpu_bounce_trace (clipping, traces and surfaces), on hardware GL only;
// wall_bounce_layers and wall_bounce_trace (the host's time to issue them:
// nothing waits), wall_bounce_readback (finish(): waits for all of the
// batch's GPU work, then reads the hits and counts); with the clustering,
// gpu_ and wall_bounce_gpu_clustering (its passes, their upload and
// read-back).
class GlClusterBouncer final : public ClusterBouncer {
public:
    GlClusterBouncer(const gl::HeadlessContext& context, const GlLayerBuilder& builder, const GlLayerTracer& tracer,
                     GlLayerRaster raster, const GlClustering* clustering)
        : context_(&context), builder_(&builder), tracer_(&tracer), raster_(raster), clustering_(clustering) {}
    GlClusterBouncer(const GlClusterBouncer&) = delete;
    GlClusterBouncer& operator=(const GlClusterBouncer&) = delete;
    // The timers' queries are deleted on the current context: this one's.
    ~GlClusterBouncer() override {
        if (!timers_) return;
        context_->make_current_for_release();
        timers_.reset();
    }

    std::optional<Clustering<float>> cluster(const std::vector<glm::vec3>& positions,
                                             const std::vector<glm::vec3>& directions, const ClusterOptions& options,
                                             float tan_half_fov, float min_near, ClusterViews<float>& views) override {
        // More rays than a storage block holds: the host clusters them (the same clusters).
        if (clustering_ == nullptr || positions.size() > clustering_->max_rays()) return std::nullopt;
        make_timers();
        timers_->begin(clustering_phase);
        Clustering<float> clusters = clustering_->cluster(positions, directions, options, tan_half_fov, min_near, &views);
        rays_on_gpu_ = true;
        timers_->end(clustering_phase);
        return clusters;
    }

    void begin(const WorldTriangles& triangles, std::size_t max_rays) override {
        make_timers();
        builder_->upload_triangles(triangles.vertices, triangles.normals);
        tracer_->begin_bounces(max_rays);
        queued_ = 0;
    }

    void add_phases(RenderStats& stats) const override {
        if (timers_) timers_->add_to(stats);
    }

    void queue(const WorldTriangles& triangles, const kernelf::LayerView& view, int layers, float thickness,
               const ClusterCulls& culls, const ClusterRays& rays) override {
        context_->make_current();
        GlLayerInput input{&triangles.vertices, &triangles.normals, &culls.own, &culls.origins,
                           culls.normal_threshold};
        if (rays_on_gpu_) {
            // The batch's rays are on the GPU: only their indices go, for
            // the cull's origins and the rays both.
            const gl::Buffer& indices = gl::reserve_storage(context_->gl(), indices_,
                                                            rays.indices.size() * sizeof(std::uint32_t),
                                                            rays.indices.data());
            input.origin_points = &clustering_->points_buffer();
            input.origin_indices = &indices;
            input.origin_count = culls.in_front ? rays.indices.size() : 0;  // the cluster's rays, any order
        }
        timers_->begin(layers_phase);
        builder_->build_resident(view, layers, input, raster_);
        timers_->end(layers_phase);
        timers_->begin(trace_phase);
        if (rays_on_gpu_)
            tracer_->queue_bounce_gathered(view, layers, thickness, *builder_, clustering_->points_buffer(), *indices_,
                                           rays.indices.size(), rays.offset, rays.group_ends, queued_);
        else
            tracer_->queue_bounce(view, layers, thickness, *builder_, rays.starts, rays.directions, rays.group_ends,
                                  queued_);
        timers_->end(trace_phase);
        queued_ += rays.indices.size();
    }

    std::vector<LayerBounceHit> finish(LayerStats& stats) override {
        context_->make_current();
        timers_->begin(readback_phase);
        std::vector<LayerBounceHit> hits = tracer_->finish_bounces(queued_);
        rays_on_gpu_ = false;  // the next batch's, if cluster() puts them there
        add_counts(stats, builder_->read_counts());  // the passes are done: no wait
        timers_->end(readback_phase);
        return hits;
    }

private:
    enum Phase : std::size_t { layers_phase, trace_phase, readback_phase, clustering_phase };

    // The context made current, and the timers made on it the first time.
    void make_timers() {
        context_->make_current();
        if (timers_) return;
        std::vector<std::string> names{"bounce_layers", "bounce_trace", "bounce_readback"};
        if (clustering_ != nullptr) names.emplace_back("bounce_gpu_clustering");
        timers_.emplace(context_->gl(), std::move(names), !context_->software(), false);  // no wait between the passes
    }

    const gl::HeadlessContext* context_;
    const GlLayerBuilder* builder_;
    const GlLayerTracer* tracer_;
    GlLayerRaster raster_;
    const GlClustering* clustering_;  // null: the host clusters
    bool rays_on_gpu_ = false;        // cluster() left this batch's rays in clustering_'s points
    std::optional<gl::Buffer> indices_;  // the queued cluster's rays, as indices of those points
    std::size_t queued_ = 0;  // rays queued since begin()
    mutable std::optional<GlPhaseTimers> timers_;  // made by begin(), on the context; read by add_phases
};

}  // namespace

ClusterLayers to_cluster_layers(GlClusterLayers&& built, LayerStats& stats) {
    add_counts(stats, built.counts);
    LayerImages images;
    images.size = built.size;
    images.layers = built.layers;
    images.depth = std::move(built.depth);
    images.triangle = std::move(built.triangle);
    DepthPyramid pyramid = DepthPyramid::from_levels(built.size, built.pyramid);
    return ClusterLayers{std::move(images), std::move(pyramid)};
}

GlDofSecondary::GlDofSecondary(GlRenderer& rasterizer, const gl::HeadlessContext& trace_context)
    : rasterizer_(&rasterizer),
      trace_context_(&trace_context),
      tracer_(made_current(trace_context)),
      builder_(trace_context),
      clustering_(trace_context) {}

PrimaryPass GlDofSecondary::primary_pass(const Scene& scene, const GlOptions& gl_options) const {
    return [this, &scene, gl_options](const RenderSettings& primary_settings, std::vector<std::uint32_t>& ids) {
        GlOptions rasterizer_options = gl_options;
        rasterizer_options.keep_sample_ids = true;
        return rasterizer_->render(scene, primary_settings, rasterizer_options, &ids);
    };
}

LayerTracer GlDofSecondary::layer_tracer() const {
    return [this](const kernelf::LayerView& view, const std::vector<float>& depth, int layers, float thickness,
                  const std::vector<kernelf::LayerSegment>& segments) {
        trace_context_->make_current();
        return tracer_.trace(view, depth, layers, thickness, segments);
    };
}

LayerBuilder GlDofSecondary::layer_builder(GlLayerRaster raster) const {
    return [this, raster](const WorldTriangles& world, const kernelf::LayerView& view, int layers,
                          const ClusterCulls& culls, LayerStats& stats) {
        trace_context_->make_current();
        const GlLayerInput input{&world.vertices, &world.normals, &culls.own, &culls.origins, culls.normal_threshold};
        return to_cluster_layers(builder_.build(view, layers, input, raster), stats);
    };
}

std::unique_ptr<ClusterBouncer> GlDofSecondary::cluster_bouncer(GlLayerRaster raster, ClustersOn clusters_on) const {
    return std::make_unique<GlClusterBouncer>(*trace_context_, builder_, tracer_, raster,
                                              clusters_on == ClustersOn::gl ? &clustering_ : nullptr);
}

RenderResult GlDofSecondary::render(const Scene& scene, const RenderSettings& settings, const GlOptions& gl_options,
                                    const SecondaryOptions& options, SecondaryStats* stats,
                                    LayerImagesOn layers_on) const {
    const PrimaryPass primary = primary_pass(scene, gl_options);
    // The layers scanned as the primary samples are, and the rays clustered:
    // in compute with the compute pipeline (what --backend auto picks on a
    // GPU); with the fragment pipeline by the GL rasterizer and on the host
    // (on llvmpipe both are the faster: its compute passes run on the CPU).
    const bool compute = gl_options.pipeline == GlPipeline::compute;
    const GlLayerRaster raster = compute ? GlLayerRaster::compute : GlLayerRaster::graphics;
    if (layers_on == LayerImagesOn::gl) {
        const std::unique_ptr<ClusterBouncer> bouncer =
            cluster_bouncer(raster, compute ? ClustersOn::gl : ClustersOn::host);
        return render_dof_secondary(scene, settings, options, stats, nullptr, &primary, nullptr, bouncer.get());
    }
    const LayerTracer tracer = layer_tracer();
    const LayerBuilder builder = layer_builder(raster);
    return render_dof_secondary(scene, settings, options, stats, &tracer, &primary,
                                layers_on == LayerImagesOn::gl_readback ? &builder : nullptr);
}

}  // namespace blurcull::frontend
