// GPU/host parity of the secondary-ray kernel (docs/secondary-rays.md): GLSL
// compute shaders built from the emitted blurcull_kernel.glsl run the facet
// classifier on the 10^6 directions of test_kernel_secondary, the cluster
// rule, kmeans_nearest and the virtual-viewpoint fit on its 2000 clusters,
// and the image-space tracing step on its 8 x 2000 rays through two layered
// planes, on a headless Mesa context; the host runs kernel<float> on the same
// float inputs. Facets, flags, counts and decisions must agree exactly, every
// value bit for bit (the functions use + - * / sqrt floor ceil clamp min max
// abs and comparisons only, which llvmpipe rounds like the host; BC_PRECISE where an
// expression could be reassociated). docs/glsl.md, "Parity".
//
// No GL context (no Mesa): fails when CI=true, else skips with a message.

#include "gl_parity_helpers.hpp"  // first: no fma contraction on the host

#include "frontend_test_helpers.hpp"
#include "secondary_generators.hpp"

#include <blurcull/glsl/kernel_glsl.hpp>
#include <blurcull/layer_trace.hpp>
#include <blurcull/secondary_clusters.hpp>
#include "render/common/bounce_shared.h"
#include "render/gl/gl_cluster_shared.h"
#include "render/gl/gl_clustering.hpp"
#include "render/gl/gl_context.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <optional>
#include <string>
#include <vector>

using namespace blurcull;
using namespace blurcull::testing;
using namespace blurcull::frontend::test;
using Kf = kernel<float>;

namespace {

// Values are compared bit for bit (0 ULP).
constexpr std::int64_t kMaxUlps = 0;

// Runs `main` (after the kernel library) over `invocations` invocations with
// inputs at SSBO bindings 0.. and the output at the next binding; uniform
// `count` = invocations.
std::vector<std::uint32_t> run_compute(const gl::HeadlessContext& context, const char* main,
                                       const std::vector<std::vector<std::uint32_t>>& inputs,
                                       std::size_t output_uints, std::uint32_t invocations) {
    const gl::Functions& f = context.gl();
    gl::Program program(f, {{GL_COMPUTE_SHADER, {glsl::kernel_source(), main}}});
    std::vector<gl::Buffer> buffers;
    for (const auto& in : inputs) buffers.emplace_back(f, GL_SHADER_STORAGE_BUFFER, in.size() * 4, in.data());
    std::vector<std::uint32_t> out(output_uints, 0u);
    gl::Buffer result(f, GL_SHADER_STORAGE_BUFFER, out.size() * 4);
    for (std::size_t b = 0; b < buffers.size(); ++b) buffers[b].bind_base(static_cast<GLuint>(b));
    result.bind_base(static_cast<GLuint>(buffers.size()));
    f.UseProgram(program.id());
    f.Uniform1ui(f.GetUniformLocation(program.id(), "count"), invocations);
    f.DispatchCompute((invocations + 63u) / 64u, 1, 1);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    f.Finish();
    gl::check_gl(f, "running a secondary-ray parity shader");
    result.read(out.data(), out.size() * 4);
    f.UseProgram(0);
    return out;
}

// Differences between two result arrays: `exact` slots must be equal, the
// others within kMaxUlps as floats.
struct Diff {
    long compared = 0;
    long exact_mismatches = 0;
    std::int64_t max_ulps = 0;
    std::string first;
};

void compare(Diff& d, const std::vector<std::uint32_t>& host, const std::vector<std::uint32_t>& gpu, int stride,
             const std::vector<int>& exact_slots, const char* what) {
    for (std::size_t i = 0; i < host.size(); ++i) {
        int slot = static_cast<int>(i % static_cast<std::size_t>(stride));
        ++d.compared;
        bool exact = std::find(exact_slots.begin(), exact_slots.end(), slot) != exact_slots.end();
        std::int64_t ulps = exact ? (host[i] == gpu[i] ? 0 : INT64_MAX) : ulp_distance(float_of(host[i]), float_of(gpu[i]));
        if (exact && ulps != 0) ++d.exact_mismatches;
        if (!exact) d.max_ulps = std::max(d.max_ulps, ulps);
        if (ulps > kMaxUlps && d.first.empty())
            d.first = std::string(what) + " item " + std::to_string(i / static_cast<std::size_t>(stride)) + " slot " +
                      std::to_string(slot) + ": host " + std::to_string(host[i]) + " (" +
                      std::to_string(float_of(host[i])) + "), GPU " + std::to_string(gpu[i]) + " (" +
                      std::to_string(float_of(gpu[i])) + ")";
    }
}

void report(const Diff& d, const char* what) {
    MESSAGE(std::string(what) << ": " << d.compared << " values, " << d.exact_mismatches << " exact ones differ, max "
                 << d.max_ulps << " ULP");
    CHECK_MESSAGE(d.exact_mismatches == 0, d.first);
    CHECK_MESSAGE(d.max_ulps <= kMaxUlps, d.first);
}

void put(std::vector<std::uint32_t>& v, Kf::vec3 x) {
    v.push_back(bits_of(x.x));
    v.push_back(bits_of(x.y));
    v.push_back(bits_of(x.z));
}

const char* const kFacetMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Directions { float dir_in[]; };
layout(std430, binding = 1) writeonly buffer Results { uint out_[]; };
uniform uint count;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    vec3 d = vec3(dir_in[3u * i], dir_in[3u * i + 1u], dir_in[3u * i + 2u]);
    out_[i] = uint(bc_dodecahedron_facet(d));
    if (i < 12u) {
        vec3 n = bc_dodecahedron_normal(int(i));
        out_[count + 3u * i] = floatBitsToUint(n.x);
        out_[count + 3u * i + 1u] = floatBitsToUint(n.y);
        out_[count + 3u * i + 2u] = floatBitsToUint(n.z);
    }
}
)glsl";

