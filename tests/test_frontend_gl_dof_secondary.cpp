// dof-secondary's GL build against its CPU build on small scenes (the
// mirror sphere and the plane mirror of dof_secondary_scenes.hpp).
//
// 1. Host layers, GL primary samples and GL trace pass: the CPU build's
//    image. Stated tolerance: every channel of every pixel within 1e-6 (both
//    run the kernel's text in float, llvmpipe rounding like the host;
//    measured: identical).
// 2. GL layers (render/gl/gl_layer_images.hpp) against the host's layers of
//    the same cluster views, every cluster of both scenes, by both scans:
//    the GL rasterizer decides which texel centres a triangle covers (8
//    subpixel bits), or the compute scan by the host's own test; the depth
//    there is the host's formula (layer_raster_shared.h). Asserted:
//    a triangle stored at a texel by both has the same depth bit for bit
//    but where the two rasterizers gave the texel centre to different
//    triangles of a near-clipped triangle's fan (within 1/64 texel of their
//    diagonal; at most 1 in 10^5 entries, relative difference <= 1e-5:
//    measured 1 of 896336, on the mirror sphere); one stored by only one of
//    them has the texel centre within 1/64 texel
//    of an edge of its image triangles (the coverage rules differ on edges
//    only), and such entries are at most 3 in 10^4 of the fragments (measured
//    0.3 and 0.8 in 10^4); the
//    counts of culled triangles are equal; the GL pyramid is the host's
//    DepthPyramid of the GL layers bit for bit. Also with 1 layer on the
//    sphere (full lists): the dropped counts differ by at most the edge
//    entries, and an entry behind the other build's full list is excused.
//    The compute scan on an IEEE-exact GL: no entry in one build only, no
//    depth differs, the same dropped count.
// 3. The whole GL build (GL layers) against the CPU build: RMSE below 0.002
//    and at most 0.5 % of the pixels off by more than 0.05. Why: the images
//    can differ only where a ray's trace reads an edge texel that one
//    rasterizer covered and the other did not (a few in 10^4 of the
//    fragments; measured: identical images), which changes that ray's hit; a 48 x 36 image at 8 spp has
//    13824 samples, so a handful of changed rays, each 1/8 of its pixel.
//
// 4. The GPU-resident bounce (clipping, traces and surfaces on the GPU)
//    against the host's on the same GL layers: the same hits per ray (the
//    test case below says how exactly).
// 4b. The rays clustered, the views fitted and each cluster's rays and
//    origins gathered on the GPU against the host's clusters, views and
//    uploaded rays: the same culls and image.
// 5. The primary pass and the layers on the compute pipeline: the fragment
//    pipeline's image.
// 6. More rays than one row of work groups (over 4.19 million).
//
// No GL context (no Mesa): fails when CI=true, else skips with a message.
#include "gl_parity_helpers.hpp"

#include "app/gl_dof_secondary.hpp"
#include "dof_secondary_scenes.hpp"
#include "render/common/layer_raster_shared.h"
#include "render/cpu/cpu_backend.hpp"
#include "render/secondary/secondary_rays.hpp"
#include "scene/builtin/secondary_scenes.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;
using blurcull::kernelf;

namespace {

// The image triangles (x, y, depth) of scene triangle t in `view`, clipped
// at the near plane as both builds do.
std::vector<std::array<glm::vec3, 3>> image_triangles(const kernelf::LayerView& view,
                                                      const std::array<glm::vec3, 3>& triangle) {
    std::vector<std::array<glm::vec3, 3>> out;
    std::array<glm::vec3, 4> clipped{};
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 a = layer_raster::bc_raster_view_point(view, triangle[static_cast<std::size_t>(i)]);
        const glm::vec3 b = layer_raster::bc_raster_view_point(view, triangle[static_cast<std::size_t>((i + 1) % 3)]);
        if (a.z >= view.near) clipped[static_cast<std::size_t>(count++)] = a;
        if ((a.z >= view.near) != (b.z >= view.near))
            clipped[static_cast<std::size_t>(count++)] = layer_raster::bc_raster_near_crossing(a, b, view.near);
    }
    for (int k = 1; k + 1 < count; ++k)
        out.push_back({layer_raster::bc_raster_image_point(view, clipped[0]),
                       layer_raster::bc_raster_image_point(view, clipped[static_cast<std::size_t>(k)]),
                       layer_raster::bc_raster_image_point(view, clipped[static_cast<std::size_t>(k + 1)])});
    return out;
}

double distance_to_segment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a;
    const double t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-300), 0.0, 1.0);
    return glm::length(p - (a + t * ab));
}

