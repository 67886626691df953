// rasterize_into_view (layer_images.hpp): a triangle clipped at the view's
// near plane, projected with the kernel's layer_image, scanned over texel
// centres with edge functions; 1 / depth is linear on the image. The
// arithmetic is render/common/layer_raster_shared.h's, which the GL build's
// passes run too.
#pragma once

#include "render/common/layer_raster_shared.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace blurcull::frontend {
namespace layer_detail {

// Sutherland-Hodgman against depth >= near; view coordinates (right, up, forward).
inline int clip_near(const std::array<glm::vec3, 3>& in, float near, std::array<glm::vec3, 4>& out) {
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 a = in[static_cast<std::size_t>(i)], b = in[static_cast<std::size_t>((i + 1) % 3)];
        const bool a_in = a.z >= near, b_in = b.z >= near;
        if (a_in) out[static_cast<std::size_t>(count++)] = a;
        if (a_in != b_in) out[static_cast<std::size_t>(count++)] = layer_raster::bc_raster_near_crossing(a, b, near);
    }
    return count;
}

// An edge owns the texel centres on it when it is a top or left edge of the
// counter-clockwise triangle.
inline bool owns_edge(glm::vec2 a, glm::vec2 b) { return (a.y == b.y && b.x < a.x) || b.y > a.y; }

template <class Fragment>
void scan_triangle(int size, glm::vec3 a, glm::vec3 b, glm::vec3 c, const Fragment& fragment) {
    // (image x, image y, depth); orient counter-clockwise.
    float area = layer_raster::bc_raster_edge(glm::vec2(a), glm::vec2(b), glm::vec2(c));
    if (!(std::abs(area) > 0.0f)) return;
    if (area < 0.0f) {
        std::swap(b, c);
        area = -area;
    }
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}) - 0.5f)));
    const int x1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}) - 0.5f)));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}) - 0.5f)));
    const int y1 = std::min(size - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}) - 0.5f)));
    const glm::vec2 pa(a), pb(b), pc(c);
    const bool own_ab = owns_edge(pa, pb), own_bc = owns_edge(pb, pc), own_ca = owns_edge(pc, pa);
    const auto edge = layer_raster::bc_raster_edge;
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
            const float wa = edge(pb, pc, centre), wb = edge(pc, pa, centre), wc = edge(pa, pb, centre);
            if (wa < 0.0f || wb < 0.0f || wc < 0.0f) continue;
            if ((wa == 0.0f && !own_bc) || (wb == 0.0f && !own_ca) || (wc == 0.0f && !own_ab)) continue;
            fragment(x, y, layer_raster::bc_raster_depth(a, b, c, area, centre));
        }
    }
}

}  // namespace layer_detail

template <class Fragment>
bool rasterize_into_view(const kernelf::LayerView& view, const std::array<glm::vec3, 3>& triangle,
                         const Fragment& fragment) {
    std::array<glm::vec3, 3> local;
    for (std::size_t k = 0; k < 3; ++k) local[k] = layer_raster::bc_raster_view_point(view, triangle[k]);
    std::array<glm::vec3, 4> clipped;
    const int count = layer_detail::clip_near(local, view.near, clipped);
    if (count < 3) return false;
    std::array<glm::vec3, 4> image;
    for (int k = 0; k < count; ++k)
        image[static_cast<std::size_t>(k)] = layer_raster::bc_raster_image_point(view, clipped[static_cast<std::size_t>(k)]);
    for (int k = 1; k + 1 < count; ++k)
        layer_detail::scan_triangle(view.size, image[0], image[static_cast<std::size_t>(k)],
                                    image[static_cast<std::size_t>(k + 1)], fragment);
    return true;
}

}  // namespace blurcull::frontend