const char* const kClusterMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { float pt[]; };          // position, direction
layout(std430, binding = 1) readonly buffer Clusters { uint cl[]; };         // offset, count
layout(std430, binding = 2) readonly buffer Params { float param[]; };       // tan_half_fov, min_near, largest
layout(std430, binding = 3) writeonly buffer Results { uint out_[]; };
uniform uint count;
const uint STRIDE = 17u;
vec3 P(uint i) { return vec3(pt[6u * i], pt[6u * i + 1u], pt[6u * i + 2u]); }
vec3 D(uint i) { return vec3(pt[6u * i + 3u], pt[6u * i + 4u], pt[6u * i + 5u]); }
void put3(uint at, vec3 v) {
    out_[at] = floatBitsToUint(v.x);
    out_[at + 1u] = floatBitsToUint(v.y);
    out_[at + 2u] = floatBitsToUint(v.z);
}
void main() {
    uint c = gl_GlobalInvocationID.x;
    if (c >= count) return;
    uint o = cl[2u * c];
    uint n = cl[2u * c + 1u];
    ClusterSums s = bc_cluster_sums_empty(bc_cluster_position_scale(param[2u + c]));
    for (uint i = 0u; i < n; ++i) s = bc_cluster_sums_add(s, P(o + i), D(o + i));
    VirtualViewFit f = bc_virtual_view_begin(s, param[0], param[1]);
    for (uint i = 0u; i < n; ++i) f = bc_virtual_view_add(f, P(o + i), D(o + i));
    VirtualView v = bc_virtual_view_finish(f);
    uint at = c * STRIDE;
    put3(at, v.eye);
    put3(at + 3u, v.forward);
    put3(at + 6u, v.right);
    put3(at + 9u, v.up);
    out_[at + 12u] = floatBitsToUint(v.near);
    out_[at + 13u] = floatBitsToUint(v.backoff);
    out_[at + 14u] = uint(v.flags);
    out_[at + 15u] = bc_clusters_for_facet(n, bc_cluster_target_size(n * 7u, 24u), 3u) * 1000u +
                     bc_kmeans_start_key(7u, int(c % 12u), n) % 1000u;
    // The nearest of the cluster's first three points, for its first 16
    // points: 2 bits each.
    vec3 centres[BC_CLUSTERS_PER_FACET_MAX] =
        vec3[BC_CLUSTERS_PER_FACET_MAX](P(o), P(o + min(1u, n - 1u)), P(o + min(2u, n - 1u)));
    uint mask = 0u;
    for (uint i = 0u; i < min(n, 16u); ++i)
        mask |= uint(bc_kmeans_nearest(P(o + i), centres, int(min(n, 3u)))) << (2u * i);
    out_[at + 16u] = mask;
}
)glsl";

