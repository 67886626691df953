#include "render/secondary/dof_secondary.hpp"

#include "render/common/bounce_shared.h"
#include "render/common/camera_model.hpp"
#include "render/common/progress.hpp"
#include "render/common/shading.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/common/parallel_items.hpp"
#include "render/secondary/exact_trace.hpp"
#include "render/secondary/secondary_rays.hpp"

#include <blurcull/layer_trace.hpp>
#include <blurcull/secondary_clusters.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

namespace blurcull::frontend {
namespace {

using K = kernelf;
using Clock = std::chrono::steady_clock;
constexpr float huge_depth = float(BC_BOUNCE_HUGE_DEPTH);  // FLT_MAX

// What every cluster's work shares.
struct BounceContext {
    const Scene& scene;
    const SecondaryOptions& options;
    const std::vector<SecondaryRay>& rays;
    const WorldTriangles& world;  // the scene at the rays' slice of the shutter (the layers' snapshot)
    bool moving;                  // the scene moves: an exact bounce sees it at its ray's own time
    const std::vector<glm::vec3>& colours;
    float tan_half_fov;
    float min_near;
    float thickness;
    float offset;  // rays start this far along their direction, off their own surface
    int spp;
    const LayerTracer* tracer;  // null: the host loop
    const LayerBuilder* layer_builder;  // null: build_cluster_layers_on_host
    ClusterBouncer* bouncer;            // not null: the whole image-space bounce there
};

// What one ray sees when traced against every triangle where they are at
// the ray's time (as the Embree reference bounces).
glm::vec3 exact_radiance(const BounceContext& c, const SecondaryRay& ray, SecondaryStats& stats) {
    ++stats.rays_exact;
    const ExactHit hit = c.moving ? trace_exact_at(c.scene, ray.time, ray.origin, ray.direction, c.offset)
                                  : trace_exact(c.world, ray.origin, ray.direction, c.offset);
    if (!hit.hit) return environment_radiance(c.scene, ray.direction);
    ++stats.rays_hit;
    const glm::vec3 normal =
        c.moving ? unit_normal(triangle_at(c.scene, hit.triangle, ray.time)) : c.world.normals[hit.triangle];
    return bounce_hit_radiance(c.scene, c.colours, hit.triangle, ray.direction, normal);
}

// The cluster's virtual view: along the mean direction, else along the facet
// normal (holds every direction of the facet from 74.76 degrees); the flags
// tell the caller what is left outside.
K::VirtualView cluster_view(const ClusterViews<float>& views, std::size_t cluster, SecondaryStats& stats) {
    if (views.along_mean[cluster].flags != BC_VIEW_DIRECTION_OUTSIDE) return views.along_mean[cluster];
    ++stats.clusters_refit_on_normal;
    return views.along_normal[cluster];
}

// The culls of a cluster's layers: its own triangles and surface depth, and
// the normal threshold from the cone of its directions.
ClusterCulls cluster_culls(const BounceContext& c, const K::LayerView& view, const std::vector<std::uint32_t>& members,
                           bool rays_resident) {
    ClusterCulls culls;
    culls.own.assign(c.world.vertices.size(), 0);
    float cos_widest = 1.0f;
    for (std::uint32_t r : members) {
        culls.own[c.rays[r].triangle] = 1;
        cos_widest = std::min(cos_widest, K::bc_dot3(c.rays[r].direction, view.forward));
    }
    culls.in_front = c.options.cull_in_front;
    if (c.options.cull_in_front && !rays_resident)
        for (std::uint32_t r : members) culls.origins.push_back(c.rays[r].origin);
    culls.normal_threshold = bounce::bc_normal_cone_threshold(cos_widest, c.options.cull_normals);
    return culls;
}

// The triangle stored nearest the hit: the layer's texel under the hit, or
// the neighbour whose depth there is closest to the hit's.
std::uint32_t hit_triangle(const LayerImages& images, const K::LayerHit& hit) {
    const int hx = bounce::bc_hit_texel(hit.image.x, images.size);
    const int hy = bounce::bc_hit_texel(hit.image.y, images.size);
    float best = std::numeric_limits<float>::infinity();
    std::uint32_t triangle = images.triangle[images.index(hit.layer, hx, hy)];
    for (int y = std::max(0, hy - 1); y <= std::min(images.size - 1, hy + 1); ++y) {
        for (int x = std::max(0, hx - 1); x <= std::min(images.size - 1, hx + 1); ++x) {
            const float gap = std::abs(images.depth[images.index(hit.layer, x, y)] - hit.depth);
            if (bounce::bc_hit_surface_closer(gap, best, x == hx && y == hy)) {
                best = gap;
                triangle = images.triangle[images.index(hit.layer, x, y)];
            }
        }
    }
    return triangle;
}

// Clips one group of rays (one pixel's samples in one lens part) for the
// cluster's layers: their segments clipped together, BC_BOUNCE_CLIP_ROUNDS
// times, by the pyramid's min/max depth over the union of their footprints.
void clip_group(const K::LayerView& view, const DepthPyramid& pyramid, float thickness, const ClusterRays& rays,
                std::size_t first, std::size_t last, K::LayerSegment* segments) {
    for (std::size_t i = first; i < last; ++i)
        segments[i] = K::layer_segment(view, rays.starts[i], rays.directions[i], huge_depth, glm::vec2(0.0f, huge_depth));
    for (int round = 0; round < BC_BOUNCE_CLIP_ROUNDS; ++round) {
        glm::vec4 box = bounce::bc_footprint_none(view.size);
        for (std::size_t i = first; i < last; ++i) box = bounce::bc_footprint_union(box, K::layer_footprint(view, segments[i]));
        if (box.x > box.z) break;  // every segment empty: all leave the layers
        const glm::vec2 range = pyramid.interval(int(box.x), int(box.y), int(box.z), int(box.w));
        const glm::vec2 clip = bounce::bc_bounce_clip(range, thickness, huge_depth);
        for (std::size_t i = first; i < last; ++i) {
            if (segments[i].empty) continue;
            segments[i] = K::layer_segment(view, rays.starts[i], rays.directions[i], huge_depth, clip);
        }
    }
}

// The cluster's members sorted into groups (one pixel's samples in one lens
// part), as the bounce takes them: their indices, in that order.
ClusterRays cluster_rays(const BounceContext& c, std::vector<std::uint32_t> members, bool rays_resident) {
    const auto spp = static_cast<std::uint32_t>(c.spp);
    auto key = [&](std::uint32_t r) { return std::make_pair(c.rays[r].sample / spp, c.rays[r].lens_part); };
    auto by_key = [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); };
    auto pixel = [&](std::uint32_t r) { return c.rays[r].sample / spp; };
    auto by_pixel = [&](std::uint32_t a, std::uint32_t b) { return pixel(a) < pixel(b); };
    // Members come in ray order, so in pixel order (resolve_primary spawns
    // the rays sample by sample): sorting each pixel's run by lens part is
    // the whole stable sort, in O(n log spp).
    if (std::is_sorted(members.begin(), members.end(), by_pixel)) {
        for (auto run = members.begin(); run != members.end();) {
            const auto end = std::find_if(run, members.end(), [&](std::uint32_t r) { return pixel(r) != pixel(*run); });
            std::stable_sort(run, end, by_key);
            run = end;
        }
    } else {
        std::stable_sort(members.begin(), members.end(), by_key);
    }
    ClusterRays rays;
    rays.offset = c.offset;
    if (!rays_resident) {
        rays.starts.reserve(members.size());
        rays.directions.reserve(members.size());
    }
    for (std::size_t i = 0; i < members.size(); ++i) {
        if (!rays_resident) {
            const SecondaryRay& ray = c.rays[members[i]];
            rays.starts.push_back(ray.origin + c.offset * ray.direction);
            rays.directions.push_back(ray.direction);
        }
        if (i + 1 == members.size() || key(members[i + 1]) != key(members[i]))
            rays.group_ends.push_back(static_cast<std::uint32_t>(i + 1));
    }
    rays.indices = std::move(members);
    return rays;
}

// Ray r's radiance from its hit in the layers (the environment on a miss).
void shade_hit(const BounceContext& c, std::uint32_t r, const LayerBounceHit& hit, std::vector<glm::vec3>& radiance,
               SecondaryStats& stats) {
    const SecondaryRay& ray = c.rays[r];
    ++stats.rays_image_space;
    stats.trace_steps += static_cast<std::uint64_t>(std::max(hit.steps, 0));
    if (!hit.hit) {
        radiance[r] = environment_radiance(c.scene, ray.direction);
        return;
    }
    ++stats.rays_hit;
    radiance[r] = bounce_hit_radiance(c.scene, c.colours, hit.triangle, ray.direction, c.world.normals[hit.triangle]);
}

// The far plane of a view: beyond every vertex of the scene.
float far_plane(const WorldTriangles& world, const K::LayerView& view) {
    float far = view.near * 2.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? world.box_max.x : world.box_min.x, (corner & 2) ? world.box_max.y : world.box_min.y,
                          (corner & 4) ? world.box_max.z : world.box_min.z);
        far = std::max(far, glm::length(p - view.eye) * 1.01f + view.near);
    }
    return far;
}

