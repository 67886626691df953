// Per triangle, once per frame: classify, screen bound, pixel rectangle, and
// which path draws it (static: render_static.*, moving: render_moving.*).
layout(local_size_x = 64) in;

layout(std430, binding = 1) writeonly buffer Infos { TriangleInfo infos[]; };

uniform int triangle_count;
uniform int method;      // BC_CULL_*
uniform int force_full;  // 1: every triangle takes the moving path

int clamp_floor(float v, int limit) {
    if (!(v > 0.0)) return 0;  // also NaN
    if (v >= float(limit)) return limit;
    return int(floor(v));
}

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= triangle_count) return;
    MovingTriangle tri = triangles[i];
    TriangleInfo info;
    info.box = vec4(0.0);
    info.rect = ivec4(0, 0, -1, -1);
    info.unused = vec4(0.0);
    int needs = classify(tri);
    info.meta = ivec4(needs, 0, PATH_NONE, 0);
    for (int k = 0; k < BC_HULL_MAX; ++k) info.hull[k] = vec4(0.0);
    if (needs == BC_INVALID) {
        infos[i] = info;
        return;
    }
    // Static and in focus: the static path (no cells, no hull, no lens/time bounds).
    bool is_static = needs == 0 && force_full == 0;
    ScreenBound b = screen_bound(tri, near_plane, is_static ? BC_CULL_BBOX : method);
    if (b.empty) {
        infos[i] = info;
        return;
    }
    info.box = vec4(b.lo, b.hi);
    info.meta.y = b.hull_count;
    for (int k = 0; k < BC_HULL_MAX; ++k) {
        if (k < b.hull_count) info.hull[k] = vec4(b.hull_edge[k], 0.0);
    }
    int w = int(image_size.x), h = int(image_size.y);
    // One pixel wider than the box on each side: this rounding is float, the
    // exact containment test is screen_contains in the fragment shader.
    ivec4 r = ivec4(clamp_floor((b.lo.x + 1.0) * 0.5 * image_size.x, w) - 1,
                    clamp_floor((1.0 - b.hi.y) * 0.5 * image_size.y, h) - 1,
                    clamp_floor((b.hi.x + 1.0) * 0.5 * image_size.x, w) + 1,
                    clamp_floor((1.0 - b.lo.y) * 0.5 * image_size.y, h) + 1);
    r = ivec4(max(r.x, 0), max(r.y, 0), min(r.z, w - 1), min(r.w, h - 1));
    if (b.lo.x > 1.0 || b.hi.x < -1.0 || b.lo.y > 1.0 || b.hi.y < -1.0 || r.x > r.z || r.y > r.w) {
        infos[i] = info;
        return;
    }
    info.rect = r;
    info.meta.z = is_static ? PATH_STATIC : PATH_MOVING;
    infos[i] = info;
}