const char* const kTraceMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Depths { float depth_in[]; };   // scene, layer, y, x
layout(std430, binding = 1) readonly buffer Rays { float ray_in[]; };       // origin, direction
layout(std430, binding = 2) readonly buffer View { float view_in[]; };      // tan, near, far, size, rays per scene
layout(std430, binding = 3) writeonly buffer Results { uint out_[]; };
uniform uint count;
const uint STRIDE = 16u;
void main() {
    uint r = gl_GlobalInvocationID.x;
    if (r >= count) return;
    LayerView v;
    v.eye = vec3(0.0);
    v.forward = vec3(0.0, 0.0, 1.0);
    v.right = vec3(1.0, 0.0, 0.0);
    v.up = vec3(0.0, 1.0, 0.0);
    v.tan_half_fov = view_in[0];
    v.near = view_in[1];
    v.far = view_in[2];
    v.size = int(view_in[3]);
    int scene = int(r / uint(view_in[4]));
    vec3 o = vec3(ray_in[6u * r], ray_in[6u * r + 1u], ray_in[6u * r + 2u]);
    vec3 d = vec3(ray_in[6u * r + 3u], ray_in[6u * r + 4u], ray_in[6u * r + 5u]);
    LayerSegment seg = bc_layer_segment(v, o, d, 1000.0, vec2(0.0, bc_huge()));
    // The loop of include/blurcull/layer_trace.hpp, reading this shader's buffer.
    LayerTrace t = bc_layer_trace_begin(v, seg, 2, 0.5);
    for (int k = 0; k < t.steps; ++k) {
        if (t.done) break;
        float depths[BC_LAYERS_MAX];
        for (int l = 0; l < BC_LAYERS_MAX; ++l)
            depths[l] = l < t.layers ? depth_in[((scene * 2 + l) * v.size + t.y) * v.size + t.x] : 0.0;
        t = bc_layer_trace_step(v, seg, t, depths);
    }
    LayerHit h = t.hit;
    vec4 box = bc_layer_footprint(v, seg);
    uint at = r * STRIDE;
    out_[at] = (seg.empty ? 1u : 0u) | (h.hit ? 2u : 0u);
    out_[at + 1u] = uint(h.layer + 1);
    out_[at + 2u] = uint(h.steps);
    out_[at + 3u] = floatBitsToUint(seg.s0);
    out_[at + 4u] = floatBitsToUint(seg.s1);
    out_[at + 5u] = floatBitsToUint(seg.z0);
    out_[at + 6u] = floatBitsToUint(seg.z1);
    out_[at + 7u] = floatBitsToUint(seg.p0.x);
    out_[at + 8u] = floatBitsToUint(seg.p1.y);
    out_[at + 9u] = floatBitsToUint(h.s);
    out_[at + 10u] = floatBitsToUint(h.depth);
    out_[at + 11u] = floatBitsToUint(h.image.x);
    out_[at + 12u] = floatBitsToUint(h.image.y);
    out_[at + 13u] = floatBitsToUint(box.x) ^ floatBitsToUint(box.w);
    vec3 q = bc_layer_project(v, o + d);
    out_[at + 14u] = floatBitsToUint(q.x);
    out_[at + 15u] = floatBitsToUint(q.z);
}
)glsl";

const char* const kAssignMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { float pt[]; };     // position, direction
layout(std430, binding = 1) readonly buffer Centres { float ce[]; };    // 12 facets x 3 centres
layout(std430, binding = 2) readonly buffer Counts { int k_in[]; };     // centres per facet
layout(std430, binding = 3) writeonly buffer Results { uint out_[]; };
uniform uint count;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    vec3 p = vec3(pt[6u * i], pt[6u * i + 1u], pt[6u * i + 2u]);
    vec3 d = vec3(pt[6u * i + 3u], pt[6u * i + 4u], pt[6u * i + 5u]);
    int face = bc_dodecahedron_facet(d);
    vec3 c[BC_CLUSTERS_PER_FACET_MAX];
    for (int k = 0; k < BC_CLUSTERS_PER_FACET_MAX; ++k) {
        int at = 3 * (face * BC_CLUSTERS_PER_FACET_MAX + k);
        c[k] = vec3(ce[at], ce[at + 1], ce[at + 2]);
    }
    out_[i] = uint(face * 4 + bc_kmeans_nearest(p, c, k_in[face]));
}
)glsl";

}  // namespace