// A cluster ready for its layers: its view, culls and groups of rays (whose
// indices are the rays they are, into the context's rays, in group order);
// or, `grouped`, its view only (the bouncer's group() made the rest, for
// every ray of the cluster).
struct PreparedCluster {
    K::LayerView view{};
    ClusterCulls culls;
    ClusterRays rays;
    bool grouped = false;
};

// From the cluster's fitted view (cluster_view): its layer view, culls and
// ray groups; the rays no view holds traced against the scene (their
// radiance written). False when no ray is left for the layers.
// With `rays_resident` (the bouncer holds the batch's rays) only their
// indices: no starts, directions or origins copied; with `grouped` (the
// bouncer grouped them too) neither culls nor groups where the view holds
// every ray.
bool prepare_cluster(const BounceContext& c, const K::VirtualView& fitted, std::vector<std::uint32_t> members,
                     std::vector<glm::vec3>& radiance, SecondaryStats& stats, PreparedCluster& out,
                     bool rays_resident = false, bool grouped = false) {
    const Clock::time_point views_start = Clock::now();
    if ((fitted.flags & ~BC_VIEW_DIRECTION_OUTSIDE) != 0) {
        ++stats.clusters_unusable;
        for (std::uint32_t r : members) radiance[r] = exact_radiance(c, c.rays[r], stats);
        return false;
    }
    K::LayerView view = K::layer_view_from(fitted, 1.0f, c.options.layer_size);
    view.far = far_plane(c.world, view);
    if ((fitted.flags & BC_VIEW_DIRECTION_OUTSIDE) != 0) {
        // Split: the rays this view cannot hold are traced against the scene.
        ++stats.clusters_split;
        const auto outside = std::stable_partition(members.begin(), members.end(), [&](std::uint32_t r) {
            return K::virtual_view_direction_inside(view.forward, view.right, view.up, view.tan_half_fov,
                                                    c.rays[r].direction);
        });
        for (auto it = outside; it != members.end(); ++it) radiance[*it] = exact_radiance(c, c.rays[*it], stats);
        members.erase(outside, members.end());
        if (members.empty()) return false;
    }
    out.view = view;
    out.grouped = grouped && (fitted.flags & BC_VIEW_DIRECTION_OUTSIDE) == 0;
    if (!out.grouped) {
        out.culls = cluster_culls(c, view, members, rays_resident);
        out.rays = cluster_rays(c, std::move(members), rays_resident);
    }
    stats.views_ms += ms_since(views_start);
    return true;
}

