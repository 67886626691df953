// The dof-secondary renderer, CPU build: depth of field seen through mirrors
// and glass (Xie, Sun and Wang, JCST 28(3) 2013; docs/secondary-rays.md,
// "The renderer"). Primary visibility is the stochastic rasterizer's
// per-sample winning triangles (render_cpu, culled, so motion blur and the
// thin lens are exact there); each sample on a reflector bounces once from
// its own lens point and hit point; the bounced rays are clustered by
// dodecahedron facet and position, each cluster gets a virtual view with a
// layered image, and the rays are traced through it in image space.
#pragma once

#include "render/common/render_types.hpp"
#include "render/secondary/layer_images.hpp"
#include "render/secondary/secondary_options.hpp"
#include "scene/scene.hpp"

#include <cstdint>

namespace blurcull::frontend {

// What a render did, for tests, the bench and the docs.
struct SecondaryStats {
    std::uint64_t reflector_samples = 0;   // primary samples on a mirror or dielectric
    std::uint64_t rays = 0;                // bounced rays
    std::uint64_t rays_image_space = 0;    // traced through a cluster's layers
    std::uint64_t rays_exact = 0;          // traced against the triangles (fallback or the exact mode)
    std::uint64_t rays_hit = 0;            // of all rays, those that found a surface
    std::uint64_t trace_steps = 0;         // texels visited by the image-space traces
    int clusters = 0;
    int clusters_refit_on_normal = 0;      // mean axis left a ray outside: fitted along the facet normal
    int clusters_split = 0;                // still some ray outside (FOV < 74.76 deg): those rays traced exactly
    int clusters_unusable = 0;             // empty or non-finite fit: every ray traced exactly
    LayerStats layers;                     // summed over the clusters
};

// Renders `scene` with settings.spp samples per pixel (the stochastic
// rasterizer's samples and culling) and one bounce on every mirror and
// dielectric sample. The bounced rays see the scene at mid-shutter (t = 0.5).
// A bounced ray that hits a surface gets its flat shade(); one that leaves
// the scene (or hits nothing in its cluster's layers) the environment.
// Deterministic for any thread count. Throws std::invalid_argument for bad
// settings or options, SceneError for a bad scene.
RenderResult render_dof_secondary(const Scene& scene, const RenderSettings& settings,
                                  const SecondaryOptions& options = {}, SecondaryStats* stats = nullptr);

}  // namespace blurcull::frontend
