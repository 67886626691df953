// Shared C++/GLSL text (see dialect.hpp): the per-footprint sample bounds
// that a renderer tests each sample against, dispatched by cull mode to
// dual_space_body.inl or two_stage_body.inl and then the planes of
// edge_bounds_body.inl or hyperplane_body.inl, by the cull's traits, and the
// shutter interval they leave. Needs every other kernel body.

struct SampleBounds {
    bool empty;    // no sample of the footprint can be covered
    vec2 u_range;  // lens u in [u_range.x, u_range.y]
    vec2 v_range;
    // Time as lines over the lens: t >= u_time_a.x + u_time_a.y u and
    // t <= u_time_a.z + u_time_a.w u, likewise for u_time_b, and over v for
    // v_time_a and v_time_b. Two-stage puts the lines of footprint condition A
    // in *_a and those of condition B in *_b; dual-space puts its one time
    // interval in *_a (slopes 0) and leaves *_b open ([0, 1]).
    vec4 u_time_a;
    vec4 u_time_b;
    vec4 v_time_a;
    vec4 v_time_b;
    BcEdgeBounds edges;  // BC_CULL_EDGES: the edges' planes in (u, v, t, s); none for the other modes
    vec2 centre;         // the footprint's centre (where sample_passes takes the planes)
};

// ---- per-footprint sample bounds ------------------------------------------------

// Bounds that keep every sample: the whole lens [-1, 1]^2 and shutter [0, 1].
BC_FN SampleBounds no_sample_bounds() {
    SampleBounds r;
    r.empty = false;
    r.u_range = vec2(real(-1), real(1));
    r.v_range = vec2(real(-1), real(1));
    r.u_time_a = vec4(real(0), real(0), real(1), real(0));
    r.u_time_b = r.u_time_a;
    r.v_time_a = r.u_time_a;
    r.v_time_b = r.u_time_a;
    r.edges = bc_no_edge_bounds();
    r.centre = vec2(real(0));
    return r;
}

// The shutter interval that holds every sample sample_passes lets through:
// each time line, linear in u (v), is extremal at an end of the lens range.
// (lo > hi when the bounds are empty.) Lets a renderer whose samples are
// sorted by time visit only that interval.
BC_FN vec2 sample_time_range(BC_IN(SampleBounds) b) {
    if (b.empty) return vec2(real(1), real(0));
    vec4 u = vec4(b.u_range.x, b.u_range.y, b.v_range.x, b.v_range.y);
    real lo = max(max(min(b.u_time_a.x + b.u_time_a.y * u.x, b.u_time_a.x + b.u_time_a.y * u.y),
                      min(b.u_time_b.x + b.u_time_b.y * u.x, b.u_time_b.x + b.u_time_b.y * u.y)),
                  max(min(b.v_time_a.x + b.v_time_a.y * u.z, b.v_time_a.x + b.v_time_a.y * u.w),
                      min(b.v_time_b.x + b.v_time_b.y * u.z, b.v_time_b.x + b.v_time_b.y * u.w)));
    real hi = min(min(max(b.u_time_a.z + b.u_time_a.w * u.x, b.u_time_a.z + b.u_time_a.w * u.y),
                      max(b.u_time_b.z + b.u_time_b.w * u.x, b.u_time_b.z + b.u_time_b.w * u.y)),
                  min(max(b.v_time_a.z + b.v_time_a.w * u.z, b.v_time_a.z + b.v_time_a.w * u.w),
                      max(b.v_time_b.z + b.v_time_b.w * u.z, b.v_time_b.z + b.v_time_b.w * u.w)));
    // A line's value inside the range can round a hair past its ends' values.
    real pad = bc_err(real(1) + max(abs(lo), abs(hi)));
    return vec2(max(lo - pad, real(0)), min(hi + pad, real(1)));
}

// One axis of the bounds: the lens range and the time lines along `axis`
// (0 = x with u, 1 = y with v). empty: no sample of the footprint can be covered.
struct SampleAxisBounds {
    bool empty;
    vec2 lens;
    vec4 lines_a;
    vec4 lines_b;
};

