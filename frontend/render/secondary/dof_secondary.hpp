// The dof-secondary renderer, CPU build: depth of field seen through mirrors
// and glass (Xie, Sun and Wang, JCST 28(3) 2013; docs/secondary-rays.md,
// "The renderer"). Primary visibility is the stochastic rasterizer's
// per-sample winning triangles (render_cpu, culled, so motion blur and the
// thin lens are exact there); each sample on a reflector bounces once from
// its own lens point and hit point; the bounced rays are clustered by
// dodecahedron facet and position, each cluster gets a virtual view with a
// layered image, and the rays are traced through it in image space.
#pragma once

#include "render/common/bounce_shared.h"
#include "render/common/camera_model.hpp"
#include "render/common/render_types.hpp"
#include "render/secondary/layer_images.hpp"
#include "render/secondary/secondary_rays.hpp"
#include "render/secondary/secondary_options.hpp"
#include "scene/scene.hpp"

#include <blurcull/secondary_clusters.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <vector>

namespace blurcull::frontend {

// What a render did, for tests, the bench and the docs.
struct SecondaryStats {
    std::uint64_t reflector_samples = 0;   // primary samples on a mirror or dielectric
    std::uint64_t rays = 0;                // bounced rays
    std::uint64_t rays_image_space = 0;    // traced through a cluster's layers
    std::uint64_t rays_exact = 0;          // traced against the triangles (fallback or the exact mode)
    std::uint64_t rays_hit = 0;            // of all rays, those that found a surface
    std::uint64_t trace_steps = 0;         // texels visited by the image-space traces
    int clusters = 0;                      // summed over the time slices
    int time_slices = 1;                   // of the shutter, each bounced in the scene at its middle
    int clusters_refit_on_normal = 0;      // mean axis left a ray outside: fitted along the facet normal
    int clusters_split = 0;                // still some ray outside (FOV < 74.76 deg): those rays traced exactly
    int clusters_unusable = 0;             // empty or non-finite fit: every ray traced exactly
    LayerStats layers;                     // summed over the clusters
    double layer_build_ms = 0.0;           // building the layers and pyramids (with a ClusterBouncer: and the clipping,
                                           // traces and surfaces run with them), summed over the clusters
    // The host's own steps of the bounce, summed over the clusters (wall
    // time where they run one at a time, as on gl; CPU time over the
    // threads on cpu): facet classification and k-means; each cluster's
    // view, culls and ray groups; shading the hits.
    double clustering_ms = 0.0, views_ms = 0.0, shading_ms = 0.0;
};

// Traces clipped segments through a cluster's layered depth images (depth
// [layer][y][x], +infinity for none): the kernel's layer_trace_begin/step
// loop, on the host (trace_layers_on_host) or in a GPU pass
// (render/gl/gl_layer_trace.hpp) that runs the same emitted text.
using LayerTracer = std::function<std::vector<kernelf::LayerHit>(
    const kernelf::LayerView& view, const std::vector<float>& depth, int layers, float thickness,
    const std::vector<kernelf::LayerSegment>& segments)>;

// Builds a cluster's layered image and its min/max depth pyramid for `view`
// with the culls: build_cluster_layers_on_host (the CPU build) by default,
// the GL rasterizer and a compute pass on the gl backend
// (render/gl/gl_layer_images.hpp, wired in app/gl_dof_secondary.hpp). Adds
// its counts to `stats`.
using LayerBuilder = std::function<ClusterLayers(const WorldTriangles& triangles, const kernelf::LayerView& view,
                                                 int layers, const ClusterCulls& culls, LayerStats& stats)>;

// The primary visibility: renders settings' samples and fills the winning
// triangle of each (render_cpu's layout, no_sample_hit for none); render_cpu
// by default, the GL rasterizer's sample ids on the gl backend (the backends
// agree sample for sample).
using PrimaryPass = std::function<RenderResult(const RenderSettings& settings, std::vector<std::uint32_t>& ids)>;

// A cluster's rays as its image-space bounce takes them, sorted into the
// groups that are clipped together (one pixel's samples in one lens part):
// group g holds rays [g ? group_ends[g - 1] : 0, group_ends[g]).
struct ClusterRays {
    // Empty when the ClusterBouncer holds the batch's rays (its cluster()
    // clustered them): then only `indices` say which.
    std::vector<glm::vec3> starts;      // the ray origins moved off their own surface
    std::vector<glm::vec3> directions;  // unit
    std::vector<std::uint32_t> group_ends;
    // Ray i is ray indices[i] of its batch (the positions and directions a
    // ClusterBouncer clustered), started at origin + offset * direction.
    std::vector<std::uint32_t> indices;
    float offset = 0.0f;
};

// A cluster's whole image-space bounce in one place: its layers with the
// culls, their pyramid, each group's interval clipping, the traces and the
// surface of each hit (render/gl's GlClusterBouncer: all on the GPU, only
// the hits come back). Per batch of clusters (a render's, or one time
// slice's): begin() with the scene's triangles and the most rays the batch
// queues, queue() once per cluster (nothing waits for its work), finish()
// for every queued ray's hit, in the order queued (by ray index where
// cluster() clustered the batch there).
class ClusterBouncer {
public:
    virtual ~ClusterBouncer() = default;
    // The primary samples resolved there (resolve_primary's result for
    // `ids`, the same bit for bit where the GPU rounds as the host does);
    // nullopt: the host resolves them. Called first, once per render.
    virtual std::optional<PrimaryResolve> resolve(const Scene& /*scene*/, const CameraModel& /*model*/,
                                                  const RenderSettings& /*settings*/,
                                                  const std::vector<std::uint32_t>& /*ids*/, int /*lens_parts*/) {
        return std::nullopt;
    }
    // The batch's rays clustered there: cluster_reflector_pixels's result,
    // and each cluster's views in `views` (fit_cluster_views's; the GL
    // build's compute passes give both bit for bit); nullopt: the host
    // clusters them and fits the views. Called before begin(). A bouncer
    // that clusters holds the rays: queue() then gets their indices only
    // (ClusterRays' starts and directions, ClusterCulls' origins empty), and
    // finish() gives the hits by ray index. `keys`: each ray's (in pixel
    // order), for group(). The result's cluster_of may be empty (the rays'
    // clusters left there): cluster_of() reads it.
    virtual std::vector<int> cluster_of() { return {}; }
    virtual std::optional<Clustering<float>> cluster(const std::vector<glm::vec3>& /*positions*/,
                                                     const std::vector<glm::vec3>& /*directions*/,
                                                     const std::vector<RayGroupKey>& /*keys*/,
                                                     const ClusterOptions& /*options*/, float /*tan_half_fov*/,
                                                     float /*min_near*/, ClusterViews<float>& /*views*/) {
        return std::nullopt;
    }
    // After cluster() clustered the batch there: every cluster's groups,
    // own triangles and normal threshold (cluster_rays' and cluster_culls'
    // for the view along forwards[j], with `cull_normals`) made there too,
    // so queue_grouped() needs only a cluster's view. False where it cannot
    // (the host prepares each cluster then, as without it).
    virtual bool group(const std::vector<glm::vec3>& /*forwards*/, bool /*cull_normals*/,
                       std::size_t /*triangles*/) {
        return false;
    }
    virtual void begin(const WorldTriangles& triangles, std::size_t max_rays) = 0;
    virtual void queue(const WorldTriangles& triangles, const kernelf::LayerView& view, int layers, float thickness,
                       const ClusterCulls& culls, const ClusterRays& rays) = 0;
    // queue() of cluster `cluster` (of cluster()'s result) as group() made
    // it, every ray of it in `view` (no split); its rays start `offset`
    // along their direction. Only after group() returned true.
    virtual void queue_grouped(const WorldTriangles& /*triangles*/, const kernelf::LayerView& /*view*/,
                               int /*layers*/, float /*thickness*/, std::size_t /*cluster*/, bool /*cull_in_front*/,
                               float /*offset*/) {
        throw std::logic_error("ClusterBouncer: queue_grouped without group()");
    }
    // Adds the batch's layer counts to `stats`.
    virtual std::vector<LayerBounceHit> finish(LayerStats& stats) = 0;
    // Its own phases (e.g. GPU time), added to the render's ms_per_phase
    // after the bounce phase.
    virtual void add_phases(RenderStats& /*stats*/) const {}
};

// The bounce of `rays` in layers already built: each group's segments
// clipped by the pyramid (BC_BOUNCE_CLIP_ROUNDS rounds), traced (by
// `tracer`, else on the host) and each hit's surface picked from the
// layers (render/common/bounce_shared.h). What ClusterBouncer does in one
// place, here in three; the reference the GL-resident bounce is tested
// against.
std::vector<LayerBounceHit> bounce_in_layers(const kernelf::LayerView& view, const ClusterLayers& layers,
                                             float thickness, const ClusterRays& rays,
                                             const LayerTracer* tracer = nullptr);

// The host loop: trace_layers per segment.
std::vector<kernelf::LayerHit> trace_layers_on_host(const kernelf::LayerView& view, const std::vector<float>& depth,
                                                    int layers, float thickness,
                                                    const std::vector<kernelf::LayerSegment>& segments);

// The shutter slices the image-space bounce of `scene` takes: options'
// time_slices, or for 0 (auto) auto_time_slices_moving when the scene moves
// in world space and 1 when it does not; 1 for the exact and environment
// bounces (an exact bounce sees the scene at its own ray's time).
int bounce_time_slices(const Scene& scene, const SecondaryOptions& options);

// Renders `scene` with settings.spp samples per pixel (the stochastic
// rasterizer's samples and culling) and one bounce on every mirror and
// dielectric sample. A bounced ray sees the scene at the middle of its
// sample's time slice (bounce_time_slices; with one, at mid-shutter): the
// rays of each slice are clustered and get layers of their own; an exact
// bounce (the mode, or the fallback of a ray no view holds) sees it at the
// ray's own time.
// A bounced ray that hits a surface gets its flat shade(); one that leaves
// the scene (or hits nothing in its cluster's layers) the environment.
// Deterministic for any thread count. With `primary` the primary samples come
// from there, else from render_cpu; with `tracer` the image-space traces
// run there, and with `layer_builder` the layered images are built there
// (either makes the clusters run one at a time, on the calling thread: a GL
// context is current on one thread), else on the host; with `bouncer` each
// cluster's layers, clipping, traces and hit surfaces run there instead
// (`tracer` and `layer_builder` unused), its calls on the calling thread,
// the host's steps around them (views, culls, ray groups, shading) on the
// render's threads. Throws
// std::invalid_argument for bad settings or options, SceneError for a bad scene.
RenderResult render_dof_secondary(const Scene& scene, const RenderSettings& settings,
                                  const SecondaryOptions& options = {}, SecondaryStats* stats = nullptr,
                                  const LayerTracer* tracer = nullptr, const PrimaryPass* primary = nullptr,
                                  const LayerBuilder* layer_builder = nullptr, ClusterBouncer* bouncer = nullptr);

}  // namespace blurcull::frontend
