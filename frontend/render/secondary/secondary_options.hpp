// The settings of the dof-secondary renderer (docs/secondary-rays.md, "The
// renderer"): the paper's parameters with its defaults (Xie, Sun and Wang,
// JCST 28(3) 2013: 8 layers, 512 x 512, 80 degrees, the lens in 4 parts).
#pragma once

#include <stdexcept>
#include <string>

namespace blurcull::frontend {

enum class SecondaryBounces {
    image_space,       // the paper's method: clusters, virtual views, layered images
    exact,             // the reference: every bounce traced against every triangle, same samples and shading
    environment_only,  // the primary-only image: every bounce sees the environment
};

// Where the gl backend builds the clusters' layered images and pyramids: the
// GL passes, which also clip, trace and pick the hits' surfaces where the
// layers are (the product, app/gl_dof_secondary.hpp); the GL passes read
// back, then the host's clipping and surfaces around the GL trace pass (the
// previous build, kept to measure against: `--layer-images gl-readback`); or
// the CPU build's code (build_cluster_layers_on_host, the reference;
// `--layer-images host`).
enum class LayerImagesOn { gl, gl_readback, host };

struct SecondaryOptions {
    int layers = 8;              // depth-peeled layers per cluster view, 1 .. 8 (BC_LAYERS_MAX)
    int clusters_per_facet = 3;  // k-means clusters per dodecahedron facet at most, 1 .. 3
    float fov_degrees = 80.0f;   // full field of view of a cluster's square virtual view, (0, 180)
    int layer_size = 512;        // texels per side of a cluster's layer images, 16 .. 4096
    int lens_parts = 4;          // 1, 4 or 16: a min/max depth interval per pixel and lens part
    int wanted_clusters = 24;    // clusters in all the cluster rule aims at (the paper: 20-30)
    // Slab thickness of a stored depth, as a fraction of the scene's bounding
    // diagonal (the thick-depth model of Lee et al.).
    float thickness_fraction = 0.01f;
    // Cull triangles whose winding normal faces away from every ray of a
    // cluster (the paper's third measure; assumes outward-wound surfaces).
    bool cull_normals = true;
    // Cull surfaces nearer than the cluster's own surface at the same texel
    // (the paper's second measure; the cluster's own triangles are culled always).
    bool cull_in_front = true;
    // How the bounced rays are traced (image_space: the method).
    SecondaryBounces bounces = SecondaryBounces::image_space;
    // Shutter slices of the image-space bounce, 1 .. 64, or 0 for auto
    // (bounce_time_slices): a bounced ray sees the scene at the middle of
    // its sample's slice, each slice with its own clusters and layers.
    int time_slices = 0;
};

// The slices `auto` gives a scene that moves in world space (one that does
// not, or whose camera alone moves, gets 1: its layers hold every time).
inline constexpr int auto_time_slices_moving = 4;

// Throws std::invalid_argument with one line naming the setting when an
// option is out of range.
inline void validate_secondary_options(const SecondaryOptions& options) {
    auto fail = [](const std::string& what) { throw std::invalid_argument("dof-secondary: " + what); };
    if (options.layers < 1 || options.layers > 8)
        fail("secondary layers must be in [1, 8], got " + std::to_string(options.layers));
    if (options.clusters_per_facet < 1 || options.clusters_per_facet > 3)
        fail("clusters per facet must be in [1, 3], got " + std::to_string(options.clusters_per_facet));
    if (!(options.fov_degrees > 0.0f && options.fov_degrees < 180.0f))
        fail("secondary field of view must be in (0, 180) degrees, got " + std::to_string(options.fov_degrees));
    if (options.layer_size < 16 || options.layer_size > 4096)
        fail("layer size must be in [16, 4096] texels, got " + std::to_string(options.layer_size));
    if (options.lens_parts != 1 && options.lens_parts != 4 && options.lens_parts != 16)
        fail("lens parts must be 1, 4 or 16, got " + std::to_string(options.lens_parts));
    if (options.wanted_clusters < 1) fail("wanted clusters must be >= 1");
    if (!(options.thickness_fraction > 0.0f && options.thickness_fraction < 1.0f))
        fail("thickness fraction must be in (0, 1)");
    if (options.time_slices < 0 || options.time_slices > 64)
        fail("time slices must be in [1, 64] (or 0: auto), got " + std::to_string(options.time_slices));
}

}  // namespace blurcull::frontend
