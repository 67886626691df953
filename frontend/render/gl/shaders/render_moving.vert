// Moving or defocused triangles: six vertices per cell (cells_per_triangle
// cells per triangle of the moving list, in triangle order), a quad over the cell's pixels
// carrying its sample bounds; empty cells get a degenerate quad.
layout(std430, binding = BC_GL_CELLS_BINDING) readonly buffer Cells { CellBounds cells[]; };
layout(std430, binding = BC_GL_MOVING_LIST_BINDING) readonly buffer MovingList { uint moving_list[]; };

uniform int cells_per_triangle;

flat out int g_index;
flat out vec4 g_lens;  // u_range, v_range
flat out vec4 g_time_lines_u_a;  // the cell's CellBounds.time_lines_*
flat out vec4 g_time_lines_u_b;
flat out vec4 g_time_lines_v_a;
flat out vec4 g_time_lines_v_b;

void main() {
    int cell = gl_VertexID / 6;
    g_index = int(moving_list[cell / cells_per_triangle]);
    CellBounds c = cells[cell];
    g_lens = c.lens;
    g_time_lines_u_a = c.time_lines_u_a;
    g_time_lines_u_b = c.time_lines_u_b;
    g_time_lines_v_a = c.time_lines_v_a;
    g_time_lines_v_b = c.time_lines_v_b;
    if (c.rect.x > c.rect.z) {
        gl_Position = vec4(-2.0, -2.0, 0.0, 1.0);
        return;
    }
    gl_Position = vec4(quad_corner(c.rect, gl_VertexID % 6), 0.5, 1.0);
}
