#include "render/gl/gl_clustering.hpp"

#include "render/gl/gl_cluster_shared.h"
#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

namespace blurcull::frontend {

using gpu::ClusterState;
using gpu::ClusterViewFit;

namespace {

glm::vec3 vec3_of(const float v[3]) { return {v[0], v[1], v[2]}; }

// A fit's finished view as the host's virtual_view_finish gives it.
kernelf::VirtualView view_of(const ClusterViewFit& fit) {
    kernelf::VirtualView v{};
    v.eye = vec3_of(fit.eye);
    v.forward = vec3_of(fit.forward);
    v.right = vec3_of(fit.right);
    v.up = vec3_of(fit.up);
    v.tan_half_fov = fit.tan_half_fov;
    v.near = fit.near;
    v.backoff = fit.backoff;
    v.flags = fit.flags;
    return v;
}

}  // namespace

GlClustering::GlClustering(const gl::HeadlessContext& context)
    : context_((context.make_current(), &context)),
      gl_(&context.gl()),
      program_(std::make_unique<gl::Program>(
          context.gl(), std::vector<gl::ShaderStage>{gl::shader_stage(GL_COMPUTE_SHADER, "render_secondary_cluster.comp",
                                                                      gl::Prelude::clusters)})) {}

// The program's and buffers' glDelete* act on the current context: this one's, with several alive.
GlClustering::~GlClustering() { context_->make_current_for_release(); }

std::size_t GlClustering::max_rays() const {
    const auto block = static_cast<std::size_t>(static_cast<unsigned>(get_integer(*gl_, GL_MAX_SHADER_STORAGE_BLOCK_SIZE)));
    return block / (2 * sizeof(glm::vec4));
}

const gl::Buffer& GlClustering::points_buffer() const {
    if (!points_) throw gl::GlError("gl: no rays clustered yet, so none on the GPU");
    return *points_;
}

Clustering<float> GlClustering::cluster(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& directions, const ClusterOptions& options,
                                        float tan_half_fov, float min_near, ClusterViews<float>* views) const {
    using K = kernelf;
    Clustering<float> out;
    const std::size_t n = std::min(positions.size(), directions.size());
    out.cluster_of.assign(n, -1);
    if (n == 0) return out;
    if (n > max_rays() || n > 0xffffffffu - 64u)
        throw gl::GlError("gl: " + std::to_string(n) + " rays to cluster, more than a storage block of the GL (" +
                          std::to_string(max_rays()) + ") or a 32-bit ray index holds");
    const gl::Functions& f = *gl_;
    std::vector<glm::vec4> points(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
        points[2 * i] = glm::vec4(positions[i], 0.0f);
        points[2 * i + 1] = glm::vec4(directions[i], 0.0f);
    }
    const ClusterState initial{};
    gl::reserve_storage(f, points_, points.size() * sizeof(glm::vec4), points.data())
        .bind_base(BC_GL_CLUSTER_POINTS_BINDING);
    gl::reserve_storage(f, labels_, n * sizeof(std::uint32_t)).bind_base(BC_GL_CLUSTER_LABELS_BINDING);
    gl::reserve_storage(f, state_, sizeof initial, &initial).bind_base(BC_GL_CLUSTER_STATE_BINDING);
    std::vector<ClusterViewFit> fits(2 * BC_CLUSTER_SLOTS, ClusterViewFit{});
    gl::reserve_storage(f, views_, fits.size() * sizeof(ClusterViewFit), fits.data())
        .bind_base(BC_GL_CLUSTER_VIEWS_BINDING);

    const GLuint id = program_->id();
    f.UseProgram(id);
    f.Uniform1ui(f.GetUniformLocation(id, "rays"), static_cast<GLuint>(n));
    f.Uniform1ui(f.GetUniformLocation(id, "wanted_clusters"), options.wanted_clusters);
    f.Uniform1ui(f.GetUniformLocation(id, "max_per_facet"), options.max_per_facet);
    f.Uniform1ui(f.GetUniformLocation(id, "seed"), options.seed);
    f.Uniform1f(f.GetUniformLocation(id, "tan_half_fov"), tan_half_fov);
    f.Uniform1f(f.GetUniformLocation(id, "min_near"), min_near);
    const GLint step_at = f.GetUniformLocation(id, "step");
    // A step over the rays (a run of BC_CLUSTER_RUN rays an invocation, 64
    // a work group, in rows: render_secondary_common.glsl's dispatch_item)
    // or over the facets (one work group); each sees the last one's writes.
    auto run = [&](int step) {
        f.Uniform1i(step_at, step);
        const bool per_facet = step == BC_CLUSTER_STEP_SETUP || step == BC_CLUSTER_STEP_PICK ||
                               step == BC_CLUSTER_STEP_UPDATE || step == BC_CLUSTER_STEP_VIEW_BEGIN ||
                               step == BC_CLUSTER_STEP_VIEW_FINISH;
        const std::size_t runs = (n + BC_CLUSTER_RUN - 1) / BC_CLUSTER_RUN;
        gl::dispatch_in_rows(f, per_facet ? 1 : (runs + 63) / 64);
        f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    };
    run(BC_CLUSTER_STEP_CLASSIFY);
    run(BC_CLUSTER_STEP_SETUP);
    run(BC_CLUSTER_STEP_START_KEY);
    run(BC_CLUSTER_STEP_START_RAY);
    run(BC_CLUSTER_STEP_PICK);
    for (int c = 1; c < BC_CLUSTERS_PER_FACET_MAX; ++c) {
        run(BC_CLUSTER_STEP_FAR_DISTANCE);
        run(BC_CLUSTER_STEP_FAR_RAY);
        run(BC_CLUSTER_STEP_PICK);
    }
    for (int it = 0; it < std::max(options.max_iterations, 1); ++it) {
        run(BC_CLUSTER_STEP_ASSIGN);
        run(BC_CLUSTER_STEP_UPDATE);
    }
    run(BC_CLUSTER_STEP_FINAL_SUMS);
    if (views != nullptr) {
        run(BC_CLUSTER_STEP_VIEW_BEGIN);
        run(BC_CLUSTER_STEP_VIEW_ADD);
        run(BC_CLUSTER_STEP_VIEW_FINISH);
    }
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    f.UseProgram(0);
    gl::check_gl(f, "dof-secondary: the clustering passes");

    ClusterState state{};
    state_->read(&state, sizeof state);
    std::vector<std::uint32_t> labels(n);
    labels_->read(labels.data(), n * sizeof(std::uint32_t));
    if (views != nullptr) {
        views_->read(fits.data(), fits.size() * sizeof(ClusterViewFit));
        views->along_mean.clear();
        views->along_normal.clear();
    }
    // The clusters as the host numbers them: by facet, then local index, the empty ones dropped.
    std::array<int, BC_CLUSTER_SLOTS> global{};
    for (int facet = 0; facet < BC_CLUSTER_FACETS; ++facet) {
        const int k = state.facet_k[facet];
        if (k == 0) continue;
        out.iterations += state.facet_iterations[facet];
        if ((state.facet_flags[facet] & BC_CLUSTER_SETTLED) == 0u) ++out.unsettled_facets;
        for (int c = 0; c < k; ++c) {
            const int slot = facet * BC_CLUSTERS_PER_FACET_MAX + c;
            K::ClusterSums s = K::cluster_sums_empty(state.position_scale);
            for (int a = 0; a < 3; ++a) {
                s.position_hi[a] = state.sum_hi[6 * slot + a];
                s.position_lo[a] = state.sum_lo[6 * slot + a];
                s.direction_hi[a] = state.sum_hi[6 * slot + 3 + a];
                s.direction_lo[a] = state.sum_lo[6 * slot + 3 + a];
            }
            s.count = state.sum_count[slot];
            s.unfit = state.sum_unfit[slot];
            global[static_cast<std::size_t>(slot)] = static_cast<int>(out.clusters.size());
            if (s.count + s.unfit == 0u) continue;
            out.clusters.push_back({facet, s});
            if (views != nullptr) {
                views->along_mean.push_back(view_of(fits[static_cast<std::size_t>(2 * slot)]));
                views->along_normal.push_back(view_of(fits[static_cast<std::size_t>(2 * slot + 1)]));
            }
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t facet = labels[i] >> 2u, local = labels[i] & 3u;
        if (facet >= BC_CLUSTER_FACETS || local >= BC_CLUSTERS_PER_FACET_MAX)
            throw gl::GlError("gl: the clustering passes left ray " + std::to_string(i) + " without a cluster");
        out.cluster_of[i] = global[facet * BC_CLUSTERS_PER_FACET_MAX + local];
    }
    return out;
}

}  // namespace blurcull::frontend