// The distance in texels from the centre of texel (x, y) to the nearest edge
// of the triangle's image triangles.
double edge_distance(const kernelf::LayerView& view, const std::array<glm::vec3, 3>& triangle, int x, int y) {
    const glm::dvec2 centre(x + 0.5, y + 0.5);
    double best = 1e300;
    for (const auto& t : image_triangles(view, triangle))
        for (int k = 0; k < 3; ++k)
            best = std::min(best, distance_to_segment(centre, glm::dvec2(t[static_cast<std::size_t>(k)]),
                                                      glm::dvec2(t[static_cast<std::size_t>((k + 1) % 3)])));
    return best;
}

struct LayerAgreement {
    std::uint64_t clusters = 0, host_fragments = 0, gl_fragments = 0;
    std::uint64_t entries_both = 0, depth_differs = 0, only_one = 0;
    double worst_edge_distance = 0;  // texels, of an entry in one build only
    double worst_depth_edge_distance = 0, worst_depth_relative = 0;  // of an entry in both whose depths differ
    std::uint64_t pyramid_cells = 0, pyramid_differs = 0;
    std::uint64_t cull_counts_differ = 0;
    std::uint64_t dropped_by_other = 0;           // in one list only, behind the other's full list
    std::uint64_t host_dropped = 0, gl_dropped = 0;  // fragments beyond the last layer
};

void compare_layers(const WorldTriangles& world, const kernelf::LayerView& view, const ClusterLayers& host,
                    const LayerStats& host_stats, const ClusterLayers& gpu, const LayerStats& gl_stats,
                    LayerAgreement& a) {
    ++a.clusters;
    a.host_fragments += host_stats.fragments;
    a.gl_fragments += gl_stats.fragments;
    a.host_dropped += host_stats.dropped;
    a.gl_dropped += gl_stats.dropped;
    if (host_stats.culled_near != gl_stats.culled_near || host_stats.culled_normal != gl_stats.culled_normal)
        ++a.cull_counts_differ;
    const LayerImages& h = host.images;
    const LayerImages& g = gpu.images;
    REQUIRE(h.size == g.size);
    REQUIRE(h.layers == g.layers);
    for (int y = 0; y < h.size; ++y) {
        for (int x = 0; x < h.size; ++x) {
            auto entries = [&](const LayerImages& im) {
                std::vector<std::pair<std::uint32_t, float>> list;
                for (int l = 0; l < im.layers; ++l) {
                    const float d = im.depth[im.index(l, x, y)];
                    if (std::isinf(d)) break;
                    list.emplace_back(im.triangle[im.index(l, x, y)], d);
                }
                return list;
            };
            const auto hl = entries(h), gll = entries(g);
            // An entry in one list only: an edge texel of its triangle, or
            // one the other build dropped behind its full list.
            auto in_one_only = [&](std::uint32_t id, float depth, const std::vector<std::pair<std::uint32_t, float>>& other) {
                if (static_cast<int>(other.size()) == h.layers && depth >= other.back().second) {
                    ++a.dropped_by_other;
                    return;
                }
                ++a.only_one;
                a.worst_edge_distance = std::max(a.worst_edge_distance, edge_distance(view, world.vertices[id], x, y));
            };
            for (const auto& [id, depth] : hl) {
                const auto found = std::find_if(gll.begin(), gll.end(), [&](const auto& e) { return e.first == id; });
                if (found == gll.end()) {
                    in_one_only(id, depth, gll);
                    continue;
                }
                ++a.entries_both;
                if (std::memcmp(&found->second, &depth, sizeof depth) != 0) {
                    // Only where the two rasterizers gave the texel to different
                    // triangles of a clipped triangle's fan (their diagonal).
                    ++a.depth_differs;
                    a.worst_depth_edge_distance =
                        std::max(a.worst_depth_edge_distance, edge_distance(view, world.vertices[id], x, y));
                    a.worst_depth_relative = std::max(a.worst_depth_relative,
                                                      std::abs(double(found->second) - double(depth)) / double(depth));
                }
            }
            for (const auto& [id, depth] : gll) {
                if (std::find_if(hl.begin(), hl.end(), [&](const auto& e) { return e.first == id; }) != hl.end()) continue;
                in_one_only(id, depth, hl);
            }
        }
    }
    // The GL pyramid against the host's pyramid of the same (GL) layers.
    const DepthPyramid reference(g);
    const auto& want = reference.levels();
    const auto& got = gpu.pyramid.levels();
    REQUIRE(want.size() == got.size());
    for (std::size_t level = 0; level < want.size(); ++level) {
        REQUIRE(want[level].size == got[level].size);
        for (std::size_t cell = 0; cell < want[level].lo.size(); ++cell) {
            ++a.pyramid_cells;
            if (std::memcmp(&want[level].lo[cell], &got[level].lo[cell], sizeof(float)) != 0 ||
                std::memcmp(&want[level].hi[cell], &got[level].hi[cell], sizeof(float)) != 0)
                ++a.pyramid_differs;
        }
    }
}

