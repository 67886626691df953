// Static, in-focus triangles (the static list, in index order): six vertices
// per triangle (glDrawArrays, GL_TRIANGLES) make a quad over its pixel
// rectangle, whatever the method. Triangles off screen get a degenerate quad.
layout(std430, binding = 1) readonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = 10) readonly buffer StaticList { uint static_list[]; };

flat out int g_index;

void main() {
    int i = int(static_list[gl_VertexID / 6]);
    g_index = i;
    if (infos[i].meta.z != PATH_STATIC) {
        gl_Position = vec4(-2.0, -2.0, 0.0, 1.0);
        return;
    }
    int k = gl_VertexID % 6;
    if (infos[i].meta.w == 1) {
        // The grown triangle (render_setup.comp): vertices 0-2; 3-5 degenerate.
        vec2 window = k == 0 ? infos[i].outline01.xy : k == 1 ? infos[i].outline01.zw : infos[i].outline2.xy;
        gl_Position = k < 3 ? vec4(window / image_size * 2.0 - 1.0, 0.5, 1.0) : vec4(-2.0, -2.0, 0.0, 1.0);
        return;
    }
    gl_Position = vec4(quad_corner(infos[i].rect, k), 0.5, 1.0);
}
