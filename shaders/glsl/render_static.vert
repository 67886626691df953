// Static, in-focus triangles: six vertices per triangle (glDrawArrays,
// GL_TRIANGLES) make a quad over its pixel rectangle, one quad per triangle
// whatever the method. Other triangles get a degenerate quad.
layout(std430, binding = 1) readonly buffer Infos { TriangleInfo infos[]; };

flat out int g_index;

void main() {
    int i = gl_VertexID / 6;
    g_index = i;
    if (infos[i].meta.z != PATH_STATIC) {
        gl_Position = vec4(-2.0, -2.0, 0.0, 1.0);
        return;
    }
    gl_Position = vec4(quad_corner(infos[i].rect, gl_VertexID % 6), 0.5, 1.0);
}