// The scenes of the whole-render comparisons: a mirror sphere, a plane
// mirror, and quads moving in a plane mirror, bounced in 4 shutter slices
// (auto; the bouncer's triangles uploaded again for each).
std::vector<Scene> bounce_scenes() {
    return {mirror_sphere_scene(), plane_mirror_scene(0.1f), plane_mirror_scene(0.05f, {1.5f, 0.0f, 0.0f})};
}

}  // namespace

TEST_CASE("dof-secondary: the GL build with host layers gives the CPU build's image") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    GlRenderer rasterizer;
    const GlDofSecondary passes(rasterizer, *context);
    const RenderSettings settings = quiet_settings(48, 36, 8);
    for (const Scene& scene : bounce_scenes()) {
        CAPTURE(scene.name);
        SecondaryStats cpu_stats, gl_stats;
        const Image cpu = render_dof_secondary(scene, settings, small_options(), &cpu_stats).image;
        const Image gpu = passes.render(scene, settings, {}, small_options(), &gl_stats, LayerImagesOn::host).image;
        const ImageError e = compare(cpu, gpu);
        MESSAGE("GL (host layers) against CPU build: max difference " << e.max_abs);
        CHECK(e.max_abs <= 1e-6);
        CHECK(gl_stats.rays == cpu_stats.rays);
        CHECK(gl_stats.trace_steps == cpu_stats.trace_steps);
        CHECK(gl_stats.rays_hit == cpu_stats.rays_hit);
        CHECK(gl_stats.rays_image_space > 0);
    }
}

namespace {

// The scenes and options the per-cluster comparisons run: the mirror sphere
// and the plane mirror with the defaults, the sphere with one layer (full
// lists, so the cascade drops fragments), and the plane mirror's quads
// moving (4 time slices: a batch of clusters per slice).
std::vector<std::pair<Scene, SecondaryOptions>> layer_cases() {
    SecondaryOptions one_layer = small_options();
    one_layer.layers = 1;
    return {{mirror_sphere_scene(), small_options()},
            {plane_mirror_scene(0.1f), small_options()},
            {mirror_sphere_scene(), one_layer},
            {plane_mirror_scene(0.05f, {1.5f, 0.0f, 0.0f}), small_options()}};  // moving: 4 time slices
}

}  // namespace

