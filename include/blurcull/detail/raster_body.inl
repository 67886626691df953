// Shared C++/GLSL text (see dialect.hpp): the raster glue every backend runs
// around the kernel, written once (docs/kernel.md, "The raster glue").
//
// Conventions (those of frontend/render's CameraModel, docs/reference-renderer.md):
//  - NDC (X, Y) in [-1, 1]^2 on screen, +Y up;
//  - raster coordinates (rx, ry) in pixels, x right and y DOWN: pixel (px, py)
//    is [px, px + 1) x [py, py + 1), row 0 at the top; a sample offset in
//    [0, 1)^2 is measured from the pixel's top-left corner;
//  - image_size = (width, height) in pixels, as reals (the GL uniform's form);
//    a lattice of `scale` cells per pixel side is an image of size * scale;
//  - integer rectangles are ivec4(x0, y0, x1, y1), inclusive; empty is
//    ivec4(0, 0, -1, -1) (x0 > x1 and y0 > y1).
// Sample positions are float on every backend: the host calls
// kernel<float>'s functions here and widens the result, as it does with
// pixel_sample. Every expression is the exact operation order the backends
// used, and BC_PRECISE keeps GLSL from fusing or reassociating it.

// ---- raster <-> NDC -------------------------------------------------------------

// NDC of raster position `raster` (pixels, y down) in an image of image_size
// pixels: X = -1 + 2 rx / width, Y = 1 - 2 ry / height, the division the
// sampler's bc_div (the same bits on every GPU). Any finite input whose
// quotient is in the normal range; the grid corners 0 and width map to -1 and 1 exactly.
BC_FN vec2 raster_to_ndc(vec2 raster, vec2 image_size) {
    BC_PRECISE real x = real(-1) + bc_div(real(2) * raster.x, image_size.x);
    BC_PRECISE real y = real(1) - bc_div(real(2) * raster.y, image_size.y);
    return vec2(x, y);
}

// Raster position (pixels, y down) of NDC `ndc`: the inverse of
// raster_to_ndc up to rounding (a few ulps of the image size).
BC_FN vec2 ndc_to_raster(vec2 ndc, vec2 image_size) {
    BC_PRECISE real x = (ndc.x + real(1)) * real(0.5) * image_size.x;
    BC_PRECISE real y = (real(1) - ndc.y) * real(0.5) * image_size.y;
    return vec2(x, y);
}

// NDC of the sample at `offset` (in [0, 1]^2, from the top-left corner) in
// pixel `pixel`: raster_to_ndc(pixel + offset). The sum is rounded first, so
// an offset just below 1 may land on the pixel's right or bottom edge.
BC_FN vec2 pixel_sample_ndc(ivec2 pixel, vec2 offset, vec2 image_size) {
    BC_PRECISE real rx = real(pixel.x) + offset.x;
    BC_PRECISE real ry = real(pixel.y) + offset.y;
    return raster_to_ndc(vec2(rx, ry), image_size);
}

// The NDC box (lo.x, lo.y, hi.x, hi.y) that pixels rect (inclusive) cover:
// lo = the NDC of grid corner (x0, y1 + 1), hi = that of (x1 + 1, y0). A
// renderer's footprint for sample_bounds and screen_footprint.
BC_FN vec4 pixel_rect_ndc(ivec4 rect, vec2 image_size) {
    vec2 top_left = raster_to_ndc(vec2(real(rect.x), real(rect.y)), image_size);
    vec2 bottom_right = raster_to_ndc(vec2(real(rect.z + 1), real(rect.w + 1)), image_size);
    return vec4(top_left.x, bottom_right.y, bottom_right.x, top_left.y);
}

// ---- the cells an NDC box can hold samples in -----------------------------------

// floor(v) clamped to [0, limit]; 0 for NaN (the rect of a NaN box is its
// clamp, and the per-sample test rejects every sample of it).
BC_FN int bc_clamp_floor(real v, int limit) {
    if (!(v > real(0))) return 0;
    if (v >= real(limit)) return limit;
    return int(floor(v));
}

