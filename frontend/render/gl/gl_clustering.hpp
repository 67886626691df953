// dof-secondary's clustering on the GPU: cluster_reflector_pixels
// (include/blurcull/secondary_clusters.hpp) as compute passes
// (shaders/render_secondary_cluster.comp), one dispatch per step, on the
// kernel's shared text. Its choices are minima and maxima and its sums
// exact, so it gives the host's clusters bit for bit where the GPU rounds
// as the host does (llvmpipe; the test asserts it). docs/secondary-rays.md,
// "Clusters on the GPU".
#pragma once

#include "render/common/bounce_shared.h"
#include "render/gl/gl_context.hpp"

#include <blurcull/secondary_clusters.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace blurcull::frontend {

class GlClustering {
public:
    // On `context` (kept alive by the caller; made current here, and by the
    // destructor to delete its program and buffers); compiles the pass.
    // cluster() runs on the current context: the caller makes `context`
    // current first. Throws gl::GlError with the compiler's log.
    explicit GlClustering(const gl::HeadlessContext& context);
    ~GlClustering();
    GlClustering(const GlClustering&) = delete;
    GlClustering& operator=(const GlClustering&) = delete;

    // cluster_reflector_pixels<float>(positions, directions, options): the
    // same Clustering, its passes on the GPU; waits for them once and reads
    // back each ray's cluster and the 36 sums. With `views`, each cluster's
    // two views too (fit_cluster_views's with tan_half_fov and min_near:
    // three more passes, read back with the rest). With `keys` (one per
    // ray, the rays in pixel order), group() may follow. Without
    // `read_labels` the rays' clusters stay on the GPU (cluster_of empty;
    // cluster_of() reads them). With `on_gpu` (at least 32 bytes a ray) the
    // same rays are already on the GPU in points_buffer()'s layout with the
    // keys' words (GlSecondaryResolve's): copied there, not uploaded.
    Clustering<float> cluster(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& directions,
                              const ClusterOptions& options = {}, float tan_half_fov = 1.0f, float min_near = 1e-3f,
                              ClusterViews<float>* views = nullptr, const std::vector<RayGroupKey>* keys = nullptr,
                              bool read_labels = true, const gl::Buffer* on_gpu = nullptr) const;

    // The last cluster()'s Clustering::cluster_of, read back (4 bytes a ray).
    std::vector<int> cluster_of() const;

    // After cluster() with keys, on the GPU and without a wait: each
    // cluster's rays sorted into its groups (one pixel's rays in one lens
    // part: the host's cluster_rays), its own triangles (a bit each of
    // `triangles`) and its normal cone's threshold for its view's forward
    // axis `forwards[j]` (cluster_culls' with `cull_normals`),
    // render_secondary_group.comp. False, with nothing done, where it
    // cannot: no keys, a forward per cluster missing, or every cluster's
    // own bits past a storage block; the host groups them then.
    bool group(const std::vector<glm::vec3>& forwards, bool cull_normals, std::size_t triangles) const;

    // Where group() left cluster j's pieces: byte offsets for
    // gl::copy_buffer into a cluster's passes.
    struct GroupedCluster {
        std::size_t rays = 0;                // its rays: its list's length, and the most groups
        std::size_t list_offset = 0;         // into lists_buffer(): its rays, as points of points_buffer()
        std::size_t pairs_offset = 0;        // into pairs_buffer(): its groups' (begin, end) in its list
        std::size_t group_count_offset = 0;  // into slots_buffer(): how many groups (a uint)
        std::size_t threshold_offset = 0;    // into slots_buffer(): its normal threshold (a float)
        std::size_t own_offset = 0;          // into own_buffer(): its own triangles' bits,
        std::size_t own_bytes = 0;           // GlLayerBuilder's layout
    };
    GroupedCluster grouped(std::size_t cluster) const;
    const gl::Buffer& lists_buffer() const;
    const gl::Buffer& pairs_buffer() const;
    const gl::Buffer& slots_buffer() const;
    const gl::Buffer& own_buffer() const;

    // The most rays cluster() takes: as many as the GL's largest shader
    // storage block holds of its per-ray points (32 bytes a ray; llvmpipe
    // says 128 MiB, 4.2 million; NVIDIA's drivers commonly 2 GiB). More throw;
    // GlDofSecondary clusters them on the host instead.
    std::size_t max_rays() const;

    // The last cluster() call's rays on the GPU: per ray its position and
    // direction (vec4 each; their w the keys' words, or 0),
    // for GlLayerTracer::queue_bounce_gathered.
    // Throws gl::GlError before the first call.
    const gl::Buffer& points_buffer() const;

private:
    const gl::HeadlessContext* context_;
    const gl::Functions* gl_;
    std::unique_ptr<gl::Program> program_, group_program_;
    mutable std::optional<gl::Buffer> points_, labels_, state_, views_;
    // group()'s: ClusterSlotGroups per slot, the lists, the pairs (and scratch), the own bits.
    mutable std::optional<gl::Buffer> slots_, lists_, pairs_, own_;
    // The last cluster()'s rays, whether they came with keys, each
    // cluster's slot, and each slot's rays.
    mutable std::size_t rays_ = 0, runs_ = 0;  // and its pixels' runs of rays
    mutable bool keyed_ = false;
    mutable std::vector<int> slot_of_cluster_, cluster_of_slot_;  // -1: an empty slot
    mutable std::vector<std::uint32_t> slot_rays_;
    mutable std::size_t own_words_ = 0;  // group()'s, per slot
};

}  // namespace blurcull::frontend