// The dual-space and two-stage bounds along one axis depend on the
// footprint's extent [s0, s1] along that axis alone (a renderer may share
// them between footprints in one row or column). For a cull with
// BC_CULL_BOUNDS_SAMPLES (the axes part of every such cull: dual-space's for
// BC_CULL_DUAL_SPACE_AXES, two-stage's otherwise); the triangle must be
// bc_triangle_boundable (sample_bounds_apply).
BC_FN SampleAxisBounds sample_axis_bounds(BC_IN(MovingTriangle) tri, int axis, real s0, real s1, int cull) {
    SampleAxisBounds r;
    r.empty = false;
    r.lines_a = vec4(real(0), real(0), real(1), real(0));
    r.lines_b = r.lines_a;
    // The caller's sample positions were rounded too.
    real pad = bc_err(max(real(1), max(abs(s0), abs(s1))));
    s0 = s0 - pad;
    s1 = s1 + pad;
    if ((cull_traits(cull) & BC_CULL_DUAL_SPACE_AXES) != 0) {
        vec2 tr;
        if (!bc_dual_time_bounds(tri, axis, s0, s1, tr)) {
            r.empty = true;
            return r;
        }
        r.lines_a = vec4(tr.x, real(0), tr.y, real(0));
        r.lens = bc_dual_lens_bounds(tri, axis, s0, s1);
    } else {
        BcEdgeCrossings crossings = bc_edge_crossings(tri, axis, s0, s1);
        r.lens = bc_two_stage_lens_bounds(tri, axis, crossings);
        if (r.lens.x > r.lens.y) {
            r.empty = true;
            return r;
        }
        // Without motion along this axis, and on one side of the focal
        // plane, the lens bounds are already where A and B both hold: the
        // time bounds would find the same range and times [0, 1].
        if (bc_axis_moves(tri, axis) || !bc_one_coc_sign(tri, axis)) {
            if (!bc_two_stage_time_bounds(tri, axis, s0, s1, crossings, r.lens, r.lines_a, r.lines_b)) {
                r.empty = true;
                return r;
            }
        }
    }
    if (r.lens.x > r.lens.y) r.empty = true;
    return r;
}

// The bounds of a footprint from its two axes' (empty when either is).
BC_FN SampleBounds combine_axis_bounds(BC_IN(SampleAxisBounds) x, BC_IN(SampleAxisBounds) y) {
    SampleBounds r = no_sample_bounds();
    if (x.empty || y.empty) {
        r.empty = true;
        return r;
    }
    r.u_range = x.lens;
    r.u_time_a = x.lines_a;
    r.u_time_b = x.lines_b;
    r.v_range = y.lens;
    r.v_time_a = y.lines_a;
    r.v_time_b = y.lines_b;
    return r;
}

// How far the caller's rounded sample positions can stray outside the
// footprint [s_lo, s_hi], per axis.
BC_FN vec2 bc_footprint_pad(vec2 s_lo, vec2 s_hi) {
    return vec2(bc_err(max(real(1), max(abs(s_lo.x), abs(s_hi.x)))),
                bc_err(max(real(1), max(abs(s_lo.y), abs(s_hi.y)))));
}

// The edge planes over the box the two-stage bounds r of the footprint
// [s_lo, s_hi] leave (on the padded footprint), added to r (add_sample_planes
// for BC_CULL_EDGE_PLANES_PER_BLOCK).
BC_FN SampleBounds bc_add_edge_planes(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi,
                                      BC_IN(SampleBounds) two_stage) {
    SampleBounds r = two_stage;
    if (r.empty) return r;
    vec2 pad = bc_footprint_pad(s_lo, s_hi);
    vec2 times = sample_time_range(r);
    if (times.x > times.y) {
        r.empty = true;
        return r;
    }
    r.edges = bc_edge_bounds(tri, s_lo - pad, s_hi + pad, r.u_range, r.v_range, times);
    // Named first: GLSL's `precise` (the emission's) reaches no argument of a
    // call whose result is swizzled (glslang's reading), so the sum is a variable.
    vec2 padded_lo = s_lo - pad;
    vec2 padded_hi = s_hi + pad;
    r.centre = vec2(bc_box_axis(padded_lo.x, padded_hi.x).x, bc_box_axis(padded_lo.y, padded_hi.y).x);
    return r;
}

// Whether the per-footprint bounds apply to the triangle at all: false for
// non-finite input or a swamped triangle, whose sample_bounds are
// no_sample_bounds() (and whose axis bounds must then not be used).
BC_FN bool sample_bounds_apply(BC_IN(MovingTriangle) tri) { return bc_triangle_boundable(tri); }

