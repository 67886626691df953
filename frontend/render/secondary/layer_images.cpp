#include "render/secondary/layer_images.hpp"

#include "render/common/bounce_shared.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace blurcull::frontend {
namespace {
constexpr float no_surface = std::numeric_limits<float>::infinity();
}  // namespace

std::vector<float> cluster_origin_depth(const kernelf::LayerView& view, const std::vector<glm::vec3>& origins) {
    std::vector<float> depth(static_cast<std::size_t>(view.size) * view.size, no_surface);
    for (const glm::vec3& origin : origins) {
        const glm::vec3 p = kernelf::layer_project(view, origin);
        if (!(p.z > 0.0f)) continue;
        const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
        if (x < 0 || y < 0 || x >= view.size || y >= view.size) continue;
        float& d = depth[static_cast<std::size_t>(y) * view.size + x];
        d = std::min(d, p.z);
    }
    for (float& d : depth)
        if (d == no_surface) d = -no_surface;
    return depth;
}

LayerImages build_layer_images(const WorldTriangles& triangles, const kernelf::LayerView& view, int layers,
                               const ClusterCulls& culls, LayerStats& stats) {
    LayerImages images;
    images.size = view.size;
    images.layers = layers;
    images.depth.assign(static_cast<std::size_t>(layers) * view.size * view.size, no_surface);
    images.triangle.assign(images.depth.size(), 0);
    const std::size_t plane = static_cast<std::size_t>(view.size) * view.size;
    const std::vector<float> cluster_depth = cluster_origin_depth(view, culls.origins);
    for (std::size_t t = 0; t < triangles.vertices.size(); ++t) {
        if (kernelf::bc_dot3(triangles.normals[t], view.forward) > culls.normal_threshold) {
            ++stats.culled_normal;
            continue;
        }
        const bool own = culls.own[t] != 0;
        const auto id = static_cast<std::uint32_t>(t);
        const bool in_front_of_near = rasterize_into_view(view, triangles.vertices[t], [&](int x, int y, float z) {
            ++stats.fragments;
            const std::size_t texel = static_cast<std::size_t>(y) * view.size + x;
            if (own || z <= cluster_depth[texel]) {
                ++stats.culled_in_front;
                return;
            }
            // Insertion into the texel's sorted list of the nearest `layers` depths.
            if (!(z < images.depth[texel + plane * static_cast<std::size_t>(layers - 1)])) {
                ++stats.dropped;
                return;
            }
            if (images.depth[texel + plane * static_cast<std::size_t>(layers - 1)] != no_surface) ++stats.dropped;
            int l = layers - 1;
            while (l > 0 && images.depth[texel + plane * static_cast<std::size_t>(l - 1)] > z) {
                images.depth[texel + plane * static_cast<std::size_t>(l)] =
                    images.depth[texel + plane * static_cast<std::size_t>(l - 1)];
                images.triangle[texel + plane * static_cast<std::size_t>(l)] =
                    images.triangle[texel + plane * static_cast<std::size_t>(l - 1)];
                --l;
            }
            images.depth[texel + plane * static_cast<std::size_t>(l)] = z;
            images.triangle[texel + plane * static_cast<std::size_t>(l)] = id;
        });
        if (!in_front_of_near) ++stats.culled_near;
    }
    return images;
}

DepthPyramid::DepthPyramid(const LayerImages& images) {
    Level base{images.size, std::vector<float>(static_cast<std::size_t>(images.size) * images.size, no_surface),
               std::vector<float>(static_cast<std::size_t>(images.size) * images.size, -no_surface)};
    for (int l = 0; l < images.layers; ++l) {
        for (int y = 0; y < images.size; ++y) {
            for (int x = 0; x < images.size; ++x) {
                const float d = images.depth[images.index(l, x, y)];
                if (d == no_surface) continue;
                const std::size_t texel = static_cast<std::size_t>(y) * images.size + x;
                base.lo[texel] = std::min(base.lo[texel], d);
                base.hi[texel] = std::max(base.hi[texel], d);
            }
        }
    }
    levels_.push_back(std::move(base));
    while (levels_.back().size > 1) {
        const Level& fine = levels_.back();
        const int size = (fine.size + 1) / 2;
        Level coarse{size, std::vector<float>(static_cast<std::size_t>(size) * size, no_surface),
                     std::vector<float>(static_cast<std::size_t>(size) * size, -no_surface)};
        for (int y = 0; y < fine.size; ++y) {
            for (int x = 0; x < fine.size; ++x) {
                const std::size_t from = static_cast<std::size_t>(y) * fine.size + x;
                const std::size_t to = static_cast<std::size_t>(y / 2) * size + x / 2;
                coarse.lo[to] = std::min(coarse.lo[to], fine.lo[from]);
                coarse.hi[to] = std::max(coarse.hi[to], fine.hi[from]);
            }
        }
        levels_.push_back(std::move(coarse));
    }
}

DepthPyramid DepthPyramid::from_levels(int size, const std::vector<float>& lo_hi) {
    DepthPyramid pyramid;
    std::size_t at = 0;
    for (int level_size = size; level_size >= 1; level_size = (level_size + 1) / 2) {
        const std::size_t cells = static_cast<std::size_t>(level_size) * static_cast<std::size_t>(level_size);
        if (at + 2 * cells > lo_hi.size()) break;
        Level level{level_size, std::vector<float>(cells), std::vector<float>(cells)};
        for (std::size_t cell = 0; cell < cells; ++cell) {
            level.lo[cell] = lo_hi[at + 2 * cell];
            level.hi[cell] = lo_hi[at + 2 * cell + 1];
        }
        at += 2 * cells;
        pyramid.levels_.push_back(std::move(level));
        if (level_size == 1) break;
    }
    if (size < 1 || at != lo_hi.size() || pyramid.levels_.empty() || pyramid.levels_.back().size != 1)
        throw std::invalid_argument("DepthPyramid::from_levels: " + std::to_string(lo_hi.size()) +
                                    " values are not the levels of a " + std::to_string(size) + "^2 pyramid");
    return pyramid;
}

ClusterLayers build_cluster_layers_on_host(const WorldTriangles& triangles, const kernelf::LayerView& view,
                                           int layers, const ClusterCulls& culls, LayerStats& stats) {
    LayerImages images = build_layer_images(triangles, view, layers, culls, stats);
    DepthPyramid pyramid(images);
    return ClusterLayers{std::move(images), std::move(pyramid)};
}

glm::vec2 DepthPyramid::interval(int x0, int y0, int x1, int y1) const {
    const int level = bounce::bc_pyramid_level(x0, y0, x1, y1, static_cast<int>(levels_.size()));
    const Level& l = levels_[static_cast<std::size_t>(level)];
    glm::vec2 range(no_surface, -no_surface);
    for (int y = y0 >> level; y <= (y1 >> level); ++y) {
        for (int x = x0 >> level; x <= (x1 >> level); ++x) {
            const std::size_t cell = static_cast<std::size_t>(y) * l.size + x;
            range.x = std::min(range.x, l.lo[cell]);
            range.y = std::max(range.y, l.hi[cell]);
        }
    }
    return range;
}

}  // namespace blurcull::frontend