TEST_CASE("dof-secondary: GL layers and pyramid against the host's, every cluster") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    const bool exact = !probe_arithmetic(*context).tolerant();
    GlRenderer rasterizer;
    const GlDofSecondary passes(rasterizer, *context);
    const RenderSettings settings = quiet_settings(48, 36, 8);
    for (const GlLayerRaster raster : {GlLayerRaster::graphics, GlLayerRaster::compute})
    for (const auto& [scene, options] : layer_cases()) {
        const std::string raster_name = raster == GlLayerRaster::compute ? "compute" : "graphics";
        CAPTURE(raster_name);
        CAPTURE(scene.name);
        CAPTURE(options.layers);
        const LayerBuilder gl_builder = passes.layer_builder(raster);
        LayerAgreement agreement;
        const LayerBuilder both = [&](const WorldTriangles& world, const kernelf::LayerView& view, int layers,
                                      const ClusterCulls& culls, LayerStats& stats) {
            LayerStats host_stats, gl_stats;
            const ClusterLayers host = build_cluster_layers_on_host(world, view, layers, culls, host_stats);
            ClusterLayers gpu = gl_builder(world, view, layers, culls, gl_stats);
            compare_layers(world, view, host, host_stats, gpu, gl_stats, agreement);
            stats.fragments += gl_stats.fragments;
            return gpu;
        };
        const PrimaryPass primary = passes.primary_pass(scene, {});
        const LayerTracer tracer = passes.layer_tracer();
        SecondaryStats stats;
        render_dof_secondary(scene, settings, options, &stats, &tracer, &primary, &both);
        MESSAGE(scene.name << ", " << raster_name << ": " << agreement.clusters << " clusters, fragments host "
                           << agreement.host_fragments
                           << " gl " << agreement.gl_fragments << "; entries in both " << agreement.entries_both
                           << " (depth differs " << agreement.depth_differs << ", at edge distance "
                           << agreement.worst_depth_edge_distance << ", relative " << agreement.worst_depth_relative
                           << "), in one only " << agreement.only_one
                           << " (worst edge distance " << agreement.worst_edge_distance << " texel); pyramid cells "
                           << agreement.pyramid_cells << " (differ " << agreement.pyramid_differs << "); dropped host "
                           << agreement.host_dropped << " gl " << agreement.gl_dropped << ", behind a full list "
                           << agreement.dropped_by_other);
        CHECK(agreement.clusters == static_cast<std::uint64_t>(stats.clusters));
        CHECK(agreement.clusters > 0);
        CHECK(agreement.entries_both > 10000);
        CHECK(double(agreement.depth_differs) <= 1e-5 * double(agreement.entries_both));
        CHECK(agreement.worst_depth_edge_distance <= 1.0 / 64.0);
        CHECK(agreement.worst_depth_relative <= 1e-5);
        CHECK(agreement.worst_edge_distance <= 1.0 / 64.0);
        // Entries in one build only are texel centres within rounding of an
        // edge (checked above). Measured 3.4e-4 of the fragments on the plane
        // mirror (large quads, sobol samples), 4e-5 on the sphere; a rule that
        // differs systematically (top-left on the wrong edges) would put a
        // whole edge's texels in one build, of the order of 1e-2 here.
        CHECK(double(agreement.only_one) <= 1e-3 * double(agreement.host_fragments));
        CHECK(agreement.cull_counts_differ == 0);
        CHECK(agreement.pyramid_cells > 0);
        CHECK(agreement.pyramid_differs == 0);
        // Each edge entry one build has and the other lacks moves at most one
        // depth across a full list's end.
        CHECK(agreement.dropped_by_other <= agreement.only_one);
        const double dropped_gap = std::abs(double(agreement.host_dropped) - double(agreement.gl_dropped));
        CHECK(dropped_gap <= double(agreement.only_one));
        if (options.layers == 1) CHECK(agreement.host_dropped > 1000);
        // The compute scan runs the host's coverage test on the image points:
        // with the host's arithmetic, the host's entries exactly.
        if (raster == GlLayerRaster::compute && exact) {
            CHECK(agreement.only_one == 0);
            CHECK(agreement.depth_differs == 0);
            CHECK(agreement.gl_dropped == agreement.host_dropped);
        }
    }
}

TEST_CASE("dof-secondary: the GL build with GL layers against the CPU build") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    const bool exact = !probe_arithmetic(*context).tolerant();
    GlRenderer rasterizer;
    const GlDofSecondary passes(rasterizer, *context);
    const RenderSettings settings = quiet_settings(48, 36, 8);
    for (const Scene& scene : bounce_scenes()) {
        CAPTURE(scene.name);
        SecondaryStats cpu_stats, gl_stats;
        const Image cpu = render_dof_secondary(scene, settings, small_options(), &cpu_stats).image;
        const RenderResult rendered = passes.render(scene, settings, {}, small_options(), &gl_stats, LayerImagesOn::gl);
        const Image& gpu = rendered.image;
        // The bouncer's phases: the host's clock always, the GPU's on hardware GL.
        auto phase = [&](const std::string& name) {
            for (const auto& [key, ms] : rendered.stats.ms_per_phase)
                if (key == name) return ms;
            return -1.0;
        };
        CHECK(phase("wall_bounce_layers") > 0.0);
        CHECK(phase("wall_bounce_trace") > 0.0);
        CHECK((phase("gpu_bounce_layers") >= 0.0) == !context->software());
        CHECK((phase("gpu_bounce_trace") >= 0.0) == !context->software());
        const ImageError e = compare(cpu, gpu);
        MESSAGE("GL (GL layers) against CPU build: RMSE " << e.rmse << ", max " << e.max_abs << ", pixels off "
                                                          << e.pixels_off << "; trace steps " << gl_stats.trace_steps
                                                          << " vs " << cpu_stats.trace_steps);
        CHECK(e.rmse < 0.002);
        CHECK(e.pixels_off <= static_cast<int>(0.005 * 48 * 36));
        CHECK(gl_stats.rays == cpu_stats.rays);
        CHECK(gl_stats.rays_image_space > 0);
        CHECK(gl_stats.time_slices == bounce_time_slices(scene, small_options()));
        CHECK(gl_stats.clusters == cpu_stats.clusters);
        CHECK(gl_stats.layers.culled_normal == cpu_stats.layers.culled_normal);
        CHECK(gl_stats.layers.culled_near == cpu_stats.layers.culled_near);
        // --layer-images gl-readback: the same GL layers, bounced on the
        // host; the same hits (test 4), so on an IEEE-exact GL the same
        // image, elsewhere within this test's tolerance.
        SecondaryStats readback_stats;
        const Image readback =
            passes.render(scene, settings, {}, small_options(), &readback_stats, LayerImagesOn::gl_readback).image;
        const ImageError r = compare(gpu, readback);
        MESSAGE("GL layers, resident against read back: RMSE " << r.rmse << ", max " << r.max_abs);
        if (exact) {
            CHECK(readback_stats.trace_steps == gl_stats.trace_steps);
            CHECK(r.max_abs == 0.0);
        } else {
            CHECK(r.rmse < 0.002);
        }
    }
}

