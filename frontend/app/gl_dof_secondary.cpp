#include "app/gl_dof_secondary.hpp"

#include "render/common/shading.hpp"
#include "render/gl/gl_cluster_shared.h"
#include "render/gl/gl_phase_timers.hpp"

#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace blurcull::frontend {
namespace {

// resolve_primary's result from the GPU resolve's read-back (its rays'
// words decoded; the lens part from the pixel key).
PrimaryResolve to_primary_resolve(const GlResolved& gpu) {
    auto float_of = [](std::uint32_t bits) {
        float value;
        std::memcpy(&value, &bits, sizeof value);
        return value;
    };
    PrimaryResolve out;
    out.sample_colour = gpu.sample_colour;
    out.reflector_samples = gpu.reflector_samples;
    out.rays.resize(gpu.info.size());
    for (std::size_t r = 0; r < gpu.info.size(); ++r) {
        const glm::uvec4 p = gpu.points[2 * r], d = gpu.points[2 * r + 1], info = gpu.info[r];
        SecondaryRay& ray = out.rays[r];
        ray.origin = glm::vec3(float_of(p.x), float_of(p.y), float_of(p.z));
        ray.direction = glm::vec3(float_of(d.x), float_of(d.y), float_of(d.z));
        ray.weight = glm::vec3(float_of(info.z));
        ray.sample = info.x;
        ray.lens_part = d.w & ((1u << BC_GROUP_PART_BITS) - 1u);
        ray.triangle = p.w;
        ray.time = float_of(info.y);
    }
    return out;
}

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
// fitted (GlClustering), each cluster's rays and origins (for the in-front
// cull) gathered from there by index instead of uploaded, and (group())
// its groups, own triangles and normal cone made there: a cluster whose
// view holds all its rays is queued with nothing but its view.
// Its phases: gpu_bounce_layers (the layers and pyramid) and
// gpu_bounce_trace (clipping, traces and surfaces), on hardware GL only;
// wall_bounce_layers and wall_bounce_trace (the host's time to issue them:
// nothing waits), wall_bounce_readback (finish(): waits for all of the
// batch's GPU work, then reads the hits and counts); with the clustering,
// gpu_ and wall_bounce_gpu_clustering (its passes, their upload and
// read-back, and the grouping pass). With `resolve` the primary samples
// are resolved there too (GlSecondaryResolve): gpu_ and
// wall_primary_resolve (the passes, the ids' upload, the read-back).
class GlClusterBouncer final : public ClusterBouncer {
public:
    GlClusterBouncer(const gl::HeadlessContext& context, const GlLayerBuilder& builder, const GlLayerTracer& tracer,
                     GlLayerRaster raster, const GlClustering* clustering, const GlSecondaryResolve* resolve)
        : context_(&context),
          builder_(&builder),
          tracer_(&tracer),
          raster_(raster),
          clustering_(clustering),
          resolve_(resolve) {}
    GlClusterBouncer(const GlClusterBouncer&) = delete;
    GlClusterBouncer& operator=(const GlClusterBouncer&) = delete;
    // The timers' queries are deleted on the current context: this one's.
    ~GlClusterBouncer() override {
        if (!timers_) return;
        context_->make_current_for_release();
        timers_.reset();
    }

    std::optional<PrimaryResolve> resolve(const Scene& scene, const CameraModel& model, const RenderSettings& settings,
                                          const std::vector<std::uint32_t>& ids, int lens_parts) override {
        if (resolve_ == nullptr) return std::nullopt;
        make_timers();
        timers_->begin(resolve_phase);
        const std::optional<GlResolved> gpu = resolve_->resolve(resolve_input(scene, model, settings, lens_parts), ids);
        timers_->end(resolve_phase);
        resolved_rays_ = gpu ? gpu->info.size() : 0;
        if (!gpu) return std::nullopt;  // past the GL's storage blocks: the host resolves them
        return to_primary_resolve(*gpu);
    }

    std::optional<Clustering<float>> cluster(const std::vector<glm::vec3>& positions,
                                             const std::vector<glm::vec3>& directions,
                                             const std::vector<RayGroupKey>& keys, const ClusterOptions& options,
                                             float tan_half_fov, float min_near, ClusterViews<float>& views) override {
        // More rays than a storage block holds: the host clusters them (the same clusters).
        if (clustering_ == nullptr || positions.size() > clustering_->max_rays()) return std::nullopt;
        make_timers();
        timers_->begin(clustering_phase);
        // The rays' clusters stay on the GPU unless the host asks (cluster_of()).
        // A batch of all the resolved rays (one shutter slice) is already
        // there, in the resolve's order: copied, not uploaded.
        const bool resolved_there = resolve_ != nullptr && resolved_rays_ > 0 && positions.size() == resolved_rays_;
        Clustering<float> clusters =
            clustering_->cluster(positions, directions, options, tan_half_fov, min_near, &views, &keys, false,
                                 resolved_there ? &resolve_->points_buffer() : nullptr);
        rays_on_gpu_ = true;
        timers_->end(clustering_phase);
        return clusters;
    }

