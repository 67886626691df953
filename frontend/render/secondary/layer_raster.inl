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

// Every texel centre the image triangle (image x, image y, depth) covers,
// with its depth there: the scan of render_layers_raster.comp.
template <class Fragment>
void scan_triangle(int size, glm::vec3 a, glm::vec3 b, glm::vec3 c, const Fragment& fragment) {
    using namespace layer_raster;
    const RasterTriangle t = bc_raster_ccw(a, b, c);
    if (!(t.area > 0.0f)) return;
    const glm::ivec4 box = bc_raster_texel_box(t, size);
    const glm::bvec3 owns = bc_raster_owned_edges(t);
    for (int y = box.y; y <= box.w; ++y) {
        for (int x = box.x; x <= box.z; ++x) {
            const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
            if (bc_raster_covers(t, owns, centre)) fragment(x, y, bc_raster_depth(t.a, t.b, t.c, t.area, centre));
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