namespace {

// The GPU-resident bounce (GlDofSecondary::cluster_bouncer) beside the
// host's bounce_in_layers on the same cluster's GL layers read back (by a
// builder of their own, so the resident batch's buffers and counts are left
// alone): per ray, the same hit, trace steps and surface, every cluster's
// hits in the order queued.
struct ResidentAgainstHost final : ClusterBouncer {
    ClusterBouncer& resident;
    const LayerBuilder& read_back;
    std::vector<LayerBounceHit> host;  // the batch's hits on the host, in the order queued
    std::uint64_t host_fragments = 0;
    std::uint64_t rays = 0, hits = 0, hit_differs = 0, steps_differ = 0, surface_differs = 0;
    ResidentAgainstHost(ClusterBouncer& r, const LayerBuilder& b) : resident(r), read_back(b) {}
    void begin(const WorldTriangles& triangles, std::size_t max_rays) override {
        resident.begin(triangles, max_rays);
        host.clear();
        host_fragments = 0;
    }
    void queue(const WorldTriangles& triangles, const kernelf::LayerView& view, int layers, float thickness,
               const ClusterCulls& culls, const ClusterRays& cluster_rays) override {
        LayerStats host_stats;
        const ClusterLayers built = read_back(triangles, view, layers, culls, host_stats);
        const std::vector<LayerBounceHit> cluster = bounce_in_layers(view, built, thickness, cluster_rays);
        host.insert(host.end(), cluster.begin(), cluster.end());
        host_fragments += host_stats.fragments;
        resident.queue(triangles, view, layers, thickness, culls, cluster_rays);
    }
    std::vector<LayerBounceHit> finish(LayerStats& stats) override {
        const std::uint64_t fragments_before = stats.fragments;
        std::vector<LayerBounceHit> got = resident.finish(stats);
        REQUIRE(got.size() == host.size());
        for (std::size_t i = 0; i < got.size(); ++i) {
            ++rays;
            hits += host[i].hit ? 1 : 0;
            hit_differs += got[i].hit != host[i].hit ? 1 : 0;
            steps_differ += got[i].steps != host[i].steps ? 1 : 0;
            surface_differs += got[i].hit && host[i].hit && got[i].triangle != host[i].triangle ? 1 : 0;
        }
        CHECK(stats.fragments - fragments_before == host_fragments);  // the same layers, counted over the batch
        return got;
    }
};

}  // namespace

// 4. The GPU-resident bounce: the groups' interval clipping, the traces and
//    the hits' surfaces on the GPU (render_secondary_clip.comp and the trace
//    pass, on the layers where GlLayerBuilder left them) against the host's
//    clipping, trace and surface choice on the same GL layers read back.
//    Both run the kernel's and bounce_shared.h's text: on an IEEE-exact GL
//    (llvmpipe) every ray's hit, steps and surface are equal (asserted 0
//    differences). On a GPU outside that model a segment end may round
//    differently and move a step; asserted there: at most 1 in 1000 rays
//    differ in anything.
TEST_CASE("dof-secondary: the GPU-resident bounce gives the host's hits on the same layers") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    const ArithmeticProbe probe = probe_arithmetic(*context);
    MESSAGE("GL arithmetic: " << probe.describe());
    GlRenderer rasterizer;
    const GlDofSecondary passes(rasterizer, *context), read_back_passes(rasterizer, *context);
    const LayerBuilder read_back = read_back_passes.layer_builder();
    const RenderSettings settings = quiet_settings(48, 36, 8);
    for (const auto& [scene, options] : layer_cases()) {
        CAPTURE(scene.name);
        CAPTURE(options.layers);
        const std::unique_ptr<ClusterBouncer> resident = passes.cluster_bouncer();
        ResidentAgainstHost both(*resident, read_back);
        const PrimaryPass primary = passes.primary_pass(scene, {});
        SecondaryStats stats;
        render_dof_secondary(scene, settings, options, &stats, nullptr, &primary, nullptr, &both);
        MESSAGE(scene.name << ", " << options.layers << " layers: " << both.rays << " rays, " << both.hits
                           << " hits; differ: hit " << both.hit_differs << ", steps " << both.steps_differ
                           << ", surface " << both.surface_differs);
        CHECK(both.rays == stats.rays_image_space);
        CHECK(both.rays > 1000);
        CHECK(both.hits > 100);
        const std::uint64_t differ = both.hit_differs + both.steps_differ + both.surface_differs;
        if (probe.tolerant())
            CHECK(double(differ) <= 1e-3 * double(both.rays));
        else
            CHECK(differ == 0);
    }
}

