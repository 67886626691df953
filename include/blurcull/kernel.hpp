// blurcull/kernel.hpp: the kernel's front page.
//
// Which of a pixel's stochastic samples (x, y, u, v, t) can a moving,
// defocused triangle cover? blurcull::kernel<Real> (kernelf, kerneld) answers
// without ever dropping a sample that the triangle covers: every bound below
// contains every sample that covers() covers, and every fallback keeps
// samples, never drops them (tests/test_kernel_*.cpp check it).
//
// Each function is a static member of kernel<Real>, written once in the shared
// C++/GLSL dialect of detail/dialect.hpp in one detail/*_body.inl file per
// algorithm, and emitted as GLSL under the name bc_<name>: kerneld::covers is
// bc_covers in a shader (docs/glsl.md). The functions listed here are the
// API. Everything named bc_* (bc_err, bc_axis_extent, bc_two_stage_lens_bounds,
// ...) is internal: the bodies' helpers, which may change without notice.
// docs/kernel.md derives every formula and every margin.
//
// Conventions
//   real    float or double (GLSL: float); vec2/vec3/vec4 are GLM vectors of it.
//   clip    clip coordinates (x, y, w): w is the view depth, > 0 in front of the
//           eye. A vertex behind the eye (w <= 0) is fine everywhere.
//   s       screen position (NDC): s = (x / w, y / w), [-1, 1]^2 on the screen.
//   uv      lens position (u, v) in [-1, 1]^2; the sample patterns' unit disk
//           lies inside. A lens position shears a vertex to (x + u c_x, y + v c_y, w).
//   t       shutter time in [0, 1]: 0 at shutter open, 1 at close.
//   CoC     signed circle of confusion (c_x, c_y) of a vertex, in clip units
//           (c / w is the blur radius in NDC); its sign flips at the focal plane.
//   near    the near plane as a view depth, > 0: samples whose hit lies closer
//           are not covered.
//   cull    which bounds to compute: BC_CULL_BBOX 0 (clipped, CoC-grown screen
//           box), BC_CULL_HULL 1 (box and convex hull), BC_CULL_DUALSPACE 2
//           (box, plus the lens and time bounds of Laine et al. 2011),
//           BC_CULL_TWO_STAGE 3 (box and hull, plus the clip-space two-stage
//           lens and time bounds of Wu et al. 2015), BC_CULL_EDGES 4 (two-stage,
//           plus a plane in (u, v, t) per triangle edge; docs/kernel.md, "Edge
//           bounds"), BC_CULL_HYPERPLANE 5 (two-stage, plus one hyperplane in
//           (x, y, u, v, t) per edge and footprint and the tile test, after
//           Munkberg and Akenine-Moller 2012; docs/kernel.md, "Hyperplane
//           culling"). Switching is this one value; what a method needs is
//           its record cull_traits(cull), which the bodies and the backends
//           read (never lists of methods).
//
// Types
//   MovingTriangle  p[6]: clip (x, y, w) of vertex i at shutter open (p[i]) and
//                   close (p[i + 3]); c[6]: the CoC of each, same indexing. Both
//                   are interpolated linearly in t.
//   ScreenBound     empty; the box [lo, hi] (NDC); hull_count edges hull_edge[k]
//                   (inside when edge.x s.x + edge.y s.y + edge.z >= 0).
//   SampleBounds    empty; the lens ranges u_range, v_range; the time lines
//                   u_time_a, u_time_b (t between .x + .y u and .z + .w u) and
//                   v_time_a, v_time_b (the same over v).
//   PixelSample     offset in the pixel, [0, 1)^2; lens in the unit disk; time in [0, 1).
//
// Typical use, per triangle and footprint (docs/kernel.md, "API in one screen"):
//   if (classify(tri) == BC_INVALID) skip the triangle;
//   ScreenBound sb = screen_bound(tri, near, cull);                 // once per triangle
//   SampleBounds b = sample_bounds(tri, footprint_lo, footprint_hi, cull);  // per pixel or tile
//   for each sample: screen_contains(sb, s) && sample_passes_at(b, s, uv, t) && covers(...)
//
// ---- Circle of confusion and motion (detail/coc_motion_body.inl) -------------------
//
// vec2 thin_lens_coc(real projection_scale, real lens_radius, real focus_depth)
//   The thin lens's CoC as a function of view depth, returned as (a, b) with
//   c(w) = a + b w = -k R + (k R / F) w, so c(F) = 0. projection_scale k: the
//   projection's scale along the axis (clip x per unit of view x / view depth,
//   e.g. P[0][0] for c_x, P[1][1] for c_y); lens_radius R >= 0 and focus_depth
//   F > 0 in view-space units. F = 0 gives an infinite (or, with k R = 0, NaN)
//   b: CoCs computed from it are not finite, and classify() reports BC_INVALID.
//
// real coc_at(vec2 coc_ab, real w)
//   The signed CoC a + b w at view depth w, for (a, b) from thin_lens_coc.
//
// real coc_controlled(vec2 coc_ab, real w, real focus_range, real max_coc)
//   Controllable defocus (Munkberg et al. 2012): the CoC of coc_at with its
//   magnitude shrunk by |b| focus_range (no blur while |w - F| <= focus_range,
//   focus_range >= 0 in view units) and clamped to max_coc >= 0 (clip units).
//   Returns a signed CoC of magnitude in [0, max_coc], with coc_at's sign.
//
// vec3 vertex_at(MovingTriangle tri, int i, real t, vec2 uv)
//   Vertex i (0..2) at time t, sheared by lens position uv: clip
//   (x + u c_x, y + v c_y, w) of the interpolated position and CoC.
//
// bool triangle_is_finite(MovingTriangle tri)
//   Whether all 30 values of the triangle are finite (no NaN, no +-Inf).
//
// int classify(MovingTriangle tri)
//   What the triangle needs: 0 (static and in focus: plain rasterization),
//   else BC_NEEDS_MOTION (1: a position or CoC changes over the shutter) and/or
//   BC_NEEDS_DEFOCUS (2: some CoC is not 0). BC_INVALID (4) for any non-finite
//   value; a renderer skips such triangles.
//
// ---- The exact test, the oracle (detail/oracle_body.inl) -------------------------------
//
// bool covers(MovingTriangle tri, vec2 s, vec2 uv, real t, real near, out real depth)
//   Whether sample (s, uv, t) is covered: the ray through s meets the sheared
//   triangle at time t (edges inclusive; homogeneous rasterization, so vertices
//   behind the eye are handled) at a view depth >= near. depth: that view depth
//   when covered; 0 when the ray misses; the too-close depth when false because
//   the hit is nearer than near. Computed relative to the sample's smallest
//   vertex (bc_oracle_pivot), the edges in the frame sheared so that the
//   sample's ray is the w axis, so an edge lands within a few eps |s| of
//   where it is whatever the triangle's size or tilt; a triangle seen edge-on through the eye within rounding
//   (det within 32 eps of its terms) covers nothing. NaN anywhere in the computation gives false; classify() flags such input.
//
// bool covers_hit(MovingTriangle tri, vec2 s, vec2 uv, real t, real near, out real depth, out vec3 barycentric)
//   covers, and where the sample is covered (true, or false only for the near
//   plane) the hit's barycentric coordinates (b0, b1, b2), b_i >= 0, summing to
//   1 up to rounding: the hit point is b0 P0 + b1 P1 + b2 P2 of the triangle's
//   vertices at time t, in clip space and equally in world space (the map
//   between them and the lens shear are affine), so a renderer interpolates
//   vertex attributes at the sample's own lens position and time with them.
//   (0, 0, 0) when the ray misses. Same verdict and depth as covers, bit for bit.
//
// ---- The per-triangle screen bound (detail/screen_bound_body.inl) ----------------------
//
// int cull_traits(int cull)
//   What cull method `cull` needs, as flags: BC_CULL_BUILDS_HULL (screen_bound
//   adds the convex hull), BC_CULL_DUAL_SPACE_AXES or BC_CULL_TWO_STAGE_AXES
//   (sample_bounds bounds lens and time per footprint axis by that method;
//   BC_CULL_BOUNDS_SAMPLES is either), BC_CULL_EDGE_PLANES_PER_BLOCK (plus an
//   edge plane in (u, v, t) per edge over that box, set up per tile and shared
//   by its footprints, and optional: a renderer may leave them out where they
//   do not pay) and BC_CULL_HYPERPLANES_PER_TILE (plus one hyperplane per edge
//   per tile and the tile test on each footprint); BC_CULL_ADDS_PLANES is
//   either plane flag. bbox 0, hull BUILDS_HULL, dualspace DUAL_SPACE_AXES,
//   twostage BUILDS_HULL | TWO_STAGE_AXES, edges and hyperplane twostage's
//   plus their planes. 0 for an unknown id. A new method is a line here, the
//   body of what it adds, and its registry entry (frontend cull_method.cpp).
//
// ScreenBound screen_bound(MovingTriangle tri, real near, int cull)
//   Where on the screen the triangle can cover anything, over every t and uv:
//   the box of its part in front of the near plane, grown by the CoC and the
//   rounding margins, and for a cull with BC_CULL_BUILDS_HULL also the
//   convex hull of the lens-shifted vertices (McGuire et al. 2010) when every
//   vertex is in front of the near plane (else hull_count = 0, the box alone).
//   empty = true: never in front of the near plane. Fallback, the whole screen
//   (empty = false, box [-huge, huge]^2, no hull): near <= 0, non-finite input,
//   or a triangle whose lens shear swamps two vertices at one shutter end (the
//   oracle is then decided by rounding; docs/kernel.md). An axis whose extent
//   overflows spans [-huge, huge].
//
// vec4 stratum_screen_box(MovingTriangle tri, real near, ScreenBound whole, vec2 time, vec2 u_range, vec2 v_range)
//   The screen box (lo.x, lo.y, hi.x, hi.y) of the samples in one stratum of
//   shutter and lens only: time in [time.x, time.y] within [0, 1], u and v in
//   the given sub-ranges of [-1, 1]. whole = screen_bound(tri, near, cull);
//   its box is narrowed to the box of the triangle's 12 stratum corners (each
//   vertex at both time ends and both lens ends, projected), with twice
//   screen_bound's margin. lo.x > hi.x: the stratum holds no covered sample.
//   A renderer that keeps its samples grouped by stratum tests a stratum's
//   samples only inside its box. A corner behind the near plane narrows
//   nothing on that axis; fallback, whole's box, where screen_bound falls back.
//
// real depth_floor_scale(MovingTriangle tri, vec2 time, vec2 u_range, vec2 v_range, real screen_extent)
// real depth_floor(MovingTriangle tri, vec2 time, real scale)
//   Occlusion culling: a lower bound on the depth covers() computes for any
//   sample it covers. depth_floor_scale, once per triangle over a box of
//   shutter and lens (and screen positions |sx|, |sy| <= screen_extent),
//   gives s in [0, 1]: D / (D + Err) with D the smallest |det| of the sheared
//   vertices over the box (Bernstein bounds of a cubic in t at the lens
//   corners) and Err a bound on covers' rounding of its edge values and det;
//   0 where a vertex is at or behind the eye or the triangle may be seen
//   edge-on. depth_floor(tri, time, s), for a time range inside the box, is
//   the smallest vertex w at the range's ends times s: every covered sample
//   of that range has a depth at least that, so a renderer whose stored
//   depths (strict depth test) are all below it can skip those samples.
//   Proof in docs/kernel.md, "Depth floors".
//
// int screen_footprint(ScreenBound b, vec2 lo, vec2 hi)
//   Where the screen rectangle [lo, hi] (NDC, lo <= hi) lies relative to b:
//   BC_FOOTPRINT_OUTSIDE (0: no sample in it passes screen_contains; also for
//   an empty b), BC_FOOTPRINT_INSIDE (2: every sample passes, the per-sample
//   test may be skipped) or BC_FOOTPRINT_PARTIAL (1).
//
// bool screen_contains(ScreenBound b, vec2 s)
//   Whether screen position s lies in the box and inside every hull edge.
//   False: no sample at s can be covered. Always false for an empty b.
//
// ---- The per-footprint sample bounds (detail/sample_bounds_body.inl) -------------------
//
// SampleBounds sample_bounds(MovingTriangle tri, vec2 s_lo, vec2 s_hi, int cull)
//   Bounds on the lens position and time of every sample in the screen
//   footprint [s_lo, s_hi] (NDC, s_lo <= s_hi: a pixel or a tile) that the
//   triangle can cover, per axis: a lens range, and time between lines in u
//   (v). BC_CULL_DUALSPACE computes them as in detail/dual_space_body.inl,
//   BC_CULL_TWO_STAGE as in detail/two_stage_body.inl, BC_CULL_EDGES as
//   two-stage plus the edge planes of detail/edge_bounds_body.inl over the
//   lens ranges and shutter interval two-stage leaves (none when a plane is not
//   finite), BC_CULL_HYPERPLANE as two-stage plus one plane per edge over that
//   box (detail/hyperplane_body.inl), empty also when a plane leaves nothing
//   of the box. empty = true: no sample
//   of the footprint can be covered. Fallback, no_sample_bounds(): a cull
//   without BC_CULL_BOUNDS_SAMPLES (bbox, hull: only the screen), non-finite input,
//   a swamped triangle (as for screen_bound). An axis whose bound cannot be
//   computed (a vertex behind the eye for dual-space's lens bound, an
//   overflow) keeps the whole lens or shutter on that axis.
//
// SampleBounds sample_bounds_in_tile(MovingTriangle tri, vec2 s_lo, vec2 s_hi, int cull, SampleBounds tile)
//   The bounds of footprint [s_lo, s_hi] inside a tile whose bounds `tile`
//   sample_bounds gave with the same cull (tile then footprint): for
//   BC_CULL_EDGES the footprint's two-stage bounds with the tile's edge planes
//   (their setup paid once per tile), for BC_CULL_HYPERPLANE the same with the
//   tile test on the footprint's own box; otherwise sample_bounds of the
//   footprint. Empty when tile is.
//
// SampleAxisBounds sample_axis_bounds(MovingTriangle tri, int axis, real s0, real s1, int cull)
// SampleBounds combine_axis_bounds(SampleAxisBounds x, SampleAxisBounds y)
//   sample_bounds's two halves: the lens range and time lines along one
//   axis (0: x and u, 1: y and v) depend only on the footprint's extent
//   [s0, s1] along it, so a renderer can share them between the footprints
//   of one column (row); combine_axis_bounds(x, y) is then
//   sample_bounds_without_planes (and so sample_bounds for a cull without
//   BC_CULL_ADDS_PLANES) on a triangle that sample_bounds_apply accepts
//   (planes need the whole box).
//
// bool sample_bounds_apply(MovingTriangle tri)
//   Whether the per-footprint bounds say anything for tri: false for
//   non-finite input or a swamped triangle (sample_bounds then gives
//   no_sample_bounds, and sample_axis_bounds must not be used).
//
// SampleBounds sample_bounds_without_planes(MovingTriangle tri, vec2 s_lo, vec2 s_hi, int cull)
// SampleBounds add_sample_planes(MovingTriangle tri, vec2 s_lo, vec2 s_hi, int cull, SampleBounds without)
//   sample_bounds in two steps: the cull's axis bounds (both axes combined;
//   no_sample_bounds() without BC_CULL_BOUNDS_SAMPLES or where the bounds do
//   not apply), then the cull's planes over the box they leave (edge planes
//   or hyperplanes and the hyperplanes' box test; `without` unchanged for a
//   cull without planes or an empty one). sample_bounds(tri, lo, hi, cull) is
//   add_sample_planes of the first where sample_bounds_apply(tri), else the
//   first, bit for bit. A renderer that bounds a tile first may add the edge
//   planes only where their setup pays: leaving them out culls less, never a
//   covered sample.
//
// SampleBounds with_tile_planes(vec2 s_lo, vec2 s_hi, int cull, SampleBounds footprint, SampleBounds tile)
//   A footprint [s_lo, s_hi]'s bounds without planes (sample_bounds_without_planes
//   or combine_axis_bounds of its axes) inside a tile whose bounds `tile`
//   carry the cull's planes: the footprint's bounds with the tile's planes,
//   and with BC_CULL_HYPERPLANES_PER_TILE the tile test on the footprint's
//   box. sample_bounds_in_tile is this of the footprint's own bounds.
//
// int plane_pieces(SampleBounds b)
// vec2 plane_piece_time(SampleBounds b, int q)
// bool plane_piece_culls_box(SampleBounds b, int q, vec2 s_lo, vec2 s_hi)
//   The planes b carries, in pieces of the shutter (0 pieces: none, as for
//   a cull without planes or planes that could not be set up), piece q's
//   shutter interval [lo, hi] in the bounds' time, and whether piece q's
//   planes leave no sample of the screen box [s_lo, s_hi] (holding the
//   samples' positions, their rounding included) inside b's lens ranges and
//   the piece's interval: then none of them passes sample_passes_at, and a
//   renderer may skip them unvisited (false when unsure).
//
// SampleBounds no_sample_bounds()
//   Bounds that keep every sample: lens [-1, 1]^2, time [0, 1], empty = false.
//
// bool sample_passes(SampleBounds b, vec2 uv, real t)
//   Whether (uv, t) lies inside the bounds. False: the triangle covers no
//   sample of the footprint with that lens position and time. Always false
//   for an empty b. BC_CULL_EDGES' planes are taken over the whole footprint.
//
// bool sample_passes_at(SampleBounds b, vec2 s, vec2 uv, real t)
//   sample_passes for a sample at screen position s (NDC, inside the
//   footprint b was made for): BC_CULL_EDGES' planes at s itself, which culls
//   more (docs/kernel.md, "Edge bounds": the sample's position). The same as
//   sample_passes for the other modes. sample_culled calls it.
//
// vec2 sample_time_range(SampleBounds b)
//   The shutter interval [lo, hi] within [0, 1] that holds every (uv, t) that
//   sample_passes lets through, for a renderer whose samples are sorted by
//   time. (1, 0) (lo > hi) for an empty b.
//
// ---- The raster glue both backends share (detail/raster_body.inl) ---------------------
// Raster coordinates are pixels, x right and y DOWN from the image's top-left
// corner; image_size is (width, height) in pixels (or cells of a lattice).
//
// vec2 raster_to_ndc(vec2 raster, vec2 image_size), vec2 ndc_to_raster(vec2 ndc, vec2 image_size)
//   Raster position <-> NDC (y up), each the inverse of the other up to rounding.
//
// vec2 pixel_sample_ndc(ivec2 pixel, vec2 offset, vec2 image_size)
//   The NDC of a sample at offset in [0, 1)^2 from pixel's top-left corner.
//
// vec4 pixel_rect_ndc(ivec4 rect, vec2 image_size)
//   The NDC box (lo.xy, hi.xy) of the inclusive pixel rectangle (x0, y0, x1, y1).
//
// ivec4 box_cell_rect(vec2 lo, vec2 hi, vec2 cells)
//   The inclusive cells (x0, y0, x1, y1), clamped to the lattice, that hold
//   every sample whose NDC lies in [lo, hi], widened by one margin rule
//   (docs/kernel.md, "The raster glue"); x0 > x1 when the box misses the image.
//
// ivec2 interleaved_cell(ivec2 tile, int slot, int tile_width)
// vec2 interleaved_sample_ndc(ivec2 cell, int scale, vec2 jitter, vec2 image_size)
//   Interleaved sampling: the lattice cell of a tile's slot, and the NDC of the
//   sample in a cell of a lattice scale times finer than the pixels.
//
// bool sample_culled(ScreenBound screen, bool check_screen, SampleBounds bounds, vec2 ndc, vec2 lens, real time)
// int sample_test(MovingTriangle tri, ScreenBound screen, bool check_screen, SampleBounds bounds,
//                 vec2 ndc, vec2 lens, real time, real near, out real depth)
//   The per-sample chain every backend runs: the lens/time bounds, the screen
//   bound (when check_screen), then covers. sample_culled is its first half;
//   sample_test returns BC_SAMPLE_CULLED 0 (not tested), BC_SAMPLE_MISSED 1 or
//   BC_SAMPLE_COVERED 2 (depth = the hit's view depth; else 0).
//
// bool depth_nearer(real depth, real nearest)
// real depth_key(real near, real depth), bool depth_key_wins(real key, uint index, real held_key, uint held_index)
//   The depth rules: the CPU z-buffer's (strictly nearer wins, so the lowest
//   index among equal depths), and the GPU's key near / depth in [0, 1] with
//   its tie rule (larger key, then lower index).
//
// vec2 camera_coc(real projection_scale, real lens_radius, real focus_depth)
//   (a, b) of c(w) = a + b w from camera parameters: thin_lens_coc, with
//   (0, 0) for a pinhole (lens_radius 0) whatever the focus.
//
// ---- The default sample pattern (detail/sampling_body.inl) -----------------------------
//
// PixelSample pixel_sample(uint px, uint py, uint index, uint spp, uint seed)
//   Sample index of pixel (px, py) with spp >= 1 samples per pixel (0 divides
//   by zero) and a seed: BC_PATTERN_HASHED, a pure function of its arguments,
//   so every backend draws the same samples. Positions are jittered strata of
//   an n x n grid (n^2 <= spp), time is stratified over spp strata, the two
//   decorrelated per pixel. index >= spp is allowed (unstratified position).
//
// PixelSampleSetup pixel_sample_setup(uint px, uint py, uint spp, uint seed)
// PixelSample pixel_sample_from(PixelSampleSetup setup, uint index)
//   pixel_sample in two steps, for a renderer that draws all of a pixel's
//   samples: the setup once per pixel, then each sample; the same samples.
//
// ---- Sample patterns (patterns.hpp: patterns<Real>, detail/patterns_body.inl) ----------
//
// Each returns a PixelSample like pixel_sample. pattern ids: BC_PATTERN_HASHED 0
// (pixel_sample), BC_PATTERN_RANDOM 1, BC_PATTERN_JITTERED 2, BC_PATTERN_SOBOL 3,
// BC_PATTERN_PADDED_SOBOL 4 (BC_PATTERN_COUNT 5); names in pattern_names.hpp.
//
// SamplerSetup sampler_setup(int pattern, uint px, uint py, uint spp, uint seed)
// PixelSample sampler_sample(SamplerSetup setup, uint index)
//   pattern_sample in two steps, the per-pixel work once: what every backend
//   draws its stochastic samples with (RenderSettings::sampler, --sampler).
//
// PixelSample pattern_sample(int pattern, uint px, uint py, uint index, uint spp, uint seed)
//   Sample index of spp of pixel (px, py) in pattern `pattern`; an unknown id
//   gives pixel_sample.
// PixelSample pattern_sample_tiled(int pattern, uint px, uint py, uint index, uint spp, uint seed, uint tile)
//   The same pattern repeated every tile pixels in x and y (tile 0 counts as
//   1), equal to the texture of make_pattern_tile.
// PixelSample pattern_random(uint px, uint py, uint index, uint seed)
//   Independent uniform samples (the baseline).
// PixelSample pattern_jittered(uint px, uint py, uint index, uint spp, uint seed)
//   Stratified in (x, y), (u, v) and t, the three paired by random
//   permutations; spp = 0 counts as 1, samples past floor(sqrt(spp))^2 are uniform.
// PixelSample pattern_sobol(uint px, uint py, uint index, uint spp, uint seed)
//   Owen-scrambled 5D Sobol (x, y, t, u, v), index scrambled per pixel: every
//   power-of-two prefix of a pixel's samples is well stratified.
// PixelSample pattern_padded_sobol(uint px, uint py, uint index, uint spp, uint seed)
//   Owen-scrambled Sobol (x, y) and (u, v, t), each with its own index
//   shuffle: position and lens each a (0, m, 2)-net.
// PixelSample interval_sample(uint px, uint py, uint stratum, uint strata, uint seed)
//   The interval method's sample: jittered, its time inside stratum `stratum`
//   of `strata` equal parts of the shutter.
// vec3 interleaved_tuple(uint k)
//   Tuple k (u, v, t) of the interleaved set: Halton bases 2 (t), 3 (radius^2)
//   and 5 (angle); (u, v) in the unit disk, t in [0, 1).
// uint interleaved_corner_colour(uint cx, uint cy, uint seed)
//   The colour, 0..2, of lattice corner (cx, cy) of the interleaved tiling.
// uint interleaved_prototype(uint tx, uint ty, uint seed)
//   The prototype, 0..80, of tile (tx, ty): its four corner colours in base 3.
// vec2 interleaved_jitter(uint gx, uint gy, uint seed)
//   Position in [0, 1)^2 of the sample of lattice cell (gx, gy) inside the cell.
// PixelSample accum_sample(uint k, uint seed)
//   Pass k of the accumulation buffer: one lens position, time and sub-pixel
//   offset for every pixel (rotated Halton points, different per seed).
//
// ---- Motion segments (detail/motion_segment_body.inl) -------------------------------
// A non-linear motion split into K linear segments: segment k is a
// MovingTriangle holding the vertices at the ends of its shutter window, so
// every function above works on it in its local time t' in [0, 1]
// (docs/kernel.md, "Motion segments").
//
// vec2 segment_window(int segment, int segments)
//   The window [k / K, (k + 1) / K] of segment k of K >= 1; the last ends at 1.
// bool segment_holds(vec2 window, real t)
//   Whether shutter time t is in the window, [lo, hi) (and t = hi when hi >= 1):
//   a sample outside its segment's window is not covered by that segment.
// real segment_local_time(vec2 window, real t)
//   (t - lo) / (hi - lo): the time to give the bounds and covers(); in [0, 1]
//   for every t the window holds.
// vec2 segment_shutter_range(vec2 window, vec2 local_range)
//   Local times [lo, hi] (e.g. sample_time_range of a segment) back to shutter
//   time, widened by the rounding and clipped to the window: conservative, every
//   held t whose local time is in [lo, hi] lies inside. (1, 0) when empty.
//
// ---- Secondary rays (detail/{dodecahedron,clusters,virtual_view,layer_trace}_body.inl) ----
//
// Depth of field through mirrors and glass after Xie, Sun and Wang (JCST 2013);
// docs/secondary-rays.md derives each formula. Positions in scene units,
// directions of any length unless said.
//
// int dodecahedron_facet(vec3 d)
//   The facet 0..11 of the regular dodecahedron whose normal maximises n . d
//   (three weighted sums of |d|, then the signs); ties: lowest family, a zero
//   component counts as positive; zero or NaN input gives a valid face.
// vec3 dodecahedron_normal(int face)
//   Unit normal of a facet (0, +-phi, +-1) ... / sqrt(1 + phi^2); zero outside 0..11.
// real cluster_position_scale(real largest)
// ClusterSums cluster_sums_empty(real position_scale)
// ClusterSums cluster_sums_add(ClusterSums s, vec3 position, vec3 direction)
// ClusterSums cluster_sums_merge(ClusterSums a, ClusterSums b)
// bool cluster_fixed_terms(vec3 position, vec3 direction, real position_scale, out ivec3 p, out ivec3 d)
// vec3 cluster_mean_position(ClusterSums s), vec3 cluster_direction_sum(ClusterSums s)
//   Exact sums over a cluster's pixels (positions, unit specular
//   directions, count) in 64-bit fixed point: the same bits in any order,
//   merged from any split, on every backend (a GPU adds the terms with
//   atomics); positions scaled by a power of two for the largest
//   |coordinate|. Their mean position (zero for no pixel) and direction sum.
// uint cluster_target_size(uint total_pixels, uint wanted_clusters)
// uint clusters_for_facet(uint facet_pixels, uint target_size, uint max_clusters)
//   The cluster rule: ceil(total / wanted) pixels per cluster, and per facet
//   round(pixels / target) clusters in [1, min(max_clusters <= 3, pixels)].
// int kmeans_nearest(vec3 position, vec3 centres[3], int count)
// uint kmeans_start_key(uint seed, int facet, uint index)
//   k-means by position: the nearest centre (lowest on ties); the seeded
//   start, the pixel of least key (a minimum in any order).
// VirtualViewFit virtual_view_begin(ClusterSums sums, real tan_half_fov, real min_near)
// VirtualViewFit virtual_view_begin_along(ClusterSums sums, vec3 axis, real tan_half_fov, real min_near)
// VirtualViewFit virtual_view_add(VirtualViewFit f, vec3 position, vec3 direction)
// VirtualView virtual_view_finish(VirtualViewFit f)
//   The virtual viewpoint of a cluster: along the mean specular direction (or
//   a given axis), backed off from the mean position by the smallest distance
//   that holds every pixel in the square frustum tan_half_fov (closed form);
//   near plane at the closest pixel. flags: BC_VIEW_DIRECTION_OUTSIDE (a ray
//   leaves every such frustum), BC_VIEW_EMPTY, BC_VIEW_BAD_PARAMETERS,
//   BC_VIEW_NOT_FINITE. Helpers: virtual_view_basis, virtual_view_point_backoff,
//   virtual_view_direction_inside.
// LayerView layer_view_from(VirtualView v, real far, int size)
// vec3 layer_project(LayerView v, vec3 p)
// LayerSegment layer_segment(LayerView v, vec3 origin, vec3 direction, real s_max, vec2 depth_range)
// vec4 layer_footprint(LayerView v, LayerSegment seg), int layer_step_count(LayerView v, LayerSegment seg)
// LayerTrace layer_trace_begin(LayerView v, LayerSegment seg, int layer_count, real thickness)
// LayerTrace layer_trace_step(LayerView v, LayerSegment seg, LayerTrace t, real depths[BC_LAYERS_MAX])
//   Image-space tracing (Lee et al. 2009/2010): a ray clipped to a layer
//   view's frustum and a min/max depth interval, stepped texel by texel; the
//   caller reads the layers' depths at the texel the trace names and passes
//   them to layer_trace_step until done; t.hit is the first hit, refined.
//
// Host-only C++ beside the kernel (not GLSL): make_pattern_tile (patterns.hpp),
// sample_pattern_name and parse_sample_pattern (pattern_names.hpp), the
// interleaved tile set make_interleaved_tiles and its cost
// (interleaved_tiles.hpp), the clustering and viewpoint drivers
// cluster_reflector_pixels and fit_virtual_view (secondary_clusters.hpp), the
// tracing loop trace_layers (layer_trace.hpp). Each has its own doc comment.
#pragma once