// The prepared cluster's hits shaded into `radiance`: ray members[i]'s is hits[i].
void shade_cluster(const BounceContext& c, const std::vector<std::uint32_t>& members, const LayerBounceHit* hits,
                   std::vector<glm::vec3>& radiance, SecondaryStats& stats) {
    const Clock::time_point shading_start = Clock::now();
    for (std::size_t i = 0; i < members.size(); ++i) shade_hit(c, members[i], hits[i], radiance, stats);
    stats.shading_ms += ms_since(shading_start);
}

// One cluster on the host (or with a LayerBuilder and LayerTracer): its
// view, its layers with the culls, its pyramid, and the traces of its rays
// (or their exact fallback).
void bounce_cluster(const BounceContext& c, const K::VirtualView& view, std::vector<std::uint32_t> members,
                    std::vector<glm::vec3>& radiance, SecondaryStats& stats) {
    PreparedCluster p;
    if (!prepare_cluster(c, view, std::move(members), radiance, stats, p)) return;
    const Clock::time_point build_start = Clock::now();
    const ClusterLayers built =
        c.layer_builder != nullptr ? (*c.layer_builder)(c.world, p.view, c.options.layers, p.culls, stats.layers)
                                   : build_cluster_layers_on_host(c.world, p.view, c.options.layers, p.culls, stats.layers);
    stats.layer_build_ms += ms_since(build_start);
    const std::vector<LayerBounceHit> hits = bounce_in_layers(p.view, built, c.thickness, p.rays, c.tracer);
    shade_cluster(c, p.rays.indices, hits.data(), radiance, stats);
}

