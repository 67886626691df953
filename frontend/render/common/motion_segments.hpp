// Motion segments: a scene whose motion was sampled at K + 1 shutter times
// (Scene::position_at, --motion-segments K) renders each moving triangle as
// K linear pieces, piece k moving from the vertices at time k / K to those at
// (k + 1) / K and existing only in its window (the kernel's segment_window;
// docs/kernel.md, "Motion segments"). A backend tests a sample against a
// piece at the piece's local time segment_local_time(window, t), and only when
// segment_holds(window, t). K = 1 is the single piece [0, 1] per triangle:
// today's model, and the backends keep their K = 1 code path unchanged.
#pragma once

#include "render/common/camera_model.hpp"
#include "render/common/moving_triangle.hpp"
#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace blurcull::frontend {

// The scene's number of motion segments K: one more than its interior times.
inline int scene_motion_segments(const Scene& scene) { return static_cast<int>(scene.position_at.size()) + 1; }

// For a renderer that models one linear motion per triangle (gl, the
// interleave / interval / accum methods): throws std::invalid_argument with one
// line, "<who>: ...", when the scene carries more than one motion segment.
inline void refuse_motion_segments(const Scene& scene, const std::string& who) {
    const int segments = scene_motion_segments(scene);
    if (segments == 1) return;
    if (scene.motion_segments_auto)
        throw std::invalid_argument(who + ": the " + std::to_string(segments) +
                                    " motion segments --motion-segments auto chose are not supported here "
                                    "(drop_motion_segments, or load with motion_segments = 1)");
    throw std::invalid_argument(who + ": " + std::to_string(segments) +
                                " motion segments are not supported here (--motion-segments > 1 renders on the cpu "
                                "and embree backends, method stochastic)");
}

// The scene's K = 1 model: the interior times (Scene::position_at,
// Camera::view_at) dropped, each vertex moving linearly from open to close.
// Returns the number of segments the scene had. For the command, where the
// default --motion-segments auto meets a renderer that carries one motion
// per triangle: it warns and renders the chords instead of refusing.
inline int drop_motion_segments(Scene& scene) {
    const int segments = scene_motion_segments(scene);
    scene.position_at.clear();
    scene.camera.view_at.clear();
    scene.motion_segments_auto = false;
    return segments;
}

// The warning drop_motion_segments' callers print: one line naming `who`.
inline std::string dropped_motion_segments_warning(const std::string& who, int segments) {
    return who + " carries one linear motion per triangle: the " + std::to_string(segments) +
           " motion segments --motion-segments auto chose are not used (rotations move along their chords; the cpu "
           "and embree backends, method stochastic, follow them)";
}

// View-space position of `vertex` at time step `step` of K (0: shutter open,
// K: close, else the interior time step / K), computed in Real like
// make_moving_triangle: the interior view is Camera::view_at, or when the scene
// has none, the view-space position interpolated between the two ends' views.
template <class Real>
glm::vec<3, Real, glm::defaultp> step_view_position(const Scene& scene, const CameraModel& model, std::size_t vertex,
                                                    int step) {
    using vec3 = glm::vec<3, Real, glm::defaultp>;
    using vec4 = glm::vec<4, Real, glm::defaultp>;
    using mat4 = glm::mat<4, 4, Real, glm::defaultp>;
    const int segments = scene_motion_segments(scene);
    if (step <= 0) return vec3(mat4(model.view_open) * vec4(vec3(scene.position_open[vertex]), Real(1)));
    if (step >= segments) return vec3(mat4(model.view_close) * vec4(vec3(scene.position_close[vertex]), Real(1)));
    const vec4 world(vec3(scene.position_at[static_cast<std::size_t>(step - 1)][vertex]), Real(1));
    if (!scene.camera.view_at.empty()) return vec3(mat4(scene.camera.view_at[static_cast<std::size_t>(step - 1)]) * world);
    const Real t = Real(step) / Real(segments);
    return (Real(1) - t) * vec3(mat4(model.view_open) * world) + t * vec3(mat4(model.view_close) * world);
}

// One piece of a triangle: segment `segment` of `segments` (window
// kernel::segment_window(segment, segments)); 0 of 1 is the whole shutter.
struct SegmentPiece {
    std::uint32_t source = 0;  // the scene triangle (its material, its id in the image)
    int segment = 0;
    int segments = 1;
};

// The pieces to render, grouped by window: first every triangle that needs
// no split, as one whole-shutter piece (all of them when K = 1, or when the
// triangle's view-space vertices are the same at every step), in triangle
// order; then segment 0 of every other triangle, in triangle order, then
// segment 1, and so on. A backend that loads a window's sample times once per
// group walks them in this order.
inline std::vector<SegmentPiece> plan_segment_pieces(const Scene& scene, const CameraModel& model) {
    const int segments = scene_motion_segments(scene);
    std::vector<SegmentPiece> whole, split;
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        bool moves = false;
        for (int corner = 0; corner < 3 && segments > 1 && !moves; ++corner) {
            const std::size_t v = scene.triangles[i][corner];
            const glm::vec3 first = step_view_position<float>(scene, model, v, 0);
            for (int step = 1; step <= segments && !moves; ++step)
                moves = step_view_position<float>(scene, model, v, step) != first;
        }
        (moves ? split : whole).push_back(SegmentPiece{static_cast<std::uint32_t>(i), 0, moves ? segments : 1});
    }
    std::vector<SegmentPiece> pieces = whole;
    pieces.reserve(whole.size() + split.size() * static_cast<std::size_t>(segments));
    for (int k = 0; k < segments && !split.empty(); ++k) {
        for (SegmentPiece piece : split) {
            piece.segment = k;
            pieces.push_back(piece);
        }
    }
    return pieces;
}

// The piece as the kernel sees it: clip-space vertices and CoCs at the ends of
// its window (make_moving_triangle for a whole-shutter piece, bit for bit).
template <class Real>
typename blurcull::kernel<Real>::MovingTriangle make_segment_triangle(const Scene& scene, const CameraModel& model,
                                                                      const SegmentPiece& piece) {
    using K = blurcull::kernel<Real>;
    if (piece.segments == 1) return make_moving_triangle<Real>(scene, model, piece.source);
    typename K::MovingTriangle result{};
    const int segments = scene_motion_segments(scene);
    for (int end = 0; end < 2; ++end) {
        // Step numbers are of the scene's K; a piece's segments equal it.
        const int step = (piece.segment + end) * segments / piece.segments;
        for (int i = 0; i < 3; ++i) {
            set_clip_vertex<Real>(model, step_view_position<Real>(scene, model, scene.triangles[piece.source][i], step),
                                  result, i + 3 * end);
        }
    }
    return result;
}

}  // namespace blurcull::frontend
