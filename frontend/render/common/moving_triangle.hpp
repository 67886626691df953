// A scene triangle as the kernel sees it: clip-space vertices at both shutter
// ends and their circles of confusion (conventions in camera_model.hpp).
#pragma once

#include "render/common/camera_model.hpp"
#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>

#include <cstddef>
#include <vector>

namespace blurcull::frontend {

// Sets slot j (vertex i at shutter end k: j = i + 3k) of `tri` from a
// view-space position: clip (k_x x, k_y y, w = -z) and the CoC at w.
template <class Real>
void set_clip_vertex(const CameraModel& model, const glm::vec<3, Real, glm::defaultp>& view,
                     typename blurcull::kernel<Real>::MovingTriangle& tri, int slot) {
    using K = blurcull::kernel<Real>;
    const Real w = -view.z;
    tri.p[slot] = typename K::vec3(static_cast<Real>(model.k_x) * view.x, static_cast<Real>(model.k_y) * view.y, w);
    tri.c[slot] = typename K::vec2(static_cast<Real>(model.a_x) + static_cast<Real>(model.b_x) * w,
                                   static_cast<Real>(model.a_y) + static_cast<Real>(model.b_y) * w);
}

// p[i + 3k] = clip (x, y, w) of vertex i at shutter end k (0 open, 1 close),
// c[i + 3k] = (c_x, c_y) at that depth. Computed in Real from the float scene
// and the camera model's float constants, so kernel<double> gets the
// double-precision image of the same float model. The caller guarantees the
// triangle and its vertex indices are valid (validate_scene).
template <class Real>
typename blurcull::kernel<Real>::MovingTriangle make_moving_triangle(const Scene& scene, const CameraModel& model,
                                                                     std::size_t triangle) {
    using K = blurcull::kernel<Real>;
    using vec3 = typename K::vec3;
    using vec4 = glm::vec<4, Real, glm::defaultp>;
    using mat4 = glm::mat<4, 4, Real, glm::defaultp>;
    const mat4 views[2] = {mat4(model.view_open), mat4(model.view_close)};
    const std::vector<glm::vec3>* positions[2] = {&scene.position_open, &scene.position_close};
    typename K::MovingTriangle result{};
    for (int end = 0; end < 2; ++end) {
        for (int i = 0; i < 3; ++i) {
            const glm::vec3& world = (*positions[end])[scene.triangles[triangle][i]];
            const vec4 view = views[end] * vec4(vec3(world), Real(1));
            set_clip_vertex<Real>(model, vec3(view), result, i + 3 * end);
        }
    }
    return result;
}

}  // namespace blurcull::frontend