// Every cluster through the ClusterBouncer, whose calls run on this thread
// (its GL context's): the host prepares `threads` clusters at a time in
// parallel and queues them in order (the GPU builds and traces them while
// the host prepares the next), the hits are read once at the end and shaded
// in parallel; each thread's statistics go to done(), the rest to `stats`.
// `rays_resident`: the bouncer clustered the rays (its hits come by ray
// index); `grouped`: and grouped them (group() returned true).
template <class Done>
void bounce_clusters_resident(const BounceContext& c, const std::vector<K::VirtualView>& views,
                              std::vector<std::vector<std::uint32_t>>& members, bool rays_resident, bool grouped,
                              std::vector<glm::vec3>& radiance, int threads, SecondaryStats& stats,
                              const Done& done) {
    c.bouncer->begin(c.world, c.rays.size());
    std::vector<std::vector<std::uint32_t>> queued;  // each queued cluster's rays, in the order of its hits (not rays_resident)
    const int clusters = static_cast<int>(views.size());
    const int window = std::max(1, threads);
    for (int first = 0; first < clusters; first += window) {
        const int count = std::min(window, clusters - first);
        std::vector<PreparedCluster> prepared(static_cast<std::size_t>(count));
        std::vector<char> ready(static_cast<std::size_t>(count), 0);
        run_parallel_items(
            threads, count, [] { return SecondaryStats{}; },
            [&](SecondaryStats& local, int k) {
                const auto j = static_cast<std::size_t>(first + k);
                ready[static_cast<std::size_t>(k)] =
                    prepare_cluster(c, views[j], std::move(members[j]), radiance, local,
                                    prepared[static_cast<std::size_t>(k)], rays_resident, grouped);
            },
            done);
        for (int k = 0; k < count; ++k) {
            if (!ready[static_cast<std::size_t>(k)]) continue;
            PreparedCluster& p = prepared[static_cast<std::size_t>(k)];
            const Clock::time_point start = Clock::now();
            if (p.grouped)
                c.bouncer->queue_grouped(c.world, p.view, c.options.layers, c.thickness,
                                         static_cast<std::size_t>(first + k), c.options.cull_in_front, c.offset);
            else
                c.bouncer->queue(c.world, p.view, c.options.layers, c.thickness, p.culls, p.rays);
            stats.layer_build_ms += ms_since(start);
            if (!rays_resident) queued.push_back(std::move(p.rays.indices));  // else its hits come by ray index
        }
    }
    const Clock::time_point start = Clock::now();
    const std::vector<LayerBounceHit> hits = c.bouncer->finish(stats.layers);
    stats.layer_build_ms += ms_since(start);  // the layers, clipping and traces, waited for here
    if (rays_resident) {
        // One hit a ray of the batch, by index: those the layers traced are
        // shaded (the others were traced against the scene).
        const int chunks = static_cast<int>(std::min<std::size_t>(c.rays.size() / 4096 + 1, 1024));
        run_parallel_items(
            threads, chunks, [] { return SecondaryStats{}; },
            [&](SecondaryStats& local, int chunk) {
                const Clock::time_point shading_start = Clock::now();
                for (std::size_t r = c.rays.size() * std::size_t(chunk) / std::size_t(chunks);
                     r < c.rays.size() * std::size_t(chunk + 1) / std::size_t(chunks); ++r)
                    if (hits[r].traced) shade_hit(c, static_cast<std::uint32_t>(r), hits[r], radiance, local);
                local.shading_ms += ms_since(shading_start);
            },
            done);
        return;
    }
    // The hits in queue order.
    std::vector<std::size_t> first_hit(queued.size(), 0);
    for (std::size_t k = 1; k < queued.size(); ++k) first_hit[k] = first_hit[k - 1] + queued[k - 1].size();
    run_parallel_items(
        threads, static_cast<int>(queued.size()), [] { return SecondaryStats{}; },
        [&](SecondaryStats& local, int k) {
            const auto at = static_cast<std::size_t>(k);
            shade_cluster(c, queued[at], hits.data() + first_hit[at], radiance, local);
        },
        done);
}