#include "detail/dialect.hpp"

#include <cmath>
#include <cstring>
#include <type_traits>

namespace blurcull {

// The bodies become static members of a class template whose member types play
// the role of GLSL's float, vec2, vec3, ... (the pattern of pbrt-v4, Blender and
// nvpro-samples for host/device shared code).
template <class Real>
struct kernel {
    static_assert(std::numeric_limits<Real>::is_iec559, "kernel<Real> needs IEEE float or double");

    using real = Real;
    using vec2 = glm::vec<2, Real, glm::defaultp>;
    using vec3 = glm::vec<3, Real, glm::defaultp>;
    using vec4 = glm::vec<4, Real, glm::defaultp>;
    using uint = std::uint32_t;
    // GLSL's ivec2, ivec4 (pixel positions and rectangles of the raster glue).
    using ivec2 = glm::ivec2;
    using ivec4 = glm::ivec4;
    // and ivec3, uvec3 (the exact cluster sums' 64-bit words).
    using ivec3 = glm::ivec3;
    using uvec3 = glm::uvec3;

    // GLSL built-ins the shared text uses, forwarded to GLM (whose names follow GLSL).
    template <class X> static X min(X a, X b) { return glm::min(a, b); }
    template <class X> static X max(X a, X b) { return glm::max(a, b); }
    template <class X> static X abs(X a) { return glm::abs(a); }
    template <class X> static X clamp(X a, X lo, X hi) { return glm::clamp(a, lo, hi); }
    template <class X> static X sqrt(X a) { return glm::sqrt(a); }
    template <class X> static X floor(X a) { return glm::floor(a); }
    template <class X> static X ceil(X a) { return glm::ceil(a); }
    template <class X> static X cos(X a) { return glm::cos(a); }
    template <class X> static X sin(X a) { return glm::sin(a); }
    // GLSL's frexp(x, out e) and ldexp(x, e): exact (the sampler's bc_div and
    // bc_sqrt scale by them). Normal floats take a path on their bits (the
    // sampler runs them several times per sample; <cmath>'s are calls),
    // with the same results as std::frexp and std::ldexp.
    static real frexp(real x, int& e) {
        if constexpr (std::is_same_v<Real, float>) {
            std::uint32_t bits = 0;
            std::memcpy(&bits, &x, sizeof bits);
            const std::uint32_t biased = (bits >> 23) & 0xffu;
            if (biased != 0u && biased != 0xffu) {
                e = int(biased) - 126;
                bits = (bits & 0x807fffffu) | (126u << 23);
                std::memcpy(&x, &bits, sizeof bits);
                return x;
            }
        }
        return std::frexp(x, &e);
    }
    static real ldexp(real x, int e) {
        if constexpr (std::is_same_v<Real, float>) {
            if (e >= -126 && e <= 127) {
                // x 2^e rounded once, as std::ldexp rounds it (exact unless it underflows).
                const std::uint32_t bits = std::uint32_t(e + 127) << 23;
                float scale = 0.0f;
                std::memcpy(&scale, &bits, sizeof scale);
                return x * scale;
            }
        }
        return std::ldexp(x, e);
    }
    static bool isnan(real a) { return a != a; }
    static bool isinf(real a) { return a == std::numeric_limits<real>::infinity() || a == -std::numeric_limits<real>::infinity(); }
    static real dot(vec2 a, vec2 b) { return glm::dot(a, b); }
    static real dot(vec3 a, vec3 b) { return glm::dot(a, b); }
    static vec3 cross(vec3 a, vec3 b) { return glm::cross(a, b); }
    // Machine epsilon and the largest finite value of `real` (GLSL prelude: constants).
    static constexpr real bc_epsilon() { return std::numeric_limits<real>::epsilon(); }
    static constexpr real bc_huge() { return std::numeric_limits<real>::max(); }
    // The smallest normal value: below it, rounding errors are absolute.
    static constexpr real bc_tiny() { return std::numeric_limits<real>::min(); }

    // One body per algorithm, each after the ones it uses (the GLSL build
    // emits them in this order too: shaders/CMakeLists.txt).
#include "detail/sampling_body.inl"
#include "detail/coc_motion_body.inl"
#include "detail/oracle_body.inl"
#include "detail/screen_bound_body.inl"
#include "detail/dual_space_body.inl"
#include "detail/two_stage_body.inl"
#include "detail/edge_bounds_body.inl"
#include "detail/hyperplane_body.inl"
#include "detail/sample_bounds_body.inl"
#include "detail/raster_body.inl"
#include "detail/dodecahedron_body.inl"
#include "detail/clusters_body.inl"
#include "detail/virtual_view_body.inl"
#include "detail/layer_trace_body.inl"
#include "detail/motion_segment_body.inl"
};

using kernelf = kernel<float>;
using kerneld = kernel<double>;

}  // namespace blurcull