TEST_CASE("GLSL assigns the mirror sphere's pixels to the host's facets and clusters") {
    auto context = context_or_skip();
    if (!context) return;
    std::vector<dvec3> dp, dd;
    mirror_sphere_pixels(dp, dd);
    std::vector<Kf::vec3> p, d;
    std::vector<std::uint32_t> points;
    for (std::size_t i = 0; i < dp.size(); ++i) {
        p.emplace_back(static_cast<float>(dp[i].x), static_cast<float>(dp[i].y), static_cast<float>(dp[i].z));
        d.emplace_back(static_cast<float>(dd[i].x), static_cast<float>(dd[i].y), static_cast<float>(dd[i].z));
        put(points, p.back());
        put(points, d.back());
    }
    ClusterOptions options;
    options.max_iterations = 1000;
    Clustering<float> clustering = cluster_reflector_pixels<float>(p, d, options);
    REQUIRE(clustering.unsettled_facets == 0);
    // The final means, by facet; and each cluster's index inside its facet.
    std::vector<std::uint32_t> centres(12 * BC_CLUSTERS_PER_FACET_MAX * 3, 0u), counts(12, 1u);
    std::vector<int> local(clustering.clusters.size());
    std::vector<int> seen(12, 0);
    for (std::size_t c = 0; c < clustering.clusters.size(); ++c) {
        int facet = clustering.clusters[c].facet;
        int k = seen[static_cast<std::size_t>(facet)]++;
        local[c] = k;
        Kf::vec3 m = Kf::cluster_mean_position(clustering.clusters[c].sums);
        for (int a = 0; a < 3; ++a)
            centres[static_cast<std::size_t>(3 * (facet * BC_CLUSTERS_PER_FACET_MAX + k) + a)] = bits_of(m[a]);
        counts[static_cast<std::size_t>(facet)] = static_cast<std::uint32_t>(k + 1);
    }
    std::vector<std::uint32_t> host;
    long agree_with_clustering = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        int face = Kf::dodecahedron_facet(d[i]);
        Kf::vec3 c[BC_CLUSTERS_PER_FACET_MAX];
        for (int k = 0; k < BC_CLUSTERS_PER_FACET_MAX; ++k)
            for (int a = 0; a < 3; ++a)
                c[k][a] = float_of(centres[static_cast<std::size_t>(3 * (face * BC_CLUSTERS_PER_FACET_MAX + k) + a)]);
        int nearest = Kf::kmeans_nearest(p[i], c, static_cast<int>(counts[static_cast<std::size_t>(face)]));
        host.push_back(static_cast<std::uint32_t>(face * 4 + nearest));
        if (nearest == local[static_cast<std::size_t>(clustering.cluster_of[i])]) ++agree_with_clustering;
    }
    std::vector<std::uint32_t> gpu =
        run_compute(*context, kAssignMain, {points, centres, counts}, host.size(), static_cast<std::uint32_t>(host.size()));
    Diff diff;
    compare(diff, host, gpu, 1, {0}, "sphere pixel");
    MESSAGE(p.size() << " sphere pixels in " << clustering.clusters.size()
                     << " clusters; the host's assignment step agrees with the settled clustering on "
                     << agree_with_clustering);
    CHECK(agree_with_clustering == static_cast<long>(p.size()));
    report(diff, "dodecahedron_facet + kmeans_nearest on the sphere");
}

namespace {

// Whether two views are one: bit for bit, or on a GPU outside the IEEE
// model (`tolerant`) the same flags and every value within 1e-4 relative.
bool same_view(const Kf::VirtualView& a, const Kf::VirtualView& b, bool tolerant) {
    auto close = [tolerant](float x, float y) {
        return tolerant ? std::fabs(x - y) <= 1e-4f * (1.0f + std::fabs(x)) : bits_of(x) == bits_of(y);
    };
    auto close3 = [&](const Kf::vec3& x, const Kf::vec3& y) { return close(x.x, y.x) && close(x.y, y.y) && close(x.z, y.z); };
    return close3(a.eye, b.eye) && close3(a.forward, b.forward) && close3(a.right, b.right) && close3(a.up, b.up) &&
           close(a.tan_half_fov, b.tan_half_fov) && close(a.near, b.near) && close(a.backoff, b.backoff) &&
           a.flags == b.flags;
}

// Whether two clusterings are one: every ray's cluster, each cluster's
// facet and sums word for word, the iterations and unsettled facets. On a
// GPU outside the IEEE model (`tolerant`) a mean may round differently and
// move a ray: asserted there, the same number of clusters on the same
// facets and at most 1 ray in 100 in another cluster.
void check_same_clustering(const Clustering<float>& host, const Clustering<float>& gpu, bool tolerant) {
    REQUIRE(gpu.clusters.size() == host.clusters.size());
    REQUIRE(gpu.cluster_of.size() == host.cluster_of.size());
    long words_differ = 0;
    for (std::size_t c = 0; c < host.clusters.size(); ++c) {
        const Kf::ClusterSums& a = host.clusters[c].sums;
        const Kf::ClusterSums& b = gpu.clusters[c].sums;
        CHECK(gpu.clusters[c].facet == host.clusters[c].facet);
        words_differ += (a.position_hi != b.position_hi) + (a.position_lo != b.position_lo) +
                        (a.direction_hi != b.direction_hi) + (a.direction_lo != b.direction_lo) +
                        (a.count != b.count) + (a.unfit != b.unfit) + (a.position_scale != b.position_scale);
    }
    long rays_differ = 0;
    for (std::size_t i = 0; i < host.cluster_of.size(); ++i) rays_differ += gpu.cluster_of[i] != host.cluster_of[i];
    MESSAGE(host.cluster_of.size() << " rays, " << host.clusters.size() << " clusters, " << host.iterations
                                   << " Lloyd iterations: " << rays_differ << " rays and " << words_differ
                                   << " sums differ");
    if (tolerant) {
        CHECK(double(rays_differ) <= 0.01 * double(host.cluster_of.size()));
        return;
    }
    CHECK(gpu.iterations == host.iterations);
    CHECK(gpu.unsettled_facets == host.unsettled_facets);
    CHECK(rays_differ == 0);
    CHECK(words_differ == 0);
}

}  // namespace