// The cull's per-axis bounds of the footprint [s_lo, s_hi] combined, without
// its planes: what sample_bounds gives before add_sample_planes.
// no_sample_bounds() for a cull without BC_CULL_BOUNDS_SAMPLES or a
// triangle the bounds do not apply to.
BC_FN SampleBounds sample_bounds_without_planes(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, int cull) {
    SampleBounds r = no_sample_bounds();
    if ((cull_traits(cull) & BC_CULL_BOUNDS_SAMPLES) == 0) return r;
    if (!bc_triangle_boundable(tri)) return r;
    SampleAxisBounds x = sample_axis_bounds(tri, 0, s_lo.x, s_hi.x, cull);
    if (x.empty) {
        r.empty = true;
        return r;
    }
    SampleAxisBounds y = sample_axis_bounds(tri, 1, s_lo.y, s_hi.y, cull);
    return combine_axis_bounds(x, y);
}

// The cull's planes over the box `without` (sample_bounds_without_planes of
// the same footprint and cull) leaves, added to it: the edge planes for
// BC_CULL_EDGE_PLANES_PER_BLOCK, the hyperplanes and their box test for
// BC_CULL_HYPERPLANES_PER_TILE (on the padded footprint); `without` itself
// for a cull without planes or when it is empty. A renderer may bound first
// and add the edge planes only where their setup pays: leaving them out
// loses culling, never a covered sample.
BC_FN SampleBounds add_sample_planes(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, int cull,
                                     BC_IN(SampleBounds) without) {
    int traits = cull_traits(cull);
    SampleBounds r = without;
    if (r.empty) return r;
    if ((traits & BC_CULL_EDGE_PLANES_PER_BLOCK) != 0) return bc_add_edge_planes(tri, s_lo, s_hi, r);
    if ((traits & BC_CULL_HYPERPLANES_PER_TILE) == 0) return r;
    // Hyperplane: one plane per edge over the whole box, and the box culled
    // whole when a plane leaves nothing (on the padded footprint).
    vec2 pad = bc_footprint_pad(s_lo, s_hi);
    vec2 times = sample_time_range(r);
    if (times.x > times.y) {
        r.empty = true;
        return r;
    }
    r.edges = bc_hyperplane_bounds(tri, s_lo - pad, s_hi + pad, r.u_range, r.v_range, times);
    r.empty = bc_hyperplane_box_empty(r.edges.piece[0], r.u_range, r.v_range, times, s_lo - pad, s_hi + pad);
    // Named first: GLSL's `precise` (the emission's) reaches no argument of a
    // call whose result is swizzled (glslang's reading), so the sum is a variable.
    vec2 padded_lo = s_lo - pad;
    vec2 padded_hi = s_hi + pad;
    r.centre = vec2(bc_box_axis(padded_lo.x, padded_hi.x).x, bc_box_axis(padded_lo.y, padded_hi.y).x);
    return r;
}

// Bounds on the lens and time of every sample in the screen footprint
// [s_lo, s_hi] (a pixel or a tile) that the triangle can cover: the cull's
// axis bounds, then its planes. A cull without BC_CULL_BOUNDS_SAMPLES
// (bbox, hull) bounds only the screen (see screen_bound).
BC_FN SampleBounds sample_bounds(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, int cull) {
    SampleBounds r = sample_bounds_without_planes(tri, s_lo, s_hi, cull);
    if ((cull_traits(cull) & BC_CULL_ADDS_PLANES) == 0 || !bc_triangle_boundable(tri)) return r;
    return add_sample_planes(tri, s_lo, s_hi, cull, r);
}

// BC_CULL_HYPERPLANE's tile test on a footprint [s_lo, s_hi] inside the
// tile whose planes r carries: those planes hold at every covered sample of
// the tile, and every covered sample of the footprint lies in the
// footprint's own box (its two-stage bounds r, its padded screen box).
BC_FN bool bc_hyperplane_footprint_empty(BC_IN(SampleBounds) r, vec2 s_lo, vec2 s_hi) {
    vec2 times = sample_time_range(r);
    if (times.x > times.y) return true;
    vec2 pad = bc_footprint_pad(s_lo, s_hi);
    return bc_hyperplane_box_empty(r.edges.piece[0], r.u_range, r.v_range, times, s_lo - pad, s_hi + pad);
}

