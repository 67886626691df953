// Compute pipeline, after render_setup.comp: per triangle on a path, the
// screen box of each of BC_GL_TIME_STRATA shutter slices (the kernel's
// bc_stratum_screen_box over the whole lens, narrowing the screen bound
// render_setup.comp kept), which render_compute_raster.comp tests each
// sample's position against before bc_sample_test. A static, in-focus
// triangle (and every triangle when time_strata is 0) keeps its one box.
layout(local_size_x = 64) in;

layout(std430, binding = BC_GL_INFOS_BINDING) readonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = BC_GL_STRATUM_BOXES_BINDING) writeonly buffer StratumBoxes { vec4 stratum_boxes[]; };

uniform int triangle_count;
uniform int time_strata;  // 1: per slice boxes, 0: the screen box for every slice

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= triangle_count) return;
    ScreenBound whole;
    whole.empty = infos[i].path == BC_GL_PATH_NONE;
    whole.lo = infos[i].box.xy;
    whole.hi = infos[i].box.zw;
    whole.hull_count = infos[i].hull_count;
    for (int h = 0; h < BC_HULL_MAX; ++h) whole.hull_edge[h] = vec3(0.0);
    for (int h = 0; h < whole.hull_count; ++h) whole.hull_edge[h] = infos[i].hull[h].xyz;
    bool sliced = time_strata != 0 && !whole.empty && infos[i].needs != 0;
    for (int s = 0; s < BC_GL_TIME_STRATA; ++s) {
        vec2 time = vec2(float(s), float(s + 1)) / float(BC_GL_TIME_STRATA);
        stratum_boxes[i * BC_GL_TIME_STRATA + s] =
            sliced ? bc_stratum_screen_box(triangles[i], near_plane, whole, time, vec2(-1.0, 1.0), vec2(-1.0, 1.0))
                   : vec4(whole.lo, whole.hi);
    }
}