TEST_CASE("the GPU clustering passes give the host's clusters and views, bit for bit on an IEEE-exact GL") {
    auto context = context_or_skip();
    if (!context) return;
    const ArithmeticProbe probe = probe_arithmetic(*context);
    MESSAGE("GL arithmetic: " << probe.describe());
    const bool tolerant = probe.tolerant();
    const frontend::GlClustering gpu_passes(*context);
    // The GPU's clustering and views against the host's, both asserted equal.
    struct {
        const frontend::GlClustering& passes;
        bool tolerant;
        Clustering<float> cluster(const std::vector<Kf::vec3>& p, const std::vector<Kf::vec3>& d,
                                  const ClusterOptions& options) const {
            const float tan_half = 0.8391f, min_near = 0.01f;
            ClusterViews<float> views;
            Clustering<float> clusters = passes.cluster(p, d, options, tan_half, min_near, &views);
            const ClusterViews<float> host = fit_cluster_views<float>(clusters, p, d, tan_half, min_near);
            REQUIRE(views.along_mean.size() == clusters.clusters.size());
            REQUIRE(views.along_normal.size() == clusters.clusters.size());
            long differ = 0, outside = 0;
            for (std::size_t c = 0; c < clusters.clusters.size(); ++c) {
                differ += !same_view(views.along_mean[c], host.along_mean[c], tolerant);
                differ += !same_view(views.along_normal[c], host.along_normal[c], tolerant);
                outside += (host.along_mean[c].flags & BC_VIEW_DIRECTION_OUTSIDE) != 0;
            }
            MESSAGE((2 * clusters.clusters.size()) << " views (" << outside << " with a direction outside along the mean): "
                                                 << differ << " differ");
            CHECK(differ == 0);
            return clusters;
        }
    } gpu{gpu_passes, tolerant};
    SUBCASE("one point repeated: fewer centres than asked") {
        std::vector<Kf::vec3> p(600, Kf::vec3(1.0f, 2.0f, 3.0f)), d(600, Kf::vec3(0.0f, 0.0f, 1.0f));
        ClusterOptions options;
        options.wanted_clusters = 1000;  // 3 asked of the facet
        const Clustering<float> host = cluster_reflector_pixels<float>(p, d, options);
        CHECK(host.clusters.size() == 1);
        check_same_clustering(host, gpu.cluster(p, d, options), tolerant);
    }
    SUBCASE("the mirror sphere's pixels, to settling and stopped early") {
        std::vector<dvec3> dp, dd;
        mirror_sphere_pixels(dp, dd);
        std::vector<Kf::vec3> p, d;
        for (std::size_t i = 0; i < dp.size(); ++i) {
            p.emplace_back(static_cast<float>(dp[i].x), static_cast<float>(dp[i].y), static_cast<float>(dp[i].z));
            d.emplace_back(static_cast<float>(dd[i].x), static_cast<float>(dd[i].y), static_cast<float>(dd[i].z));
        }
        for (int iterations : {1, 8, 1000}) {
            CAPTURE(iterations);
            ClusterOptions options;
            options.max_iterations = iterations;
            check_same_clustering(cluster_reflector_pixels<float>(p, d, options), gpu.cluster(p, d, options), tolerant);
        }
    }
    SUBCASE("300,000 random rays over every facet, with coincident, NaN and infinite ones") {
        Rng rng(0xc1u);
        std::vector<Kf::vec3> p, d;
        for (int i = 0; i < 300000; ++i) {
            p.emplace_back(static_cast<float>(rng.uniform(-30.0, 30.0)), static_cast<float>(rng.uniform(0.0, 2.0)),
                           static_cast<float>(rng.uniform(-1.0, 1.0)));
            const dvec3 u = random_unit(rng);
            d.emplace_back(static_cast<float>(u.x), static_cast<float>(u.y), static_cast<float>(u.z));
        }
        // 500 rays at one point (equal distances: the least ray wins), and points that do not fit.
        for (int i = 0; i < 500; ++i) {
            p.emplace_back(5.0f, 5.0f, 5.0f);
            d.emplace_back(0.0f, 0.0f, -1.0f);
        }
        const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
        p[17] = Kf::vec3(nan, 0.0f, 0.0f);
        p[4242] = Kf::vec3(0.0f, inf, 0.0f);
        d[99999] = Kf::vec3(nan, 0.0f, 1.0f);
        for (std::uint32_t seed : {0x5eedu, 7u}) {
            CAPTURE(seed);
            ClusterOptions options;
            options.seed = seed;
            options.wanted_clusters = seed == 7u ? 30u : 24u;
            const Clustering<float> host = cluster_reflector_pixels<float>(p, d, options);
            CHECK(host.clusters.size() >= 12);
            check_same_clustering(host, gpu.cluster(p, d, options), tolerant);
        }
    }
}