// 4b. The rays clustered and the views fitted in compute passes
//    (GlClustering, what the bouncer does by default), then each cluster's
//    rays and its in-front cull's origins gathered there by index
//    (queue_bounce_gathered, GlLayerInput::origin_points), and each
//    cluster's groups, own triangles and normal cone made there
//    (GlClustering::group), against the host's clustering, views, groups
//    and culls and the rays uploaded, the rest alike; with a field of view
//    that splits clusters too (their rays outside traced against the scene,
//    the rest prepared on the host, their clusters read back). The
//    clustering is minima, maxima and exact sums, so on an
//    IEEE-exact GL the same clusters (tests/test_frontend_gl_secondary_parity.cpp
//    asserts it cluster by cluster), hence the same trace steps and image
//    bit for bit; elsewhere within test 3's tolerance.
TEST_CASE("dof-secondary: the rays clustered on the GPU give the host clustering's image") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    const bool exact = !probe_arithmetic(*context).tolerant();
    GlRenderer rasterizer;
    const GlDofSecondary passes(rasterizer, *context);
    const RenderSettings settings = quiet_settings(48, 36, 8);
    std::uint64_t in_front_culls = 0, normal_culls = 0, split = 0;  // the culls and the split: exercised
    SecondaryOptions narrow = small_options();
    narrow.fov_degrees = 60.0f;  // under 74.76 degrees: some clusters split
    for (const Scene& scene : bounce_scenes())
    for (const SecondaryOptions& options : {small_options(), narrow}) {
        CAPTURE(scene.name);
        CAPTURE(options.fov_degrees);
        const PrimaryPass primary = passes.primary_pass(scene, {});
        auto render_with = [&](GlDofSecondary::ClustersOn on, SecondaryStats& stats) {
            const std::unique_ptr<ClusterBouncer> bouncer = passes.cluster_bouncer(GlLayerRaster::graphics, on);
            return render_dof_secondary(scene, settings, options, &stats, nullptr, &primary, nullptr, bouncer.get());
        };
        SecondaryStats gpu_stats, host_stats;
        const RenderResult gpu = render_with(GlDofSecondary::ClustersOn::gl, gpu_stats);
        const RenderResult host = render_with(GlDofSecondary::ClustersOn::host, host_stats);
        bool timed = false;
        for (const auto& [key, ms] : gpu.stats.ms_per_phase) timed = timed || (key == "wall_bounce_gpu_clustering" && ms > 0.0);
        CHECK(timed);
        const ImageError e = compare(host.image, gpu.image);
        MESSAGE(scene.name << ": " << gpu_stats.clusters << " clusters on the GPU, " << host_stats.clusters
                           << " on the host; trace steps " << gpu_stats.trace_steps << " vs " << host_stats.trace_steps
                           << "; image RMSE " << e.rmse << ", max " << e.max_abs);
        CHECK(gpu_stats.rays == host_stats.rays);
        CHECK(gpu_stats.clusters > 0);
        in_front_culls += host_stats.layers.culled_in_front;
        normal_culls += host_stats.layers.culled_normal;
        split += host_stats.clusters_split;
        if (exact) {
            CHECK(gpu_stats.clusters == host_stats.clusters);
            CHECK(gpu_stats.clusters_split == host_stats.clusters_split);
            CHECK(gpu_stats.rays_exact == host_stats.rays_exact);
            CHECK(gpu_stats.rays_hit == host_stats.rays_hit);
            CHECK(gpu_stats.trace_steps == host_stats.trace_steps);
            CHECK(gpu_stats.layers.culled_in_front == host_stats.layers.culled_in_front);
            CHECK(gpu_stats.layers.culled_normal == host_stats.layers.culled_normal);
            CHECK(gpu_stats.layers.fragments == host_stats.layers.fragments);
            CHECK(e.max_abs == 0.0);
        } else {
            CHECK(e.rmse < 0.002);
        }
    }
    CHECK(in_front_culls > 0);
    CHECK(normal_culls > 0);
    CHECK(split > 0);
}