void add_stats(SecondaryStats& into, const SecondaryStats& from) {
    into.rays_image_space += from.rays_image_space;
    into.rays_exact += from.rays_exact;
    into.rays_hit += from.rays_hit;
    into.trace_steps += from.trace_steps;
    into.clusters_refit_on_normal += from.clusters_refit_on_normal;
    into.clusters_split += from.clusters_split;
    into.clusters_unusable += from.clusters_unusable;
    into.layers.fragments += from.layers.fragments;
    into.layers.culled_near += from.layers.culled_near;
    into.layers.culled_in_front += from.layers.culled_in_front;
    into.layers.culled_normal += from.layers.culled_normal;
    into.layers.dropped += from.layers.dropped;
    into.layer_build_ms += from.layer_build_ms;
    into.clustering_ms += from.clustering_ms;
    into.views_ms += from.views_ms;
    into.shading_ms += from.shading_ms;
}

// Each ray's group key (ClusterBouncer::cluster): its reflector triangle,
// pixel and lens part; none where a pixel index does not fit its 28 bits.
std::vector<RayGroupKey> group_keys(const BounceContext& c) {
    std::vector<RayGroupKey> keys;
    const auto spp = static_cast<std::uint32_t>(c.spp);
    if (c.rays.empty() || c.rays.back().sample / spp >= (1u << 28)) return keys;  // rays in sample order
    keys.reserve(c.rays.size());
    for (const SecondaryRay& ray : c.rays) keys.push_back({ray.triangle, (ray.sample / spp) << 4u | ray.lens_part});
    return keys;
}

