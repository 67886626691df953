// dof-secondary's clustering on the GPU: cluster_reflector_pixels
// (include/blurcull/secondary_clusters.hpp) as compute passes
// (shaders/render_secondary_cluster.comp), one dispatch per step, on the
// kernel's shared text. Its choices are minima and maxima and its sums
// exact, so it gives the host's clusters bit for bit where the GPU rounds
// as the host does (llvmpipe; the test asserts it). docs/secondary-rays.md,
// "Clusters on the GPU".
#pragma once

#include "render/gl/gl_context.hpp"

#include <blurcull/secondary_clusters.hpp>

#include <glm/glm.hpp>

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
    // three more passes, read back with the rest).
    Clustering<float> cluster(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& directions,
                              const ClusterOptions& options = {}, float tan_half_fov = 1.0f, float min_near = 1e-3f,
                              ClusterViews<float>* views = nullptr) const;

    // The most rays cluster() takes: as many as the GL's largest shader
    // storage block holds of its per-ray points (32 bytes a ray; llvmpipe
    // says 128 MiB, 4.2 million; NVIDIA's drivers commonly 2 GiB). More throw;
    // GlDofSecondary clusters them on the host instead.
    std::size_t max_rays() const;

    // The last cluster() call's rays on the GPU: per ray its position and
    // direction (vec4 each), for GlLayerTracer::queue_bounce_gathered.
    // Throws gl::GlError before the first call.
    const gl::Buffer& points_buffer() const;

private:
    const gl::HeadlessContext* context_;
    const gl::Functions* gl_;
    std::unique_ptr<gl::Program> program_;
    mutable std::optional<gl::Buffer> points_, labels_, state_, views_;
};

}  // namespace blurcull::frontend
