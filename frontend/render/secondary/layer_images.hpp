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
// nearer than the cluster's points at the same texel (`cluster_depth`,
// -infinity where no point of the cluster projects); (3) triangles whose winding
// normal lies inside the cone of the cluster's directions, shrunk by the
// cone's half-angle (n . forward > sin(half-angle)): every ray of the cluster
// meets them from behind.
struct ClusterCulls {
    std::vector<std::uint8_t> own;     // per triangle: hit by a sample of the cluster
    std::vector<float> cluster_depth;  // size x size
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
    explicit DepthPyramid(const LayerImages& images);
    // The (min, max) depth of the surfaces in texel box [x0, x1] x [y0, y1]
    // (from at most 2 x 2 cells of the level that covers it); min > max when
    // there is none.
    glm::vec2 interval(int x0, int y0, int x1, int y1) const;

private:
    struct Level {
        int size;
        std::vector<float> lo, hi;
    };
    std::vector<Level> levels_;
};

}  // namespace blurcull::frontend

#include "render/secondary/layer_raster.inl"