// 5. The primary pass on the compute pipeline (GlOptions::pipeline compute,
//    `--gl-pipeline compute`, what --backend auto picks on a hardware GPU),
//    which also scans the layers in compute (GlLayerRaster::compute): the
//    compute pipeline keeps the fragment pipeline's winner per sample
//    (tests/test_frontend_gl_compute.cpp) and the compute scan the GL
//    rasterizer's layers (test 2), so the bounced rays, and the image, are
//    the same: on an IEEE-exact GL bit for bit (asserted max 0); elsewhere
//    within test 3's tolerance.
TEST_CASE("dof-secondary: the compute pipeline (primary pass and layers) gives the fragment pipeline's image") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    const ArithmeticProbe probe = probe_arithmetic(*context);
    GlRenderer rasterizer;
    const GlDofSecondary passes(rasterizer, *context);
    const RenderSettings settings = quiet_settings(48, 36, 8);
    GlOptions compute;
    compute.pipeline = GlPipeline::compute;
    for (const Scene& scene : {mirror_sphere_scene(), plane_mirror_scene(0.1f)}) {
        CAPTURE(scene.name);
        SecondaryStats fragment_stats, compute_stats;
        const RenderResult fragment = passes.render(scene, settings, {}, small_options(), &fragment_stats);
        const RenderResult on_compute = passes.render(scene, settings, compute, small_options(), &compute_stats);
        const ImageError e = compare(fragment.image, on_compute.image);
        MESSAGE(scene.name << ": compute against fragment primary pass: RMSE " << e.rmse << ", max " << e.max_abs
                           << "; rays " << compute_stats.rays << " vs " << fragment_stats.rays);
        CHECK(compute_stats.rays > 0);
        if (probe.tolerant()) {
            CHECK(e.rmse < 0.002);
            CHECK(e.pixels_off <= static_cast<int>(0.005 * 48 * 36));
        } else {
            CHECK(compute_stats.rays == fragment_stats.rays);
            CHECK(compute_stats.trace_steps == fragment_stats.trace_steps);
            CHECK(e.max_abs == 0.0);
        }
    }
}

// 6. More rays than one row of work groups: the clip and trace passes
//    dispatch rows of at most 65,535 groups of 64 (dispatch_items), so a
//    cluster of over 4.19 million rays (the JCST water at 800x600, 100 spp,
//    has some) runs in a second row. 4,194,340 segments through the trace
//    pass, all empty (quick) but the last 100, which pass through a layer
//    and must hit as on the host.
TEST_CASE("dof-secondary: the trace pass takes more rays than one row of work groups") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    GlRenderer rasterizer;
    const GlDofSecondary passes(rasterizer, *context);
    const LayerTracer tracer = passes.layer_tracer();
    kernelf::LayerView view;
    view.eye = glm::vec3(0.0f);
    view.forward = glm::vec3(0.0f, 0.0f, 1.0f);
    view.right = glm::vec3(1.0f, 0.0f, 0.0f);
    view.up = glm::vec3(0.0f, 1.0f, 0.0f);
    view.tan_half_fov = 1.0f;
    view.near = 0.1f;
    view.far = 100.0f;
    view.size = 8;
    const std::vector<float> depth(64, 5.0f);  // one layer: a plane at depth 5
    const std::size_t count = 65535u * 64u + 100u;
    kernelf::LayerSegment empty{};
    empty.empty = true;
    std::vector<kernelf::LayerSegment> segments(count, empty);
    for (std::size_t i = count - 100; i < count; ++i) {
        const float x = -0.5f + 0.01f * static_cast<float>(i - (count - 100));
        segments[i] = kernelf::layer_segment(view, glm::vec3(x, 0.2f, 1.0f), glm::vec3(0.0f, 0.0f, 1.0f), 1e30f,
                                             glm::vec2(0.0f, 1e30f));
    }
    const std::vector<kernelf::LayerHit> gpu = tracer(view, depth, 1, 0.1f, segments);
    const std::vector<kernelf::LayerSegment> last(segments.end() - 100, segments.end());
    const std::vector<kernelf::LayerHit> host = trace_layers_on_host(view, depth, 1, 0.1f, last);
    REQUIRE(gpu.size() == count);
    int hits = 0, differ = 0;
    for (std::size_t i = 0; i < 100; ++i) {
        const kernelf::LayerHit& g = gpu[count - 100 + i];
        hits += g.hit ? 1 : 0;
        differ += g.hit != host[i].hit || g.steps != host[i].steps ? 1 : 0;
    }
    int stray = 0;  // an empty segment has no hit and no step
    for (std::size_t i = 0; i + 100 < count; ++i) stray += gpu[i].hit || gpu[i].steps != 0 ? 1 : 0;
    CHECK(hits == 100);
    CHECK(differ == 0);
    CHECK(stray == 0);
}

