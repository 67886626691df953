// Shared C++/GLSL text (see dialect.hpp): the per-footprint sample bounds
// that a renderer tests each sample against, dispatched by cull method to the
// dual-space, two-stage (kernel_body.inl) and edge (edge_bounds_body.inl)
// bounds, and the shutter interval they leave. Needs every other kernel body.

struct SampleBounds {
    bool empty;    // no sample of the footprint can be covered
    vec2 u_range;  // lens u in [u_range.x, u_range.y]
    vec2 v_range;
    vec4 tx;       // t >= tx.x + tx.y u  and  t <= tx.z + tx.w u
    vec4 tx2;      // a second pair of lines in (u, t), same form
    vec4 ty;       // t >= ty.x + ty.y v  and  t <= ty.z + ty.w v
    vec4 ty2;
    BcEdgeBounds edges;  // BC_CULL_EDGES: the edges' planes in (u, v, t)
};

// ---- per-footprint sample bounds ------------------------------------------------

BC_FN SampleBounds no_sample_bounds() {
    SampleBounds r;
    r.empty = false;
    r.u_range = vec2(real(-1), real(1));
    r.v_range = vec2(real(-1), real(1));
    r.tx = vec4(real(0), real(0), real(1), real(0));
    r.tx2 = r.tx;
    r.ty = r.tx;
    r.ty2 = r.tx;
    r.edges = bc_no_edge_bounds();
    return r;
}

// The shutter interval that holds every sample sample_passes lets through:
// each time line, linear in u (v), is extremal at an end of the lens range.
// (lo > hi when the bounds are empty.) Lets a renderer whose samples are
// sorted by time visit only that interval.
BC_FN vec2 sample_time_range(BC_IN(SampleBounds) b) {
    if (b.empty) return vec2(real(1), real(0));
    vec4 u = vec4(b.u_range.x, b.u_range.y, b.v_range.x, b.v_range.y);
    real lo = max(max(min(b.tx.x + b.tx.y * u.x, b.tx.x + b.tx.y * u.y),
                      min(b.tx2.x + b.tx2.y * u.x, b.tx2.x + b.tx2.y * u.y)),
                  max(min(b.ty.x + b.ty.y * u.z, b.ty.x + b.ty.y * u.w),
                      min(b.ty2.x + b.ty2.y * u.z, b.ty2.x + b.ty2.y * u.w)));
    real hi = min(min(max(b.tx.z + b.tx.w * u.x, b.tx.z + b.tx.w * u.y),
                      max(b.tx2.z + b.tx2.w * u.x, b.tx2.z + b.tx2.w * u.y)),
                  min(max(b.ty.z + b.ty.w * u.z, b.ty.z + b.ty.w * u.w),
                      max(b.ty2.z + b.ty2.w * u.z, b.ty2.z + b.ty2.w * u.w)));
    // A line's value inside the range can round a hair past its ends' values.
    real pad = bc_err(real(1) + max(abs(lo), abs(hi)));
    return vec2(max(lo - pad, real(0)), min(hi + pad, real(1)));
}

// Bounds on the lens and time of every sample in the screen footprint
// [s_lo, s_hi] (a pixel or a tile) that the triangle can cover.
// BC_CULL_BBOX and BC_CULL_HULL bound only the screen (see screen_bound).
BC_FN SampleBounds sample_bounds(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, int method) {
    SampleBounds r = no_sample_bounds();
    if (method != BC_CULL_DUALSPACE && method != BC_CULL_CLIP2 && method != BC_CULL_EDGES) return r;
    if (!bc_triangle_boundable(tri)) return r;
    // The caller's sample positions were rounded too.
    vec2 pad = vec2(bc_err(max(real(1), max(abs(s_lo.x), abs(s_hi.x)))),
                    bc_err(max(real(1), max(abs(s_lo.y), abs(s_hi.y)))));
    s_lo = s_lo - pad;
    s_hi = s_hi + pad;
    for (int axis = 0; axis < 2; ++axis) {
        vec2 lens;
        vec4 lines = vec4(real(0), real(0), real(1), real(0));
        vec4 lines2 = lines;
        if (method == BC_CULL_DUALSPACE) {
            vec2 tr;
            if (!bc_dual_time(tri, axis, s_lo[axis], s_hi[axis], tr)) {
                r.empty = true;
                return r;
            }
            lines = vec4(tr.x, real(0), tr.y, real(0));
            lens = bc_dual_lens(tri, axis, s_lo[axis], s_hi[axis]);
        } else {
            BcEdgeCrossings crossings = bc_edge_crossings(tri, axis, s_lo[axis], s_hi[axis]);
            lens = bc_stage1(tri, axis, crossings);
            if (lens.x > lens.y) {
                r.empty = true;
                return r;
            }
            // Without motion along this axis, and on one side of the focal
            // plane, stage 1's range is already where A and B both hold:
            // stage 2 would find the same range and times [0, 1].
            if (bc_axis_moves(tri, axis) || !bc_one_coc_sign(tri, axis)) {
                if (!bc_stage2(tri, axis, s_lo[axis], s_hi[axis], crossings, lens, lines, lines2)) {
                    r.empty = true;
                    return r;
                }
            }
        }
        if (lens.x > lens.y) {
            r.empty = true;
            return r;
        }
        if (axis == 0) {
            r.u_range = lens;
            r.tx = lines;
            r.tx2 = lines2;
        } else {
            r.v_range = lens;
            r.ty = lines;
            r.ty2 = lines2;
        }
    }
    if (method == BC_CULL_EDGES) {
        vec2 times = sample_time_range(r);
        if (times.x > times.y) {
            r.empty = true;
            return r;
        }
        r.edges = bc_edge_bounds(tri, s_lo, s_hi, r.u_range, r.v_range, times);
    }
    return r;
}

BC_FN bool sample_passes(BC_IN(SampleBounds) b, vec2 uv, real t) {
    if (b.empty) return false;
    if (uv.x < b.u_range.x || uv.x > b.u_range.y || uv.y < b.v_range.x || uv.y > b.v_range.y) return false;
    if (t < b.tx.x + b.tx.y * uv.x || t > b.tx.z + b.tx.w * uv.x) return false;
    if (t < b.ty.x + b.ty.y * uv.y || t > b.ty.z + b.ty.w * uv.y) return false;
    if (t < b.tx2.x + b.tx2.y * uv.x || t > b.tx2.z + b.tx2.w * uv.x) return false;
    if (t < b.ty2.x + b.ty2.y * uv.y || t > b.ty2.z + b.ty2.w * uv.y) return false;
    return bc_edge_bounds_pass(b.edges, uv, t);
}