// A footprint [s_lo, s_hi]'s bounds without planes (sample_bounds_without_planes,
// or combine_axis_bounds of its axes) inside a tile whose bounds `tile`
// carry the cull's planes: the footprint's bounds with the tile's planes,
// and for BC_CULL_HYPERPLANES_PER_TILE the footprint culled whole when a
// tile plane leaves nothing of its own box. Empty when tile is.
BC_FN SampleBounds with_tile_planes(vec2 s_lo, vec2 s_hi, int cull, BC_IN(SampleBounds) footprint,
                                    BC_IN(SampleBounds) tile) {
    if (tile.empty) return tile;
    SampleBounds r = footprint;
    if (r.empty) return r;
    r.edges = tile.edges;
    r.centre = tile.centre;
    if ((cull_traits(cull) & BC_CULL_HYPERPLANES_PER_TILE) != 0) r.empty = bc_hyperplane_footprint_empty(r, s_lo, s_hi);
    return r;
}

// Bounds of a footprint [s_lo, s_hi] inside a tile whose bounds `tile` came
// from sample_bounds with the same cull (tile then footprint): for a cull
// that adds planes, the footprint's own bounds without planes with the
// tile's planes (with_tile_planes), which hold for every sample of the tile
// inside the tile's bounds (and a sample outside those cannot be covered:
// docs/kernel.md, "Edge bounds", tile then footprint), so the planes' setup
// is paid once per tile; for every other cull the footprint's own bounds.
// An empty tile gives empty bounds.
BC_FN SampleBounds sample_bounds_in_tile(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, int cull,
                                         BC_IN(SampleBounds) tile) {
    if (tile.empty) return tile;
    if ((cull_traits(cull) & BC_CULL_ADDS_PLANES) == 0) return sample_bounds(tri, s_lo, s_hi, cull);
    return with_tile_planes(s_lo, s_hi, cull, sample_bounds_without_planes(tri, s_lo, s_hi, cull), tile);
}

// The planes' pieces in time of bounds b (each over part of the shutter): 0
// when b carries no planes (a cull without them, or planes that could not
// be set up), else 1 to BC_EDGE_PIECES.
BC_FN int plane_pieces(BC_IN(SampleBounds) b) { return b.edges.piece[0].mode == BC_EDGE_NONE ? 0 : b.edges.pieces; }

// The shutter interval [lo, hi] (the bounds' local time) of piece q < plane_pieces(b).
BC_FN vec2 plane_piece_time(BC_IN(SampleBounds) b, int q) { return b.edges.piece[q].time; }

// Whether piece q's planes leave no sample of the screen box [s_lo, s_hi]
// (NDC, holding the sample positions it is asked for, their rounding
// included) inside b's lens ranges and the piece's shutter interval: then no
// such sample passes sample_passes_at. False when unsure.
BC_FN bool plane_piece_culls_box(BC_IN(SampleBounds) b, int q, vec2 s_lo, vec2 s_hi) {
    return bc_edge_piece_culls_box(b.edges.piece[q], s_lo, s_hi, b.u_range, b.v_range);
}

// The lens and time bounds of sample_passes without the edge planes.
BC_FN bool bc_lens_time_passes(BC_IN(SampleBounds) b, vec2 uv, real t) {
    if (b.empty) return false;
    if (uv.x < b.u_range.x || uv.x > b.u_range.y || uv.y < b.v_range.x || uv.y > b.v_range.y) return false;
    if (t < b.u_time_a.x + b.u_time_a.y * uv.x || t > b.u_time_a.z + b.u_time_a.w * uv.x) return false;
    if (t < b.v_time_a.x + b.v_time_a.y * uv.y || t > b.v_time_a.z + b.v_time_a.w * uv.y) return false;
    if (t < b.u_time_b.x + b.u_time_b.y * uv.x || t > b.u_time_b.z + b.u_time_b.w * uv.x) return false;
    if (t < b.v_time_b.x + b.v_time_b.y * uv.y || t > b.v_time_b.z + b.v_time_b.w * uv.y) return false;
    return true;
}

// Whether sample (uv, t), anywhere in the footprint, lies inside the bounds:
// false means the triangle cannot cover it (the caller skips the exact test).
// The edge planes are taken at the footprint's centre and widened over it;
// sample_passes_at tests them at the sample's own position and culls more.
BC_FN bool sample_passes(BC_IN(SampleBounds) b, vec2 uv, real t) {
    if (!bc_lens_time_passes(b, uv, t)) return false;
    return bc_edge_bounds_pass_at(b.edges, b.centre, uv, t, real(1));
}

// sample_passes for a sample at screen position s (NDC, inside the
// footprint the bounds were made for): the edge planes at s itself.
BC_FN bool sample_passes_at(BC_IN(SampleBounds) b, vec2 s, vec2 uv, real t) {
    if (!bc_lens_time_passes(b, uv, t)) return false;
    return bc_edge_bounds_pass_at(b.edges, s, uv, t, real(0));
}