// 6. The primary resolve on the GPU (GlSecondaryResolve, the passes of
//    render_secondary_resolve.comp on resolve_shared.h's fp64 text) against
//    the host's resolve_primary on the cpu backend's winners: the mirror
//    sphere, the moving plane mirror and the water (glass: reflected and
//    refracted rays, total internal reflection), 1, 4 and 16 lens parts.
//    On an IEEE-exact GL every sample colour and every ray (origin,
//    direction, weight, sample, time, triangle, pixel and lens part), in
//    the host's order, bit for bit; elsewhere the counts within 1 in 1000
//    and the values within 1e-4.
TEST_CASE("dof-secondary: the primary resolve on the GPU gives the host's sample colours and rays") {
    std::optional<blurcull::gl::HeadlessContext> context = context_or_skip();
    if (!context) return;
    const bool exact = !probe_arithmetic(*context).tolerant();
    const GlSecondaryResolve passes(*context);
    const RenderSettings settings = quiet_settings(48, 36, 8);
    std::vector<Scene> scenes{mirror_sphere_scene(), plane_mirror_scene(0.05f, {1.5f, 0.0f, 0.0f}),
                              builtin::make_water(1.0f, 48.0f / 36.0f)};
    std::uint64_t reflected_twice = 0;
    for (const Scene& scene : scenes) {
        std::vector<std::uint32_t> ids;
        render_cpu(scene, settings, CpuOptions{}, &ids);
        const CameraModel model(scene.camera, settings.width, settings.height);
        for (int parts : {1, 4, 16}) {
            CAPTURE(scene.name);
            CAPTURE(parts);
            const PrimaryResolve host = resolve_primary(scene, model, settings, ids, parts);
            const std::optional<GlResolved> resolved = passes.resolve(resolve_input(scene, model, settings, parts), ids);
            REQUIRE(resolved.has_value());
            const GlResolved& gpu = *resolved;
            REQUIRE(gpu.sample_colour.size() == host.sample_colour.size());
            long colours_differ = 0, rays_differ = 0;
            for (std::size_t k = 0; k < host.sample_colour.size(); ++k)
                for (int c = 0; c < 3; ++c) {
                    const float h = host.sample_colour[k][c], g = gpu.sample_colour[k][c];
                    colours_differ += exact ? bits_of(h) != bits_of(g) : std::abs(h - g) > 1e-4f;
                }
            const std::size_t rays = std::min(host.rays.size(), gpu.info.size());
            for (std::size_t r = 0; r < rays && exact; ++r) {
                const SecondaryRay& h = host.rays[r];
                const glm::uvec4 p = gpu.points[2 * r], d = gpu.points[2 * r + 1], info = gpu.info[r];
                bool same = p.w == h.triangle && d.w == ((h.sample / 8u) << 4u | h.lens_part) && info.x == h.sample &&
                            info.y == bits_of(h.time) && info.z == bits_of(h.weight.x) && h.weight.x == h.weight.z;
                for (int c = 0; c < 3; ++c)
                    same = same && p[c] == bits_of(h.origin[c]) && d[c] == bits_of(h.direction[c]);
                rays_differ += same ? 0 : 1;
            }
            for (std::size_t r = 1; r < host.rays.size(); ++r)
                reflected_twice += host.rays[r].sample == host.rays[r - 1].sample ? 1 : 0;
            MESSAGE(scene.name << ", " << parts << " lens parts: " << host.rays.size() << " rays on the host, "
                               << gpu.info.size() << " on the GPU; " << colours_differ << " colour values and "
                               << rays_differ << " rays differ");
            CHECK(gpu.reflector_samples == host.reflector_samples);
            CHECK(host.rays.size() > 100);
            if (exact) {
                CHECK(gpu.info.size() == host.rays.size());
                CHECK(colours_differ == 0);
                CHECK(rays_differ == 0);
            } else {
                CHECK(std::abs(double(gpu.info.size()) - double(host.rays.size())) <= 1e-3 * double(host.rays.size()));
                CHECK(colours_differ <= long(host.sample_colour.size() / 1000));
            }
        }
    }
    CHECK(reflected_twice > 100);  // the glass's samples spawn two rays
}