// Every ray's radiance by the options' bounce mode, in parallel over
// clusters (or rays); each ray's value is written by one thread only.
std::vector<glm::vec3> bounce_all(const BounceContext& c, int threads, SecondaryStats& stats) {
    std::vector<glm::vec3> radiance(c.rays.size(), glm::vec3(0.0f));
    std::mutex merge;
    auto done = [&](const SecondaryStats& local) {
        std::lock_guard<std::mutex> lock(merge);
        add_stats(stats, local);
    };
    if (c.options.bounces != SecondaryBounces::image_space) {
        const int chunks = static_cast<int>(std::min<std::size_t>(c.rays.size() / 256 + 1, 4096));
        run_parallel_items(
            threads, chunks, [] { return SecondaryStats{}; },
            [&](SecondaryStats& local, int chunk) {
                for (std::size_t r = c.rays.size() * std::size_t(chunk) / std::size_t(chunks);
                     r < c.rays.size() * std::size_t(chunk + 1) / std::size_t(chunks); ++r)
                    radiance[r] = c.options.bounces == SecondaryBounces::exact
                                      ? exact_radiance(c, c.rays[r], local)
                                      : environment_radiance(c.scene, c.rays[r].direction);
            },
            done);
        return radiance;
    }
    std::vector<glm::vec3> positions, directions;
    for (const SecondaryRay& ray : c.rays) {
        positions.push_back(ray.origin);
        directions.push_back(ray.direction);
    }
    ClusterOptions cluster_options;
    cluster_options.wanted_clusters = static_cast<std::uint32_t>(c.options.wanted_clusters);
    cluster_options.max_per_facet = static_cast<std::uint32_t>(c.options.clusters_per_facet);
    const Clock::time_point clustering_start = Clock::now();
    // Its classification and k-means assignments on the threads (the same clusters as on one).
    auto parallel_for = [threads](std::size_t count, const auto& body) {
        run_parallel_ranges(threads, count, 1, [&](std::size_t i, std::size_t) { body(i); });
    };
    std::optional<Clustering<float>> resident_clustering;
    ClusterViews<float> fitted;
    if (c.bouncer != nullptr)
        resident_clustering =
            c.bouncer->cluster(positions, directions, group_keys(c), cluster_options, c.tan_half_fov, c.min_near, fitted);
    Clustering<float> clustering =
        resident_clustering ? std::move(*resident_clustering)
                            : cluster_reflector_pixels<float>(positions, directions, cluster_options, parallel_for);
    stats.clustering_ms += ms_since(clustering_start);
    const int clusters = static_cast<int>(clustering.clusters.size());
    stats.clusters += clusters;
    // Each cluster's two views, in one pass over the rays (where the bouncer did not fit them).
    const Clock::time_point views_start = Clock::now();
    if (!resident_clustering)
        fitted = fit_cluster_views<float>(clustering, positions, directions, c.tan_half_fov, c.min_near, parallel_for);
    std::vector<K::VirtualView> views;
    for (std::size_t j = 0; j < clustering.clusters.size(); ++j) views.push_back(cluster_view(fitted, j, stats));
    stats.views_ms += ms_since(views_start);
    // Where the bouncer clustered them: each cluster's groups and culls
    // there too, for its view (timed among the bouncer's phases).
    bool grouped = false;
    if (resident_clustering) {
        std::vector<glm::vec3> forwards;
        for (const K::VirtualView& view : views) forwards.push_back(view.forward);
        grouped = c.bouncer->group(forwards, c.options.cull_normals, c.world.vertices.size());
    }
    // Each cluster's rays, on the host: all of them, or with the groups
    // made there only those of a cluster its view does not hold whole (the
    // rays' clusters then read back only for those).
    std::vector<std::vector<std::uint32_t>> members(clustering.clusters.size());
    std::vector<char> wanted(clustering.clusters.size(), 1);
    for (std::size_t j = 0; j < views.size(); ++j) wanted[j] = !grouped || views[j].flags != 0;
    if (std::find(wanted.begin(), wanted.end(), 1) != wanted.end()) {
        if (clustering.cluster_of.empty()) clustering.cluster_of = c.bouncer->cluster_of();
        if (clustering.cluster_of.size() != c.rays.size())
            throw std::logic_error("dof-secondary: the bouncer gave no cluster for each ray");
        for (std::size_t r = 0; r < c.rays.size(); ++r) {
            const auto j = static_cast<std::size_t>(clustering.cluster_of[r]);
            if (wanted[j]) members[j].push_back(static_cast<std::uint32_t>(r));
        }
    }
    if (c.bouncer != nullptr) {
        bounce_clusters_resident(c, views, members, resident_clustering.has_value(), grouped, radiance, threads, stats,
                                 done);
        return radiance;
    }
    run_parallel_items(
        threads, clusters, [] { return SecondaryStats{}; },
        [&](SecondaryStats& local, int j) {
            bounce_cluster(c, views[static_cast<std::size_t>(j)], members[static_cast<std::size_t>(j)], radiance, local);
        },
        done);
    return radiance;
}

// The rays of each shutter slice, in ray order: slice s holds the times in
// [s / slices, (s + 1) / slices), the last one 1 too.
std::vector<std::vector<std::uint32_t>> rays_by_time_slice(const std::vector<SecondaryRay>& rays, int slices) {
    std::vector<std::vector<std::uint32_t>> out(static_cast<std::size_t>(slices));
    for (std::size_t r = 0; r < rays.size(); ++r) {
        const float scaled = rays[r].time * float(slices);
        const int slice = scaled >= 0.0f ? std::min(slices - 1, static_cast<int>(scaled)) : 0;  // NaN: 0
        out[static_cast<std::size_t>(slice)].push_back(static_cast<std::uint32_t>(r));
    }
    return out;
}

}  // namespace

int bounce_time_slices(const Scene& scene, const SecondaryOptions& options) {
    if (options.bounces != SecondaryBounces::image_space) return 1;  // exact bounces take each ray's own time
    if (options.time_slices > 0) return options.time_slices;
    return scene_moves(scene) ? auto_time_slices_moving : 1;
}

