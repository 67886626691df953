// Static, in-focus triangles: six vertices per triangle (glDrawArrays, GL_TRIANGLES)
// make a quad over its pixel rectangle, depth from the triangle's plane
// (z = near / w, affine over the screen), so the fixed-function depth test
// compares at the MSAA sample positions. Other triangles get a degenerate quad.
layout(std430, binding = 1) readonly buffer Infos { TriangleInfo infos[]; };

flat out int g_index;

void main() {
    int i = gl_VertexID / 6;
    g_index = i;
    if (infos[i].meta.z != PATH_STATIC) {
        gl_Position = vec4(-2.0, -2.0, 0.0, 1.0);
        return;
    }
    vec2 ndc = quad_corner(infos[i].rect, gl_VertexID % 6);
    vec4 plane = infos[i].plane;
    gl_Position = vec4(ndc, near_plane * (plane.x * ndc.x + plane.y * ndc.y + plane.z), 1.0);
}