TEST_CASE("the GPU grouping pass lists each cluster's groups, own triangles and normal cone as the host makes them") {
    auto context = context_or_skip();
    if (!context) return;
    const bool tolerant = probe_arithmetic(*context).tolerant();
    const frontend::GlClustering passes(*context);
    // 20,000 pixels in order, each with 0 to 16 rays (8 spp, a dielectric's
    // two a sample) in 16 lens parts; one pixel's 16 rays in one part;
    // directions spread over the sphere, so clusters split a pixel's rays.
    Rng rng(0x9e0u);
    const std::uint32_t triangles = 1000;
    std::vector<Kf::vec3> p, d;
    std::vector<frontend::RayGroupKey> keys;
    for (std::uint32_t pixel = 0; pixel < 20000; ++pixel) {
        const int rays = pixel == 777 ? 16 : rng.below(17);
        for (int k = 0; k < rays; ++k) {
            p.emplace_back(static_cast<float>(rng.uniform(-10.0, 10.0)), static_cast<float>(rng.uniform(-1.0, 1.0)),
                           static_cast<float>(rng.uniform(-5.0, 5.0)));
            const dvec3 u = random_unit(rng);
            d.emplace_back(static_cast<float>(u.x), static_cast<float>(u.y), static_cast<float>(u.z));
            const auto part = static_cast<std::uint32_t>(pixel == 777 ? 5 : rng.below(16));
            keys.push_back({static_cast<std::uint32_t>(rng.below(static_cast<int>(triangles))), pixel << 4u | part});
        }
    }
    ClusterOptions options;
    options.wanted_clusters = 30;
    ClusterViews<float> views;
    const Clustering<float> clusters = passes.cluster(p, d, options, 0.8391f, 0.01f, &views, &keys);
    REQUIRE(clusters.clusters.size() >= 12);
    std::vector<Kf::vec3> forwards;
    for (std::size_t j = 0; j < clusters.clusters.size(); ++j)
        forwards.push_back((views.along_mean[j].flags & BC_VIEW_DIRECTION_OUTSIDE) != 0 ? views.along_normal[j].forward
                                                                                      : views.along_mean[j].forward);
    for (bool cull_normals : {true, false}) {
        CAPTURE(cull_normals);
        REQUIRE(passes.group(forwards, cull_normals, triangles));
        // The host's: per cluster its groups (rays by pixel and part), own triangles and least cosine.
        const std::size_t count = clusters.clusters.size();
        std::vector<std::map<std::uint32_t, std::vector<std::uint32_t>>> groups(count);
        std::vector<std::set<std::uint32_t>> own(count);
        std::vector<float> cos_widest(count, 1.0f);
        for (std::size_t r = 0; r < p.size(); ++r) {
            const auto j = static_cast<std::size_t>(clusters.cluster_of[r]);
            groups[j][keys[r].pixel_part].push_back(static_cast<std::uint32_t>(r));
            own[j].insert(keys[r].triangle);
            cos_widest[j] = std::min(cos_widest[j], Kf::bc_dot3(d[r], forwards[j]));
        }
        long wrong_groups = 0, wrong_own = 0, wrong_threshold = 0;
        std::size_t listed = 0, split_pixels = 0;
        for (std::size_t j = 0; j < count; ++j) {
            const frontend::GlClustering::GroupedCluster g = passes.grouped(j);
            std::vector<std::uint32_t> list(g.rays), pairs(2 * g.rays), bits(g.own_bytes / 4);
            std::uint32_t group_count = 0;
            float threshold = 0.0f;
            passes.lists_buffer().read(list.data(), list.size() * 4, g.list_offset);
            passes.pairs_buffer().read(pairs.data(), pairs.size() * 4, g.pairs_offset);
            passes.own_buffer().read(bits.data(), bits.size() * 4, g.own_offset);
            passes.slots_buffer().read(&group_count, 4, g.group_count_offset);
            passes.slots_buffer().read(&threshold, 4, g.threshold_offset);
            // Every group once, each one key's rays, all of them.
            std::set<std::uint32_t> seen;
            wrong_groups += group_count != groups[j].size();
            for (std::uint32_t k = 0; k < std::min<std::size_t>(group_count, g.rays); ++k) {
                const std::uint32_t begin = pairs[2 * k], end = pairs[2 * k + 1];
                if (!(begin < end && end <= g.rays)) {
                    ++wrong_groups;
                    continue;
                }
                std::vector<std::uint32_t> rays(list.begin() + begin, list.begin() + end);
                std::sort(rays.begin(), rays.end());
                const std::uint32_t key = keys[rays[0]].pixel_part;
                wrong_groups += !seen.insert(key).second || groups[j].count(key) == 0 || groups[j][key] != rays;
                listed += rays.size();
            }
            for (std::uint32_t t = 0; t < triangles; ++t)
                wrong_own += (((bits[t / 32] >> (t % 32)) & 1u) != 0u) != (own[j].count(t) != 0);
            const float expected = frontend::bounce::bc_normal_cone_threshold(cos_widest[j], cull_normals);
            wrong_threshold += tolerant ? std::fabs(threshold - expected) > 1e-5f : bits_of(threshold) != bits_of(expected);
        }
        for (std::uint32_t pixel = 0; pixel < 20000; ++pixel) {
            std::set<std::size_t> in;  // the clusters holding a ray of the pixel
            for (std::size_t j = 0; j < count; ++j)
                for (std::uint32_t part = 0; part < 16; ++part)
                    if (groups[j].count(pixel << 4u | part) != 0) in.insert(j);
            split_pixels += in.size() > 1;
        }
        MESSAGE(p.size() << " rays, " << count << " clusters, " << split_pixels
                         << " pixels split between clusters: groups wrong " << wrong_groups << ", own bits wrong "
                         << wrong_own << ", thresholds wrong " << wrong_threshold);
        CHECK(split_pixels > 1000);  // the case the sort by slot is for
        CHECK(listed == p.size());
        CHECK(wrong_groups == 0);
        CHECK(wrong_own == 0);
        CHECK(wrong_threshold == 0);
    }
}