std::vector<LayerBounceHit> bounce_in_layers(const kernelf::LayerView& view, const ClusterLayers& layers,
                                             float thickness, const ClusterRays& rays, const LayerTracer* tracer) {
    std::vector<K::LayerSegment> segments(rays.starts.size());
    std::size_t first = 0;
    for (std::uint32_t end : rays.group_ends) {
        clip_group(view, layers.pyramid, thickness, rays, first, end, segments.data());
        first = end;
    }
    const LayerImages& images = layers.images;
    const std::vector<K::LayerHit> traced =
        tracer != nullptr ? (*tracer)(view, images.depth, images.layers, thickness, segments)
                          : trace_layers_on_host(view, images.depth, images.layers, thickness, segments);
    std::vector<LayerBounceHit> hits(traced.size());
    for (std::size_t i = 0; i < traced.size(); ++i) {
        hits[i].hit = traced[i].hit;
        hits[i].steps = traced[i].steps;
        if (traced[i].hit) hits[i].triangle = hit_triangle(images, traced[i]);
    }
    return hits;
}

std::vector<kernelf::LayerHit> trace_layers_on_host(const kernelf::LayerView& view, const std::vector<float>& depth,
                                                    int layers, float thickness,
                                                    const std::vector<kernelf::LayerSegment>& segments) {
    const std::size_t plane = static_cast<std::size_t>(view.size) * static_cast<std::size_t>(view.size);
    std::vector<kernelf::LayerHit> hits(segments.size());
    for (std::size_t i = 0; i < segments.size(); ++i) {
        hits[i] = trace_layers<float>(view, segments[i], layers, thickness, [&](int l, int x, int y) {
            return depth[plane * static_cast<std::size_t>(l) + static_cast<std::size_t>(y) * view.size + x];
        });
    }
    return hits;
}