    std::vector<int> cluster_of() override {
        if (!rays_on_gpu_) return {};
        context_->make_current();
        timers_->begin(clustering_phase);
        std::vector<int> clusters = clustering_->cluster_of();
        timers_->end(clustering_phase);
        return clusters;
    }

    bool group(const std::vector<glm::vec3>& forwards, bool cull_normals, std::size_t triangles) override {
        if (!rays_on_gpu_) return false;
        context_->make_current();
        timers_->begin(clustering_phase);
        const bool grouped = clustering_->group(forwards, cull_normals, triangles);
        timers_->end(clustering_phase);
        return grouped;
    }

    void begin(const WorldTriangles& triangles, std::size_t max_rays) override {
        make_timers();
        builder_->upload_triangles(triangles.vertices, triangles.normals);
        tracer_->begin_bounces(max_rays);
        queued_ = 0;
        batch_rays_ = max_rays;
    }

    void add_phases(RenderStats& stats) const override {
        if (timers_) timers_->add_to(stats);
    }

    void queue(const WorldTriangles& triangles, const kernelf::LayerView& view, int layers, float thickness,
               const ClusterCulls& culls, const ClusterRays& rays) override {
        context_->make_current();
        GlLayerInput input{&triangles.vertices, &triangles.normals, &culls.own, &culls.origins,
                           culls.normal_threshold};
        if (!rays_on_gpu_) {
            timers_->begin(layers_phase);
            builder_->build_resident(view, layers, input, raster_);
            timers_->end(layers_phase);
            timers_->begin(trace_phase);
            tracer_->queue_bounce(view, layers, thickness, *builder_, rays.starts, rays.directions, rays.group_ends,
                                  queued_);
            timers_->end(trace_phase);
            queued_ += rays.indices.size();
            return;
        }
        // The batch's rays are on the GPU: only their indices and groups
        // go, for the cull's origins and the rays both.
        const gl::Functions& f = context_->gl();
        gl::reserve_storage(f, indices_, rays.indices.size() * sizeof(std::uint32_t), rays.indices.data());
        const std::vector<std::uint32_t> words = group_words(rays.group_ends);
        gl::reserve_storage(f, groups_, words.size() * sizeof(std::uint32_t), words.data());
        bounce_gathered(view, layers, thickness, input, rays.indices.size(), culls.in_front, rays.offset,
                        rays.group_ends.size());
    }

    void queue_grouped(const WorldTriangles& triangles, const kernelf::LayerView& view, int layers, float thickness,
                       std::size_t cluster, bool cull_in_front, float offset) override {
        context_->make_current();
        const gl::Functions& f = context_->gl();
        const GlClustering::GroupedCluster g = clustering_->grouped(cluster);
        // The cluster's list, its groups' count and pairs, copied where the
        // passes read a cluster's; its own bits and threshold by the build.
        const std::size_t word = sizeof(std::uint32_t);
        gl::copy_buffer(f, clustering_->lists_buffer(), g.list_offset,
                        gl::reserve_storage(f, indices_, g.rays * word), 0, g.rays * word);
        const gl::Buffer& groups = gl::reserve_storage(f, groups_, (1 + 2 * g.rays) * word);
        gl::copy_buffer(f, clustering_->slots_buffer(), g.group_count_offset, groups, 0, word);
        gl::copy_buffer(f, clustering_->pairs_buffer(), g.pairs_offset, groups, word, 2 * g.rays * word);
        GlLayerInput input{&triangles.vertices, &triangles.normals, nullptr, nullptr, 2.0f};
        input.own_source = &clustering_->own_buffer();
        input.own_offset = g.own_offset;
        input.threshold_source = &clustering_->slots_buffer();
        input.threshold_offset = g.threshold_offset;
        bounce_gathered(view, layers, thickness, input, g.rays, cull_in_front, offset, g.rays);
    }

