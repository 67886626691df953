// A cluster's layered image (depth peeling on the CPU: the `layers` nearest
// surfaces per texel after the paper's three culls), and its min/max depth
// pyramid (docs/secondary-rays.md, "The renderer").
#pragma once

#include "render/secondary/exact_trace.hpp"

#include <blurcull/kernel.hpp>

#include <cstdint>
#include <vector>

namespace blurcull::frontend {

// What no ray of a cluster can reach, culled before peeling (Xie et al.
// section 3.4): (1) depths before the near plane at the cluster (the view's
// near, by clipping); (2) the cluster's own triangles and every surface
// nearer than the cluster's points at the same texel (the nearest of
// `origins` projecting there, cluster_origin_depth); (3) triangles whose winding
// normal lies inside the cone of the cluster's directions, shrunk by the
// cone's half-angle (n . forward > sin(half-angle)): every ray of the cluster
// meets them from behind.
struct ClusterCulls {
    std::vector<std::uint8_t> own;     // per triangle: hit by a sample of the cluster
    std::vector<glm::vec3> origins;    // the cluster's ray origins; empty: no in-front cull but `own`,
                                       // unless in_front (a ClusterBouncer holding the rays gathers them)
    bool in_front = false;             // the in-front cull is on
    float normal_threshold = 2.0f;     // cull when n . forward > this (2: never)
};

struct LayerStats {
    std::uint64_t fragments = 0;        // texels covered by triangles, before the culls
    std::uint64_t culled_near = 0;      // triangles wholly before the near plane
    std::uint64_t culled_in_front = 0;  // fragments of the cluster or in front of it
    std::uint64_t culled_normal = 0;    // triangles facing away from every ray of the cluster
    std::uint64_t dropped = 0;          // fragments beyond the last layer
};

struct LayerImages {
    int size = 0;
    int layers = 0;
    std::vector<float> depth;           // [layer][y][x] view depth, +infinity for none; sorted per texel
    std::vector<std::uint32_t> triangle;  // the surface of each depth
    std::size_t index(int layer, int x, int y) const {
        return (static_cast<std::size_t>(layer) * size + static_cast<std::size_t>(y)) * size + static_cast<std::size_t>(x);
    }
};

// Calls fragment(x, y, depth) for every texel centre of the view's image the
// triangle covers in front of the near plane (clipped there), with the
// perspective-correct view depth; returns false when it lies wholly before
// the near plane. Shared edges go to one triangle only (top-left rule).
template <class Fragment>
bool rasterize_into_view(const kernelf::LayerView& view, const std::array<glm::vec3, 3>& triangle,
                         const Fragment& fragment);

// The cluster's depth per texel: the nearest view depth of the cluster's
// points (its rays' origins) that project into the texel, -infinity where
// none does (nothing culled there).
std::vector<float> cluster_origin_depth(const kernelf::LayerView& view, const std::vector<glm::vec3>& origins);

// The layered image of `view` with the culls applied.
LayerImages build_layer_images(const WorldTriangles& triangles, const kernelf::LayerView& view, int layers,
                               const ClusterCulls& culls, LayerStats& stats);

// Min/max view depth over every layer, per texel, then halved level by level.
class DepthPyramid {
public:
    struct Level {
        int size;
        std::vector<float> lo, hi;  // [y][x]; lo = +infinity, hi = -infinity where no surface
    };
    explicit DepthPyramid(const LayerImages& images);
    // A pyramid built elsewhere (the GL build's compute pass): `lo_hi` holds
    // the levels of a base of `size` x `size` cells, finest first, each cell's
    // (lo, hi) in turn; the level sizes are (size + 1) / 2 down to 1. Throws
    // std::invalid_argument when the array has another length.
    static DepthPyramid from_levels(int size, const std::vector<float>& lo_hi);
    // The (min, max) depth of the surfaces in texel box [x0, x1] x [y0, y1]
    // (from at most 2 x 2 cells of the level that covers it); min > max when
    // there is none.
    glm::vec2 interval(int x0, int y0, int x1, int y1) const;
    const std::vector<Level>& levels() const { return levels_; }

private:
    DepthPyramid() = default;
    std::vector<Level> levels_;
};

// A cluster's layered image and the pyramid the interval clipping reads.
struct ClusterLayers {
    LayerImages images;
    DepthPyramid pyramid;
};

// The CPU build: build_layer_images, then DepthPyramid of the images.
ClusterLayers build_cluster_layers_on_host(const WorldTriangles& triangles, const kernelf::LayerView& view,
                                           int layers, const ClusterCulls& culls, LayerStats& stats);

}  // namespace blurcull::frontend

#include "render/secondary/layer_raster.inl"