RenderResult render_dof_secondary(const Scene& scene, const RenderSettings& settings, const SecondaryOptions& options,
                                  SecondaryStats* stats_out, const LayerTracer* tracer, const PrimaryPass* primary_pass,
                                  const LayerBuilder* layer_builder, ClusterBouncer* bouncer) {
    validate_secondary_options(options);
    // The bounce resolves a hit with vertices linear over the shutter.
    if (!scene.position_at.empty())
        throw std::invalid_argument("dof-secondary: motion segments (K > 1) are not supported yet; use 1 segment");
    const Clock::time_point start = Clock::now();
    std::vector<std::uint32_t> ids;
    RenderSettings primary_settings = settings;
    primary_settings.method = RenderMethod::stochastic;
    RenderResult result = primary_pass != nullptr ? (*primary_pass)(primary_settings, ids)
                                                  : render_cpu(scene, primary_settings, CpuOptions{}, &ids);
    if (ids.size() != static_cast<std::size_t>(settings.width) * settings.height * settings.spp)
        throw std::invalid_argument("dof-secondary: the primary pass returned no sample ids");
    const CameraModel model(scene.camera, settings.width, settings.height);

    Clock::time_point phase = Clock::now();
    // The bouncer runs the image-space bounce only (exact and environment
    // bounces stay on the host); it may resolve the samples too.
    ClusterBouncer* const resident = options.bounces == SecondaryBounces::image_space ? bouncer : nullptr;
    std::optional<PrimaryResolve> resolved;
    if (resident != nullptr) resolved = resident->resolve(scene, model, settings, ids, options.lens_parts);
    PrimaryResolve primary =
        resolved ? std::move(*resolved) : resolve_primary(scene, model, settings, ids, options.lens_parts);
    const WorldTriangles world = world_triangles(scene, 0.5f);
    const std::vector<glm::vec3> colours = shade_all(scene);
    result.stats.ms_per_phase.emplace_back("resolve", ms_since(phase));

    phase = Clock::now();
    const float diagonal = std::max(world.diagonal(), 1e-6f);
    const bool moving = scene_moves(scene);
    const float tan_half_fov = std::tan(0.5f * options.fov_degrees * 3.14159265358979f / 180.0f);
    auto context_for = [&](const std::vector<SecondaryRay>& rays, const WorldTriangles& at) {
        return BounceContext{scene, options, rays, at, moving, colours, tan_half_fov, 1e-3f * diagonal,
                             options.thickness_fraction * diagonal, 1e-4f * diagonal, settings.spp, tracer,
                             layer_builder, resident};
    };
    SecondaryStats stats;
    stats.reflector_samples = primary.reflector_samples;
    stats.rays = primary.rays.size();
    stats.time_slices = bounce_time_slices(scene, options);
    // A LayerTracer or LayerBuilder makes GL calls inside each cluster's
    // work, so one thread; a ClusterBouncer's calls stay on this thread while
    // the host's steps around them run on all.
    const int threads = tracer != nullptr || layer_builder != nullptr ? 1 : render_threads(settings);
    std::vector<glm::vec3> radiance;
    if (stats.time_slices == 1) {
        radiance = bounce_all(context_for(primary.rays, world), threads, stats);
    } else {
        // Each slice of the shutter: its rays, clustered and bounced in the
        // scene at the slice's middle.
        radiance.assign(primary.rays.size(), glm::vec3(0.0f));
        const std::vector<std::vector<std::uint32_t>> slices = rays_by_time_slice(primary.rays, stats.time_slices);
        for (std::size_t slice = 0; slice < slices.size(); ++slice) {
            if (slices[slice].empty()) continue;
            std::vector<SecondaryRay> rays;
            rays.reserve(slices[slice].size());
            for (std::uint32_t r : slices[slice]) rays.push_back(primary.rays[r]);
            const WorldTriangles at =
                world_triangles(scene, (float(slice) + 0.5f) / float(stats.time_slices));
            const std::vector<glm::vec3> seen = bounce_all(context_for(rays, at), threads, stats);
            for (std::size_t i = 0; i < rays.size(); ++i) radiance[slices[slice][i]] = seen[i];
        }
    }
    for (std::size_t r = 0; r < primary.rays.size(); ++r)
        primary.sample_colour[primary.rays[r].sample] += primary.rays[r].weight * radiance[r];
    result.stats.ms_per_phase.emplace_back("bounce", ms_since(phase));
    // Its host steps (SecondaryStats), then the bouncer's own.
    if (options.bounces == SecondaryBounces::image_space) {
        result.stats.ms_per_phase.emplace_back("wall_bounce_clustering", stats.clustering_ms);
        result.stats.ms_per_phase.emplace_back("wall_bounce_views", stats.views_ms);
        result.stats.ms_per_phase.emplace_back("wall_bounce_shading", stats.shading_ms);
    }
    if (resident != nullptr) resident->add_phases(result.stats);
    result.image = resolve_samples(primary.sample_colour, settings.width, settings.height, settings.spp);
    result.stats.ms_total = ms_since(start);
    if (options.time_slices > 1 && options.bounces != SecondaryBounces::image_space) {
        result.warnings.push_back("dof-secondary: " + std::to_string(options.time_slices) +
                                  " time slices asked for, not used: the " +
                                  (options.bounces == SecondaryBounces::exact ? "exact bounce sees each ray's own time"
                                                                              : "environment bounce sees no scene"));
    }
    if (stats.clusters_split + stats.clusters_unusable > 0) {
        result.warnings.push_back("dof-secondary: " + std::to_string(stats.clusters_split + stats.clusters_unusable) +
                                  " clusters had rays no virtual view of this field of view holds; their " +
                                  std::to_string(stats.rays_exact) + " rays were traced against the scene");
    }
    // Added to the primary pass's statistics, whose counters (samples_occluded) stay.
    RenderStats bounce;
    bounce.secondary_rays = stats.rays;
    bounce.counters = {{"reflector_samples", double(stats.reflector_samples)},
                       {"secondary_rays", double(stats.rays)},
                       {"rays_image_space", double(stats.rays_image_space)},
                       {"rays_exact", double(stats.rays_exact)},
                       {"rays_hit", double(stats.rays_hit)},
                       {"trace_steps", double(stats.trace_steps)},
                       {"clusters", double(stats.clusters)},
                       {"bounce_time_slices", double(stats.time_slices)},
                       {"clusters_refit_on_normal", double(stats.clusters_refit_on_normal)},
                       {"clusters_split", double(stats.clusters_split)},
                       {"clusters_unusable", double(stats.clusters_unusable)},
                       {"layer_fragments", double(stats.layers.fragments)},
                       {"culled_near_triangles", double(stats.layers.culled_near)},
                       {"culled_in_front_fragments", double(stats.layers.culled_in_front)},
                       {"culled_normal_triangles", double(stats.layers.culled_normal)},
                       {"dropped_fragments", double(stats.layers.dropped)},
                       {"layer_build_ms", stats.layer_build_ms}};
    result.stats.add(bounce);
    if (stats_out != nullptr) *stats_out = stats;
    return result;
}

}  // namespace blurcull::frontend