TEST_CASE("GLSL dodecahedron_facet and normals equal the host's on 10^6 directions") {
    auto context = context_or_skip();
    if (!context) return;
    std::vector<dvec3> directions = facet_test_directions(0xd0dec4ull, 1000000);
    std::vector<std::uint32_t> in, host;
    for (const dvec3& d : directions) {
        Kf::vec3 v(static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z));
        put(in, v);
        host.push_back(static_cast<std::uint32_t>(Kf::dodecahedron_facet(v)));
    }
    auto n = static_cast<std::uint32_t>(directions.size());
    for (int f = 0; f < 12; ++f) put(host, Kf::dodecahedron_normal(f));
    std::vector<std::uint32_t> gpu = run_compute(*context, kFacetMain, {in}, host.size(), n);
    Diff facets, normals;
    compare(facets, std::vector<std::uint32_t>(host.begin(), host.begin() + n),
            std::vector<std::uint32_t>(gpu.begin(), gpu.begin() + n), 1, {0}, "facet");
    compare(normals, std::vector<std::uint32_t>(host.begin() + n, host.end()),
            std::vector<std::uint32_t>(gpu.begin() + n, gpu.end()), 1, {0}, "normal");
    report(facets, "dodecahedron_facet");
    report(normals, "dodecahedron_normal");
}

TEST_CASE("GLSL virtual viewpoints, cluster rule and kmeans_nearest equal the host's on 2000 clusters") {
    auto context = context_or_skip();
    if (!context) return;
    // The clusters of test_kernel_secondary's float case.
    Rng rng(0x71e3ull + sizeof(float));
    const float tan_half = static_cast<float>(std::tan(40.0 * 3.14159265358979323846 / 180.0));
    const float min_near = 0.01f;
    std::vector<std::uint32_t> points, clusters, host, largest;
    constexpr int kStride = 17;
    for (int c = 0; c < 2000; ++c) {
        SyntheticCluster sc = make_cluster(rng, c % 5 == 0 ? 80.0 : 30.0);
        clusters.push_back(static_cast<std::uint32_t>(points.size() / 6));
        clusters.push_back(static_cast<std::uint32_t>(sc.positions.size()));
        std::vector<Kf::vec3> p, d;
        float largest_coordinate = 0.0f;
        for (std::size_t i = 0; i < sc.positions.size(); ++i) {
            p.emplace_back(static_cast<float>(sc.positions[i].x), static_cast<float>(sc.positions[i].y),
                           static_cast<float>(sc.positions[i].z));
            d.emplace_back(static_cast<float>(sc.directions[i].x), static_cast<float>(sc.directions[i].y),
                           static_cast<float>(sc.directions[i].z));
            put(points, p.back());
            put(points, d.back());
            for (int a = 0; a < 3; ++a) largest_coordinate = std::max(largest_coordinate, std::fabs(p.back()[a]));
        }
        largest.push_back(bits_of(largest_coordinate));
        const Kf::ClusterSums sums = cluster_sums_of<float>(p, d);
        Kf::VirtualView v = fit_virtual_view<float>(sums, p, d, tan_half, min_near);
        put(host, v.eye);
        put(host, v.forward);
        put(host, v.right);
        put(host, v.up);
        host.push_back(bits_of(v.near));
        host.push_back(bits_of(v.backoff));
        host.push_back(static_cast<std::uint32_t>(v.flags));
        auto n = static_cast<std::uint32_t>(p.size());
        host.push_back(Kf::clusters_for_facet(n, Kf::cluster_target_size(n * 7u, 24u), 3u) * 1000u +
                       Kf::kmeans_start_key(7u, c % 12, n) % 1000u);
        Kf::vec3 centres[BC_CLUSTERS_PER_FACET_MAX] = {p[0], p[std::min<std::size_t>(1, n - 1)],
                                                       p[std::min<std::size_t>(2, n - 1)]};
        std::uint32_t mask = 0;
        for (std::uint32_t i = 0; i < std::min(n, 16u); ++i)
            mask |= static_cast<std::uint32_t>(Kf::kmeans_nearest(p[i], centres, static_cast<int>(std::min(n, 3u))))
                    << (2u * i);
        host.push_back(mask);
    }
    std::vector<std::uint32_t> params = {bits_of(tan_half), bits_of(min_near)};
    params.insert(params.end(), largest.begin(), largest.end());
    std::vector<std::uint32_t> gpu = run_compute(*context, kClusterMain, {points, clusters, params}, host.size(), 2000u);
    Diff d;
    compare(d, host, gpu, kStride, {14, 15, 16}, "cluster");
    report(d, "virtual_view_* / clusters_for_facet / kmeans_nearest");
}

