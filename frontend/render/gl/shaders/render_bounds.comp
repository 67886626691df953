// Per cell of each moving triangle (the moving path's list), once per frame: its pixels and the chosen
// method's sample bounds for them (the footprint), in parallel. A cell whose
// bounds hold no sample is marked empty and never rasterized.
layout(local_size_x = 64) in;

layout(std430, binding = BC_GL_INFOS_BINDING) readonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = BC_GL_CELLS_BINDING) writeonly buffer Cells { CellBounds cells[]; };
layout(std430, binding = BC_GL_MOVING_LIST_BINDING) readonly buffer MovingList { uint moving_list[]; };  // index order

uniform int moving_count;
uniform int cells_per_triangle;  // 1, or BC_GL_CELLS_MAX when the method bounds lens and time
uniform int method;
uniform int cell_pixels;         // the smallest cell side, in pixels

void main() {
    int slot = int(gl_GlobalInvocationID.x);
    if (slot >= moving_count * cells_per_triangle) return;
    int i = int(moving_list[slot / cells_per_triangle]), cell = slot % cells_per_triangle;
    CellBounds out_cell;
    SampleBounds sb = bc_no_sample_bounds();
    out_cell.rect = ivec4(0, 0, -1, -1);
    ivec4 r = infos[i].rect;
    if (infos[i].path == BC_GL_PATH_MOVING) {
        int width = r.z - r.x + 1, height = r.w - r.y + 1;
        int columns = cells_per_triangle == 1 ? 1 : clamp((width + cell_pixels - 1) / cell_pixels, 1, 4);
        int rows = cells_per_triangle == 1 ? 1 : clamp((height + cell_pixels - 1) / cell_pixels, 1, 4);
        int row = cell / 4, column = cell % 4;
        if (cells_per_triangle == 1) row = column = 0;
        int cell_w = (width + columns - 1) / columns, cell_h = (height + rows - 1) / rows;
        ivec4 c = ivec4(r.x + column * cell_w, r.y + row * cell_h, 0, 0);
        c.z = min(c.x + cell_w - 1, r.z);
        c.w = min(c.y + cell_h - 1, r.w);
        if (row < rows && column < columns && c.x <= c.z && c.y <= c.w) {
            out_cell.rect = c;
            if (cells_per_triangle > 1 && infos[i].needs != 0) {
                // The footprint as the CPU backend forms it.
                vec4 footprint = bc_pixel_rect_ndc(c, image_size);
                sb = bc_sample_bounds(triangles[i], footprint.xy, footprint.zw, method);
                if (sb.empty) out_cell.rect = ivec4(0, 0, -1, -1);
            }
        }
    }
    out_cell.lens = vec4(sb.u_range, sb.v_range);
    out_cell.time_lines_u_a = sb.u_time_a;
    out_cell.time_lines_u_b = sb.u_time_b;
    out_cell.time_lines_v_a = sb.v_time_a;
    out_cell.time_lines_v_b = sb.v_time_b;
    cells[slot] = out_cell;
}
