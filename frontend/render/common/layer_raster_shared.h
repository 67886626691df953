// The arithmetic of rasterizing a triangle into a dof-secondary layer view,
// written once for C++ and GLSL (like optics_shared.h): the CPU build's scan
// (render/secondary/layer_raster.inl) and the GL build's passes
// (render/gl/shaders/render_layers_*) call these, so both store the same
// view depth at a texel centre they both cover (docs/secondary-rays.md, "The
// renderer", step 3). Every expression is the one the host evaluated before
// it was shared (glm::mix's a (1 - t) + b t, the kernel's left-to-right dot),
// and `precise` in GLSL keeps Mesa from reassociating it.
#ifndef BLURCULL_LAYER_RASTER_SHARED_H
#define BLURCULL_LAYER_RASTER_SHARED_H

#ifdef __cplusplus
#include <blurcull/kernel.hpp>

#include <glm/glm.hpp>

namespace blurcull::frontend::layer_raster {
using glm::bvec3;
using glm::ivec4;
using glm::vec2;
using glm::vec3;
using glm::ceil;
using glm::clamp;
using glm::floor;
using glm::max;
using glm::min;
using LayerView = kernelf::LayerView;
inline float bc_dot3(vec3 a, vec3 b) { return kernelf::bc_dot3(a, b); }
inline vec2 bc_layer_image(const LayerView& v, float x, float y, float z) { return kernelf::bc_layer_image(v, x, y, z); }
#define BC_RASTER_FN inline
#define BC_RASTER_VIEW const LayerView&
#define BC_RASTER_PRECISE
#else
#define BC_RASTER_FN
#define BC_RASTER_VIEW in LayerView
#define BC_RASTER_PRECISE precise
#endif

// View coordinates (along right, up, forward) of world point p.
BC_RASTER_FN vec3 bc_raster_view_point(BC_RASTER_VIEW v, vec3 p) {
    vec3 q = p - v.eye;
    return vec3(bc_dot3(q, v.right), bc_dot3(q, v.up), bc_dot3(q, v.forward));
}

// Where the edge from a to b (view coordinates, one end on each side of
// depth `near`) crosses that depth: the Sutherland-Hodgman clip point.
BC_RASTER_FN vec3 bc_raster_near_crossing(vec3 a, vec3 b, float near) {
    BC_RASTER_PRECISE float t = (near - a.z) / (b.z - a.z);
    BC_RASTER_PRECISE vec3 p = a * (1.0f - t) + b * t;
    return p;
}

// (image x, image y, view depth) of a clipped view point: the kernel's
// layer_image at the depth, held at `near` against the clip's rounding.
BC_RASTER_FN vec3 bc_raster_image_point(BC_RASTER_VIEW v, vec3 p) {
    float z = max(p.z, v.near);
    vec2 xy = bc_layer_image(v, p.x, p.y, z);
    return vec3(xy.x, xy.y, z);
}

// Twice the signed area of (p, q, r): positive when counter-clockwise.
BC_RASTER_FN float bc_raster_edge(vec2 p, vec2 q, vec2 r) {
    BC_RASTER_PRECISE float e = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
    return e;
}

// An image triangle (image x, image y, view depth) turned counter-clockwise,
// with twice its area (bc_raster_ccw): what a scan of it starts from.
struct RasterTriangle {
    vec3 a;
    vec3 b;
    vec3 c;
    float area;  // not above 0 (0, NaN) for a degenerate triangle: nothing to scan
};

// (a, b, c) counter-clockwise: b and c swapped when bc_raster_edge is negative.
BC_RASTER_FN RasterTriangle bc_raster_ccw(vec3 a, vec3 b, vec3 c) {
    float area = bc_raster_edge(vec2(a.x, a.y), vec2(b.x, b.y), vec2(c.x, c.y));
    bool flip = area < 0.0f;
    RasterTriangle t;
    t.a = a;
    t.b = flip ? c : b;
    t.c = flip ? b : c;
    t.area = flip ? -area : area;
    return t;
}

// The texels (x0, y0, x1, y1) whose centres the triangle's bounding box may
// hold, clamped to the size x size image: none when x0 > x1 or y0 > y1.
// Clamped as floats, so no conversion overflows.
BC_RASTER_FN ivec4 bc_raster_texel_box(RasterTriangle t, int size) {
    float last = float(size - 1);
    float x0 = clamp(floor(min(min(t.a.x, t.b.x), t.c.x) - 0.5f), 0.0f, float(size));
    float x1 = clamp(ceil(max(max(t.a.x, t.b.x), t.c.x) - 0.5f), -1.0f, last);
    float y0 = clamp(floor(min(min(t.a.y, t.b.y), t.c.y) - 0.5f), 0.0f, float(size));
    float y1 = clamp(ceil(max(max(t.a.y, t.b.y), t.c.y) - 0.5f), -1.0f, last);
    return ivec4(int(x0), int(y0), int(x1), int(y1));
}

// Whether the edge from a to b owns the texel centres on it: a top or left
// edge of the counter-clockwise triangle (the top-left rule, so a centre on
// an edge two triangles share is covered once).
BC_RASTER_FN bool bc_raster_owns_edge(vec2 a, vec2 b) { return (a.y == b.y && b.x < a.x) || b.y > a.y; }

// bc_raster_owns_edge of the triangle's edges bc, ca and ab.
BC_RASTER_FN bvec3 bc_raster_owned_edges(RasterTriangle t) {
    vec2 a = vec2(t.a.x, t.a.y);
    vec2 b = vec2(t.b.x, t.b.y);
    vec2 c = vec2(t.c.x, t.c.y);
    return bvec3(bc_raster_owns_edge(b, c), bc_raster_owns_edge(c, a), bc_raster_owns_edge(a, b));
}

// Whether the triangle covers `centre`; owns: bc_raster_owned_edges(t).
BC_RASTER_FN bool bc_raster_covers(RasterTriangle t, bvec3 owns, vec2 centre) {
    vec2 a = vec2(t.a.x, t.a.y);
    vec2 b = vec2(t.b.x, t.b.y);
    vec2 c = vec2(t.c.x, t.c.y);
    float wa = bc_raster_edge(b, c, centre);
    float wb = bc_raster_edge(c, a, centre);
    float wc = bc_raster_edge(a, b, centre);
    if (wa < 0.0f || wb < 0.0f || wc < 0.0f) return false;
    return !((wa == 0.0f && !owns.x) || (wb == 0.0f && !owns.y) || (wc == 0.0f && !owns.z));
}

// The view depth at image point `centre` of the counter-clockwise image
// triangle (a, b, c) of doubled area `area` = bc_raster_edge(a, b, c) > 0:
// 1 / depth is linear on the image, interpolated with the edge functions.
BC_RASTER_FN float bc_raster_depth(vec3 a, vec3 b, vec3 c, float area, vec2 centre) {
    float wa = bc_raster_edge(vec2(b.x, b.y), vec2(c.x, c.y), centre);
    float wb = bc_raster_edge(vec2(c.x, c.y), vec2(a.x, a.y), centre);
    float wc = bc_raster_edge(vec2(a.x, a.y), vec2(b.x, b.y), centre);
    BC_RASTER_PRECISE float inverse_depth = (wa / a.z + wb / b.z + wc / c.z) / area;
    BC_RASTER_PRECISE float depth = 1.0f / inverse_depth;
    return depth;
}

#ifdef __cplusplus
}  // namespace blurcull::frontend::layer_raster
#endif

#endif  // BLURCULL_LAYER_RASTER_SHARED_H