    std::vector<LayerBounceHit> finish(LayerStats& stats) override {
        context_->make_current();
        timers_->begin(readback_phase);
        // Gathered rays' hits are by index: one a ray of the batch.
        std::vector<LayerBounceHit> hits = tracer_->finish_bounces(rays_on_gpu_ ? batch_rays_ : queued_);
        rays_on_gpu_ = false;  // the next batch's, if cluster() puts them there
        add_counts(stats, builder_->read_counts());  // the passes are done: no wait
        timers_->end(readback_phase);
        return hits;
    }

private:
    enum Phase : std::size_t { layers_phase, trace_phase, readback_phase, clustering_phase, resolve_phase };

    // A cluster of `rays` rays whose indices and groups (at most
    // max_groups) are in indices_ and groups_: its layers with `input`'s
    // culls (and the in-front cull of those rays' origins), then its clip
    // and traces, hits by ray index.
    void bounce_gathered(const kernelf::LayerView& view, int layers, float thickness, GlLayerInput input,
                         std::size_t rays, bool cull_in_front, float offset, std::size_t max_groups) {
        input.origin_points = &clustering_->points_buffer();
        input.origin_indices = &*indices_;
        input.origin_count = cull_in_front ? rays : 0;  // the cluster's rays, any order
        timers_->begin(layers_phase);
        builder_->build_resident(view, layers, input, raster_);
        timers_->end(layers_phase);
        timers_->begin(trace_phase);
        tracer_->queue_bounce_gathered(view, layers, thickness, *builder_, clustering_->points_buffer(), *indices_,
                                       rays, offset, *groups_, max_groups);
        timers_->end(trace_phase);
    }

    // The context made current, and the timers made on it the first time.
    void make_timers() {
        context_->make_current();
        if (timers_) return;
        std::vector<std::string> names{"bounce_layers", "bounce_trace", "bounce_readback"};
        if (clustering_ != nullptr) names.emplace_back("bounce_gpu_clustering");
        if (resolve_ != nullptr) names.emplace_back("primary_resolve");
        timers_.emplace(context_->gl(), std::move(names), !context_->software(), false);  // no wait between the passes
    }

    const gl::HeadlessContext* context_;
    const GlLayerBuilder* builder_;
    const GlLayerTracer* tracer_;
    GlLayerRaster raster_;
    const GlClustering* clustering_;  // null: the host clusters
    const GlSecondaryResolve* resolve_;  // null: the host resolves
    std::size_t resolved_rays_ = 0;      // the rays resolve() left on the GPU
    bool rays_on_gpu_ = false;        // cluster() left this batch's rays in clustering_'s points
    // The queued cluster's rays, as indices of those points, and its
    // groups (group_words' layout).
    std::optional<gl::Buffer> indices_, groups_;
    std::size_t queued_ = 0;      // rays queued since begin(), their rays uploaded
    std::size_t batch_rays_ = 0;  // begin()'s, the batch's rays
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

GlResolveInput resolve_input(const Scene& scene, const CameraModel& model, const RenderSettings& settings,
                             int lens_parts) {
    GlResolveInput in;
    in.width = settings.width;
    in.height = settings.height;
    in.spp = settings.spp;
    in.sampler = settings.sampler;
    in.seed = settings.seed;
    in.lens_parts = lens_parts;
    in.k_x = model.k_x;
    in.k_y = model.k_y;
    in.lens_radius = model.lens_radius;
    in.lens_slope = model.lens_slope();
    in.background = scene.background;
    for (std::size_t v = 0; v < scene.position_open.size(); ++v) {
        in.view_open.push_back(model.view_position(scene, v, 0));
        in.view_close.push_back(model.view_position(scene, v, 1));
    }
    in.world_open = scene.position_open;
    in.world_close = scene.position_close;
    in.triangles = scene.triangles;
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        const Material& material = scene.materials[scene.triangle_material[t]];
        in.kinds.push_back(static_cast<std::uint32_t>(material.kind));
        in.iors.push_back(material.ior);
    }
    in.colours = shade_all(scene);
    in.inverse_open = glm::inverse(glm::dmat4(model.view_open));
    in.inverse_close = glm::inverse(glm::dmat4(model.view_close));
    return in;
}

GlDofSecondary::GlDofSecondary(GlRenderer& rasterizer, const gl::HeadlessContext& trace_context)
    : rasterizer_(&rasterizer),
      trace_context_(&trace_context),
      tracer_(made_current(trace_context)),
      builder_(trace_context),
      clustering_(trace_context),
      resolve_(trace_context) {}

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
    const bool on_gl = clusters_on == ClustersOn::gl;
    return std::make_unique<GlClusterBouncer>(*trace_context_, builder_, tracer_, raster,
                                              on_gl ? &clustering_ : nullptr, on_gl ? &resolve_ : nullptr);
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
