// Per triangle, once per frame: classify, screen bound, pixel rectangle, and
// which path draws it (static: render_static.*, moving: render_moving.*).
layout(local_size_x = 64) in;

layout(std430, binding = BC_GL_INFOS_BINDING) writeonly buffer Infos { TriangleInfo infos[]; };
// classify() of each triangle, run on the host (kernel<float>, bit-identical)
// since the host builds the per-path draw lists from it.
layout(std430, binding = BC_GL_CLASSES_BINDING) readonly buffer Classes { int classes[]; };

uniform int triangle_count;
uniform int method;      // BC_CULL_*
uniform int force_full;  // 1: every triangle takes the moving path

// How far, in pixels, the static path pushes a triangle's edges out: a pixel
// holding a covered sample of the pattern must have all four MSAA samples
// (where GL runs the per-sample shader) inside what is drawn. Each sample is
// less than a pixel from the others along each axis, so the triangle grown by
// a pixel-sized box suffices; 1/64 more for the float rounding here and
// llvmpipe's 1/256-pixel snapping.
const float OUTLINE_GROWTH = 1.0 + 1.0 / 64.0;

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// A static, in-focus triangle (vertex k at p[k]) on screen, every edge pushed
// out by OUTLINE_GROWTH pixels along x and y (the box's support along the
// edge normal), as three window positions (pixels, y up). False when a
// vertex is not in front of the near plane, the triangle is edge-on, or the
// result is not finite: the caller draws the rect instead.
bool grown_outline(MovingTriangle tri, out vec2 outline[3]) {
    vec2 v[3];
    for (int k = 0; k < 3; ++k) {
        outline[k] = vec2(0.0);
        if (!(tri.p[k].z >= near_plane)) return false;
        // Window y grows upwards: the raster position of the NDC mirrored in y.
        vec2 ndc = tri.p[k].xy / tri.p[k].z;
        v[k] = bc_ndc_to_raster(vec2(ndc.x, -ndc.y), image_size);
    }
    float area2 = cross2(v[1] - v[0], v[2] - v[0]);
    if (!(abs(area2) > 1e-6)) return false;
    float orientation = area2 > 0.0 ? 1.0 : -1.0;
    vec3 edge_line[3];  // n.x, n.y, c: inside is dot(n, x) <= c, n the unit outward normal
    for (int k = 0; k < 3; ++k) {
        vec2 e = v[(k + 1) % 3] - v[k];
        vec2 n = orientation * vec2(e.y, -e.x);
        n /= length(n);
        edge_line[k] = vec3(n, dot(n, v[k]) + (abs(n.x) + abs(n.y)) * OUTLINE_GROWTH);
    }
    for (int k = 0; k < 3; ++k) {
        vec3 a = edge_line[(k + 2) % 3], b = edge_line[k];  // the two edges through vertex k
        float det = a.x * b.y - a.y * b.x;
        outline[k] = vec2(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det;
        if (any(isinf(outline[k])) || any(isnan(outline[k]))) return false;
    }
    return true;
}

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= triangle_count) return;
    MovingTriangle tri = triangles[i];
    TriangleInfo info;
    info.box = vec4(0.0);
    info.rect = ivec4(0, 0, -1, -1);
    info.outline01 = vec4(0.0);
    info.outline2 = vec4(0.0);
    int needs = classes[i];
    info.needs = needs;
    info.hull_count = 0;
    info.path = BC_GL_PATH_NONE;
    info.padding = 0;
    for (int k = 0; k < BC_HULL_MAX; ++k) info.hull[k] = vec4(0.0);
    if (needs == BC_INVALID) {
        infos[i] = info;
        return;
    }
    // Static and in focus: the static path (no cells, no hull, no lens/time bounds).
    bool is_static = needs == 0 && force_full == 0;
    ScreenBound b = bc_screen_bound(tri, near_plane, is_static ? BC_CULL_BBOX : method);
    if (b.empty) {
        infos[i] = info;
        return;
    }
    info.box = vec4(b.lo, b.hi);
    info.hull_count = b.hull_count;
    for (int k = 0; k < BC_HULL_MAX; ++k) {
        if (k < b.hull_count) info.hull[k] = vec4(b.hull_edge[k], 0.0);
    }
    // The pixels that can hold a sample in the box (the exact containment
    // test is screen_contains in the fragment shader); empty off screen.
    ivec4 r = bc_box_cell_rect(b.lo, b.hi, image_size);
    if (r.x > r.z || r.y > r.w) {
        infos[i] = info;
        return;
    }
    info.rect = r;
    info.path = is_static ? BC_GL_PATH_STATIC : BC_GL_PATH_MOVING;
    // The static path draws one triangle per static triangle (llvmpipe's
    // cost here is per primitive, not per fragment): the triangle grown by a
    // pixel, or, when that is larger (small or thin triangles: a thin
    // sliver's grown corners reach far), the right triangle whose legs are
    // twice the rect's sides (plus a quarter pixel), which holds the rect.
    if (is_static) {
        float left = float(r.x), bottom = image_size.y - float(r.w + 1);
        vec2 legs = 2.0 * vec2(float(r.z + 1 - r.x), float(r.w + 1 - r.y)) + 0.25;
        vec2 outline[3];
        outline[0] = vec2(left, bottom);
        outline[1] = vec2(left + legs.x, bottom);
        outline[2] = vec2(left, bottom + legs.y);
        vec2 grown[3];
        if (grown_outline(tri, grown) &&
            abs(cross2(grown[1] - grown[0], grown[2] - grown[0])) < legs.x * legs.y) {
            outline = grown;
        }
        info.outline01 = vec4(outline[0], outline[1]);
        info.outline2 = vec4(outline[2], 0.0, 0.0);
    }
    infos[i] = info;
}