// The cells, clamped to a lattice of `cells` = (columns, rows) cells (the
// image size in pixels, or times `scale` for a lattice of scale^2 cells per
// pixel), that hold every sample whose (rounded) NDC lies in the closed box
// [lo, hi]; empty (ivec4(0, 0, -1, -1)) when the box misses the screen.
// Margin policy: a sample of cell c lies in raster [c, c + 1] up to the
// rounding of its position, and the rect's raster coordinates are rounded
// too; both errors are a few ulps of the lattice size (about 3 eps max(cells)
// cells in float). The box is widened by 1/64 cell, or BC_MARGIN ulps of the
// lattice size where that is more (beyond 16384 cells in float), which keeps
// every such sample with a wide safety factor and grows a sub-pixel
// triangle's rect to at most 2 x 2 cells. (It replaced three rules: none on
// the CPU, which could lose a sample rounded onto its pixel's edge; one
// whole cell for the CPU methods; 1/64 pixel on the GPU.)
BC_FN ivec4 box_cell_rect(vec2 lo, vec2 hi, vec2 cells) {
    ivec4 none = ivec4(0, 0, -1, -1);
    // Samples have -1 <= X, Y <= 1 exactly (raster_to_ndc of [0, size]).
    if (lo.x > real(1) || hi.x < real(-1) || lo.y > real(1) || hi.y < real(-1)) return none;
    real margin = max(real(0.015625), real(BC_MARGIN) * bc_epsilon() * max(cells.x, cells.y));
    int columns = int(cells.x), rows = int(cells.y);
    BC_PRECISE real left = (lo.x + real(1)) * real(0.5) * cells.x - margin;
    BC_PRECISE real right = (hi.x + real(1)) * real(0.5) * cells.x + margin;
    BC_PRECISE real top = (real(1) - hi.y) * real(0.5) * cells.y - margin;
    BC_PRECISE real bottom = (real(1) - lo.y) * real(0.5) * cells.y + margin;
    ivec4 r = ivec4(bc_clamp_floor(left, columns), bc_clamp_floor(top, rows),
                    min(bc_clamp_floor(right, columns), columns - 1), min(bc_clamp_floor(bottom, rows), rows - 1));
    if (r.x > r.z || r.y > r.w) return none;
    return r;
}

// ---- sample placement of the interleave method ----------------------------------

// Lattice cell of tile slot `slot` (cy * tile_width + cx, as
// InterleavedTiles::tuple_slot holds it) in tile `tile`: tile * tile_width +
// (cx, cy). May lie past the image's edge (a partial tile): the caller skips it.
BC_FN ivec2 interleaved_cell(ivec2 tile, int slot, int tile_width) {
    return tile * tile_width + ivec2(slot % tile_width, slot / tile_width);
}

// NDC of the interleave method's sample in lattice cell `cell` (scale x scale
// cells per pixel; cell (px scale + i, py scale + j) is pixel (px, py)'s
// sample j scale + i), at `jitter` in [0, 1)^2 of the cell
// (patterns::interleaved_jitter(cell, seed)): as an offset in the pixel, kept
// below 1 (the largest real below 1), then pixel_sample_ndc. Its (u, v, t) is
// the tuple its tile slot holds (docs/sampling.md). cell >= 0, scale >= 1.
BC_FN vec2 interleaved_sample_ndc(ivec2 cell, int scale, vec2 jitter, vec2 image_size) {
    BC_PRECISE vec2 cell_offset = vec2(real(cell.x % scale), real(cell.y % scale)) + jitter;
    vec2 offset = vec2(bc_div(cell_offset.x, real(scale)), bc_div(cell_offset.y, real(scale)));
    BC_PRECISE real below_one = real(1) - real(0.5) * bc_epsilon();
    offset = min(offset, vec2(below_one));
    return pixel_sample_ndc(cell / scale, offset, image_size);
}