TEST_CASE("GLSL layer tracing equals the host's on 8 x 2000 rays through two layered planes, and their reverses") {
    auto context = context_or_skip();
    if (!context) return;
    // The scenes and rays of test_kernel_secondary's float case.
    Rng rng(0x7ace0ull + sizeof(float));
    constexpr int kScenes = 8;
    constexpr int kRaysPerScene = 2000;
    std::vector<std::uint32_t> depths, rays, host;
    LayerScene first;
    for (int scene = 0; scene < kScenes; ++scene) {
        LayerScene s = make_layer_scene(rng);
        if (scene == 0) first = s;
        std::vector<float> image[2];
        for (int l = 0; l < 2; ++l)
            for (double z : s.depth[l]) {
                image[l].push_back(static_cast<float>(z));
                depths.push_back(bits_of(static_cast<float>(z)));
            }
        Kf::LayerView v;
        v.eye = Kf::vec3(0.0f);
        v.forward = Kf::vec3(0.0f, 0.0f, 1.0f);
        v.right = Kf::vec3(1.0f, 0.0f, 0.0f);
        v.up = Kf::vec3(0.0f, 1.0f, 0.0f);
        v.tan_half_fov = static_cast<float>(s.tan_half_fov);
        v.near = static_cast<float>(s.near);
        v.far = static_cast<float>(s.far);
        v.size = s.size;
        auto fetch = [&](int layer, int x, int y) { return image[layer][static_cast<std::size_t>(y * s.size + x)]; };
        for (int n = 0; n < kRaysPerScene; ++n) {
            TraceRay ray = make_trace_ray(rng, s);
            Kf::vec3 o(static_cast<float>(ray.origin.x), static_cast<float>(ray.origin.y), static_cast<float>(ray.origin.z));
            Kf::vec3 forward(static_cast<float>(ray.direction.x), static_cast<float>(ray.direction.y),
                             static_cast<float>(ray.direction.z));
            // The kernel test's ray, then the same ray reversed (misses, empty segments).
            for (Kf::vec3 d : {forward, -forward}) {
                put(rays, o);
                put(rays, d);
                Kf::LayerSegment seg = Kf::layer_segment(v, o, d, 1000.0f, Kf::vec2(0.0f, Kf::bc_huge()));
                Kf::LayerHit h = trace_layers<float>(v, seg, 2, 0.5f, fetch);
                Kf::vec4 box = Kf::layer_footprint(v, seg);
                Kf::vec3 q = Kf::layer_project(v, o + d);
                std::uint32_t values[16] = {(seg.empty ? 1u : 0u) | (h.hit ? 2u : 0u), static_cast<std::uint32_t>(h.layer + 1),
                                            static_cast<std::uint32_t>(h.steps), bits_of(seg.s0), bits_of(seg.s1),
                                            bits_of(seg.z0), bits_of(seg.z1), bits_of(seg.p0.x), bits_of(seg.p1.y),
                                            bits_of(h.s), bits_of(h.depth), bits_of(h.image.x), bits_of(h.image.y),
                                            bits_of(box.x) ^ bits_of(box.w), bits_of(q.x), bits_of(q.z)};
                host.insert(host.end(), values, values + 16);
            }
        }
    }
    std::vector<std::uint32_t> view = {bits_of(static_cast<float>(first.tan_half_fov)), bits_of(static_cast<float>(first.near)),
                                       bits_of(static_cast<float>(first.far)), bits_of(static_cast<float>(first.size)),
                                                       bits_of(static_cast<float>(2 * kRaysPerScene))};
    std::vector<std::uint32_t> gpu =
        run_compute(*context, kTraceMain, {depths, rays, view}, host.size(), 2 * kScenes * kRaysPerScene);
    Diff d;
    compare(d, host, gpu, 16, {0, 1, 2, 13}, "trace");
    long hits = 0;
    for (std::size_t i = 0; i < host.size(); i += 16) hits += (host[i] & 2u) ? 1 : 0;
    MESSAGE(hits << " of " << 2 * kScenes * kRaysPerScene << " rays hit");
    CHECK(hits >= kScenes * kRaysPerScene);
    CHECK(hits < 2 * kScenes * kRaysPerScene);
    report(d, "layer_segment / layer_trace_* / layer_footprint / layer_project");
}
