#include "render/gl/gl_clustering.hpp"

#include "render/gl/gl_cluster_shared.h"
#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

namespace blurcull::frontend {

using gpu::ClusterSlotGroups;
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

// The bits of a float as a word (the points' w carry the keys' words).
float float_of_bits(std::uint32_t bits) {
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

// render_secondary_group.comp's bc_float_order of a float.
std::uint32_t float_order(float x) {
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

}  // namespace

GlClustering::GlClustering(const gl::HeadlessContext& context)
    : context_((context.make_current(), &context)),
      gl_(&context.gl()),
      program_(std::make_unique<gl::Program>(
          context.gl(), std::vector<gl::ShaderStage>{gl::shader_stage(GL_COMPUTE_SHADER, "render_secondary_cluster.comp",
                                                                      gl::Prelude::clusters)})),
      group_program_(std::make_unique<gl::Program>(
          context.gl(), std::vector<gl::ShaderStage>{gl::shader_stage(GL_COMPUTE_SHADER, "render_secondary_group.comp",
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
                                        float tan_half_fov, float min_near, ClusterViews<float>* views,
                                        const std::vector<RayGroupKey>* keys, bool read_labels,
                                        const gl::Buffer* on_gpu) const {
    using K = kernelf;
    Clustering<float> out;
    keyed_ = false;  // until this call's rays are on the GPU
    rays_ = 0;
    slot_of_cluster_.clear();
    const std::size_t n = std::min(positions.size(), directions.size());
    out.cluster_of.assign(read_labels ? n : 0, -1);
    if (n == 0) return out;
    if (n > max_rays() || n > 0xffffffffu - 64u)
        throw gl::GlError("gl: " + std::to_string(n) + " rays to cluster, more than a storage block of the GL (" +
                          std::to_string(max_rays()) + ") or a 32-bit ray index holds");
    const gl::Functions& f = *gl_;
    const bool keyed = keys != nullptr && keys->size() == n;
    rays_ = n;
    // The pixels' runs (group() dispatches one invocation each).
    runs_ = 0;
    for (std::size_t i = 0; keyed && i < n; ++i)
        runs_ += i == 0 || ((*keys)[i].pixel_part >> BC_GROUP_PART_BITS) != ((*keys)[i - 1].pixel_part >> BC_GROUP_PART_BITS);
    // Each w holds a key's word as its bits (group() reads them as words;
    // no pass does arithmetic on them).
    if (on_gpu != nullptr && on_gpu->size() >= 2 * n * sizeof(glm::vec4)) {
        // The same rays already there in this layout: copied on the GPU, nothing uploaded.
        gl::copy_buffer(f, *on_gpu, 0, gl::reserve_storage(f, points_, 2 * n * sizeof(glm::vec4)), 0,
                        2 * n * sizeof(glm::vec4));
    } else {
        std::vector<glm::vec4> points(2 * n);
        for (std::size_t i = 0; i < n; ++i) {
            points[2 * i] = glm::vec4(positions[i], float_of_bits(keyed ? (*keys)[i].triangle : 0u));
            points[2 * i + 1] = glm::vec4(directions[i], float_of_bits(keyed ? (*keys)[i].pixel_part : 0u));
        }
        gl::reserve_storage(f, points_, points.size() * sizeof(glm::vec4), points.data());
    }
    points_->bind_base(BC_GL_CLUSTER_POINTS_BINDING);
    const ClusterState initial{};
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
    if (views != nullptr) {
        views_->read(fits.data(), fits.size() * sizeof(ClusterViewFit));
        views->along_mean.clear();
        views->along_normal.clear();
    }
    // The clusters as the host numbers them: by facet, then local index, the empty ones dropped.
    cluster_of_slot_.assign(BC_CLUSTER_SLOTS, -1);
    slot_of_cluster_.clear();
    slot_rays_.assign(BC_CLUSTER_SLOTS, 0u);
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
            if (s.count + s.unfit == 0u) continue;
            cluster_of_slot_[static_cast<std::size_t>(slot)] = static_cast<int>(out.clusters.size());
            out.clusters.push_back({facet, s});
            slot_of_cluster_.push_back(slot);
            slot_rays_[static_cast<std::size_t>(slot)] = s.count + s.unfit;
            if (views != nullptr) {
                views->along_mean.push_back(view_of(fits[static_cast<std::size_t>(2 * slot)]));
                views->along_normal.push_back(view_of(fits[static_cast<std::size_t>(2 * slot + 1)]));
            }
        }
    }
    keyed_ = keyed;
    if (read_labels) out.cluster_of = cluster_of();
    return out;
}

std::vector<int> GlClustering::cluster_of() const {
    std::vector<std::uint32_t> labels(rays_);
    if (rays_ > 0) labels_->read(labels.data(), rays_ * sizeof(std::uint32_t));
    std::vector<int> out(rays_, -1);
    for (std::size_t i = 0; i < rays_; ++i) {
        const std::uint32_t facet = labels[i] >> 2u, local = labels[i] & 3u;
        const int cluster = facet < BC_CLUSTER_FACETS && local < BC_CLUSTERS_PER_FACET_MAX
                                ? cluster_of_slot_[facet * BC_CLUSTERS_PER_FACET_MAX + local]
                                : -1;
        if (cluster < 0)
            throw gl::GlError("gl: the clustering passes left ray " + std::to_string(i) + " without a cluster");
        out[i] = cluster;
    }
    return out;
}

bool GlClustering::group(const std::vector<glm::vec3>& forwards, bool cull_normals, std::size_t triangles) const {
    if (!keyed_ || !points_ || forwards.size() != slot_of_cluster_.size()) return false;
    const std::size_t block = max_rays() * 2 * sizeof(glm::vec4);
    const std::size_t own_words = (triangles + 31) / 32;
    if (own_words * BC_CLUSTER_SLOTS * sizeof(std::uint32_t) > block || triangles > 0xffffffffu) return false;
    const gl::Functions& f = *gl_;
    own_words_ = own_words;
    // Each slot's list from its first ray, in slot order; its forward axis
    // the cluster's; its least cosine 1, a cone of one direction, so far.
    std::vector<ClusterSlotGroups> slots(BC_CLUSTER_SLOTS, ClusterSlotGroups{});
    std::uint32_t first = 0;
    for (std::size_t slot = 0; slot < slots.size(); ++slot) {
        slots[slot].first = first;
        slots[slot].rays = slot_rays_[slot];
        slots[slot].cos_key = float_order(1.0f);
        slots[slot].normal_threshold = 2.0f;
        first += slot_rays_[slot];
    }
    for (std::size_t j = 0; j < forwards.size(); ++j) {
        ClusterSlotGroups& slot = slots[static_cast<std::size_t>(slot_of_cluster_[j])];
        for (int a = 0; a < 3; ++a) slot.forward[a] = forwards[j][a];
    }
    const std::size_t n = rays_;
    gl::reserve_storage(f, slots_, slots.size() * sizeof(ClusterSlotGroups), slots.data())
        .bind_base(BC_GL_GROUP_SLOTS_BINDING);
    gl::reserve_storage(f, lists_, n * sizeof(std::uint32_t)).bind_base(BC_GL_GROUP_LISTS_BINDING);
    // Pairs, scratch, the runs' count (0) and first rays: 5 n + 1 words.
    const std::uint32_t no_runs = 0;
    const gl::Buffer& pairs = gl::reserve_storage(f, pairs_, (5 * n + 1) * sizeof(std::uint32_t));
    pairs.write(&no_runs, sizeof no_runs, 4 * n * sizeof(std::uint32_t));
    pairs.bind_base(BC_GL_GROUP_PAIRS_BINDING);
    const std::vector<std::uint32_t> no_bits(own_words * BC_CLUSTER_SLOTS, 0u);
    gl::reserve_storage(f, own_, no_bits.size() * sizeof(std::uint32_t), no_bits.data())
        .bind_base(BC_GL_GROUP_OWN_BINDING);
    points_->bind_base(BC_GL_CLUSTER_POINTS_BINDING);
    labels_->bind_base(BC_GL_CLUSTER_LABELS_BINDING);

    const GLuint id = group_program_->id();
    f.UseProgram(id);
    f.Uniform1ui(f.GetUniformLocation(id, "rays"), static_cast<GLuint>(n));
    f.Uniform1ui(f.GetUniformLocation(id, "own_words"), static_cast<GLuint>(own_words));
    f.Uniform1ui(f.GetUniformLocation(id, "triangles"), static_cast<GLuint>(triangles));
    f.Uniform1i(f.GetUniformLocation(id, "cull_normals"), cull_normals ? 1 : 0);
    const GLint step = f.GetUniformLocation(id, "step");
    f.Uniform1i(step, BC_GROUP_STEP_RAYS);
    gl::dispatch_in_rows(f, (n + 63) / 64);
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    f.Uniform1i(step, BC_GROUP_STEP_RUNS);
    gl::dispatch_in_rows(f, (runs_ + 63) / 64);
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    f.Uniform1i(step, BC_GROUP_STEP_THRESHOLDS);
    f.DispatchCompute(1, 1, 1);
    // The cluster passes read the lists and pairs, and copy from every buffer.
    f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    f.UseProgram(0);
    return true;
}

GlClustering::GroupedCluster GlClustering::grouped(std::size_t cluster) const {
    if (cluster >= slot_of_cluster_.size() || !slots_)
        throw gl::GlError("gl: cluster " + std::to_string(cluster) + " was not grouped on the GPU");
    const auto slot = static_cast<std::size_t>(slot_of_cluster_[cluster]);
    std::size_t first = 0;
    for (std::size_t s = 0; s < slot; ++s) first += slot_rays_[s];
    GroupedCluster g;
    g.rays = slot_rays_[slot];
    g.list_offset = first * sizeof(std::uint32_t);
    g.pairs_offset = 2 * first * sizeof(std::uint32_t);
    g.group_count_offset = slot * sizeof(ClusterSlotGroups) + offsetof(ClusterSlotGroups, groups);
    g.threshold_offset = slot * sizeof(ClusterSlotGroups) + offsetof(ClusterSlotGroups, normal_threshold);
    g.own_offset = slot * own_words_ * sizeof(std::uint32_t);
    g.own_bytes = own_words_ * sizeof(std::uint32_t);
    return g;
}

namespace {
const gl::Buffer& grouped_buffer(const std::optional<gl::Buffer>& buffer) {
    if (!buffer) throw gl::GlError("gl: no rays grouped yet");
    return *buffer;
}
}  // namespace

const gl::Buffer& GlClustering::lists_buffer() const { return grouped_buffer(lists_); }
const gl::Buffer& GlClustering::pairs_buffer() const { return grouped_buffer(pairs_); }
const gl::Buffer& GlClustering::slots_buffer() const { return grouped_buffer(slots_); }
const gl::Buffer& GlClustering::own_buffer() const { return grouped_buffer(own_); }

}  // namespace blurcull::frontend
