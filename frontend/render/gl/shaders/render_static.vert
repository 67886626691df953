// Static, in-focus triangles (the static list, in index order): three
// vertices per triangle (glDrawArrays, GL_TRIANGLES), the one triangle
// render_setup.comp chose to hold every pixel the triangle's samples can be
// in. Triangles off screen get a degenerate one.
layout(std430, binding = BC_GL_INFOS_BINDING) readonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = BC_GL_STATIC_LIST_BINDING) readonly buffer StaticList { uint static_list[]; };

flat out int g_index;

void main() {
    int i = int(static_list[gl_VertexID / 3]);
    g_index = i;
    if (infos[i].path != BC_GL_PATH_STATIC) {
        gl_Position = vec4(-2.0, -2.0, 0.0, 1.0);
        return;
    }
    int k = gl_VertexID % 3;
    vec2 window = k == 0 ? infos[i].outline01.xy : k == 1 ? infos[i].outline01.zw : infos[i].outline2.xy;
    // Window y grows upwards: the NDC of the raster position, mirrored in y
    // (render_setup.comp's outline, inverted).
    vec2 ndc = bc_raster_to_ndc(window, image_size);
    gl_Position = vec4(ndc.x, -ndc.y, 0.5, 1.0);
}