// ---- the per-sample test chain and the depth rules ------------------------------

#define BC_SAMPLE_CULLED 0   // rejected by the lens/time bounds or the screen bound: not tested
#define BC_SAMPLE_MISSED 1   // tested (a renderer's samples_tested), not covered
#define BC_SAMPLE_COVERED 2  // tested and covered (samples_hit); depth is its view depth

// The culling half of sample_test: whether the sample is rejected without an
// exact test, by the lens/time bounds (sample_passes_at) or, when check_screen,
// the screen bound (screen_contains). A renderer that puts a cheaper test of
// its own between the culls and covers (the CPU backend's fast coverage test)
// calls this, then covers.
BC_FN bool sample_culled(BC_IN(ScreenBound) screen, bool check_screen, BC_IN(SampleBounds) bounds, vec2 ndc,
                         vec2 lens, real time) {
    if (!sample_passes_at(bounds, ndc, lens, time)) return true;
    return check_screen && !screen_contains(screen, ndc);
}

// One sample (screen position ndc, lens position lens, shutter time time)
// against one triangle, as every backend tests it: the lens/time bounds
// (sample_passes; no_sample_bounds() passes every sample with lens in
// [-1, 1]^2 and time in [0, 1], which every pattern's samples are), then the
// screen bound (screen_contains; skipped when check_screen is false, which a
// renderer may do where screen_footprint said INSIDE), then the exact test
// (covers, which rejects hits nearer than `near`). Returns BC_SAMPLE_*;
// depth is the hit's view depth w >= near when COVERED, else 0.
BC_FN int sample_test(BC_IN(MovingTriangle) tri, BC_IN(ScreenBound) screen, bool check_screen,
                      BC_IN(SampleBounds) bounds, vec2 ndc, vec2 lens, real time, real near, BC_OUT(real) depth) {
    depth = real(0);
    if (sample_culled(screen, check_screen, bounds, ndc, lens, time)) return BC_SAMPLE_CULLED;
    if (!covers(tri, ndc, lens, time, near, depth)) return BC_SAMPLE_MISSED;
    return BC_SAMPLE_COVERED;
}

// The CPU z-buffer's rule: a covered sample at view depth `depth` replaces
// the nearest so far only when strictly nearer, so with the triangles in
// index order the lowest index wins among equal depths. nearest starts at
// +infinity (no hit); a NaN depth never wins.
BC_FN bool depth_nearer(real depth, real nearest) {
    return depth < nearest;
}

// The GPU depth buffer's key of a covered sample at view depth `depth` >= near
// > 0: near / depth in (0, 1], larger is nearer, clamped to [0, 1] as the
// depth buffer clamps gl_FragDepth; the buffer is cleared to 0 (no hit), so a
// key of 0 (an underflowed far hit) never wins.
BC_FN real depth_key(real near, real depth) {
    return clamp(near / depth, real(0), real(1));
}

// The GPU rule between a sample's key and the held one: the larger key wins
// (the strict GREATER depth test), and on equal keys the lower triangle index
// (what drawing in index order with that test keeps). The CPU rule on w and
// this one on near / w agree but where distinct depths round to one key.
BC_FN bool depth_key_wins(real key, uint index, real held_key, uint held_index) {
    return key > held_key || (key == held_key && index < held_index);
}

// ---- the circle of confusion from camera parameters -----------------------------

// The signed circle of confusion c(w) = a + b w along one axis of the
// camera (thin_lens_coc) with projection scale k (x_clip = k x_view; k_x or
// k_y), lens radius R >= 0 and focus depth F > 0: a = -k R, b = k R / F.
// With no lens (R = 0) b is 0 whatever F is (F may be unset: 0 or not
// finite), and a is -0.
BC_FN vec2 camera_coc(real projection_scale, real lens_radius, real focus_depth) {
    return thin_lens_coc(projection_scale, lens_radius, lens_radius > real(0) ? focus_depth : real(1));
}
