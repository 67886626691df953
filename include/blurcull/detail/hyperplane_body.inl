// Shared C++/GLSL text (see dialect.hpp): hyperplane culling
// (BC_CULL_HYPERPLANE), after Munkberg and Akenine-Moller, "Hyperplane
// Culling for Stochastic Rasterization", Eurographics 2012 short papers.
//
// Their two tests per screen tile, as this kernel realises them
// (docs/kernel.md, "Hyperplane culling"): test 1, linear bounds of the time
// in (u, t) and (v, t), is the two-stage lines; test 2 is one affine
// hyperplane in (x, y, u, v, t) per triangle edge, below the edge function
// over the tile's whole box of lens, time and screen position (one plane per
// edge, no pieces in time: the paper's hyperplane). A box lying wholly on the
// culled side of some plane holds no covered sample and is culled whole (the
// tile test: the box's corner farthest along the plane's normal); otherwise
// each sample is tested against the planes at its own position. The planes
// come from the edge polynomials of edge_bounds_body.inl, so the formula of
// the edge functions is written once.

// The three edges' hyperplanes over the footprint [s_lo, s_hi] (padded for
// the caller's rounding already) and the box u_range x v_range x t_range:
// one plane per edge over the whole box (BcEdgeBounds with one piece). No
// planes (BC_EDGE_NONE) where one is not finite.
BC_FN BcEdgeBounds bc_hyperplane_bounds(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, vec2 u_range,
                                        vec2 v_range, vec2 t_range) {
    BcEdgeBounds b = bc_no_edge_bounds();
    BcEdgeFunctions fn = bc_edge_functions(tri, s_lo, s_hi, u_range, v_range, t_range);
    BcEdgePlanes e = bc_no_edge_planes();
    for (int k = 0; k < 3; ++k) {
        // The whole box is one piece: xi_t itself, centre 0, half-width 1.
        vec2 slope_x = bc_screen_slope(fn.nx[k], fn.nx_radius[k], real(0), real(1));
        vec2 slope_y = bc_screen_slope(fn.ny[k], fn.ny_radius[k], real(0), real(1));
        if (!bc_edge_plane(fn.f[k], fn.extra[k], slope_x, slope_y, fn.u_box, fn.v_box, fn.t_box, fn.sx, fn.sy, k, e))
            return bc_no_edge_bounds();
    }
    e.mode = fn.mode;
    e.time = t_range;
    b.pieces = 1;
    b.piece[0] = e;
    return b;
}

// The largest value of edge k's plane (without its constant) over the box
// u in u_range, v in v_range, t in t_range, s in [s_lo, s_hi]: at the corner
// farthest along its normal. In .y the rounding of that sum.
BC_FN vec2 bc_hyperplane_reach(BC_IN(BcEdgePlanes) e, int k, vec2 u_range, vec2 v_range, vec2 t_range, vec2 s_lo,
                               vec2 s_hi) {
    real mu = max(e.du[k] * u_range.x, e.du[k] * u_range.y);
    real mv = max(e.dv[k] * v_range.x, e.dv[k] * v_range.y);
    real mt = max(e.dt[k] * t_range.x, e.dt[k] * t_range.y);
    real mx = max(e.dx[k] * s_lo.x, e.dx[k] * s_hi.x);
    real my = max(e.dy[k] * s_lo.y, e.dy[k] * s_hi.y);
    real reach = mu + mv + mt + mx + my;
    return vec2(reach, bc_err(abs(mu) + abs(mv) + abs(mt) + abs(mx) + abs(my)));
}

// The tile test: whether the planes e leave no sample of the box (every
// covered sample of which lies in it) that could be covered. One-sided: some
// plane is below zero at the box's best corner. Two-sided (a covered sample
// has every plane >= 0 with hi, or every plane <= 0 with lo): some plane is
// surely negative over the whole box and some surely positive.
BC_FN bool bc_hyperplane_box_empty(BC_IN(BcEdgePlanes) e, vec2 u_range, vec2 v_range, vec2 t_range, vec2 s_lo,
                                   vec2 s_hi) {
    if (e.mode == BC_EDGE_NONE) return false;
    bool below = false;  // some plane's largest value (with hi) is < 0
    bool above = false;  // some plane's smallest value (with lo) is > 0
    // The smallest value of a plane is minus the largest of its negation.
    BcEdgePlanes negated = e;
    negated.du = -e.du;
    negated.dv = -e.dv;
    negated.dt = -e.dt;
    negated.dx = -e.dx;
    negated.dy = -e.dy;
    for (int k = 0; k < 3; ++k) {
        vec2 most = bc_hyperplane_reach(e, k, u_range, v_range, t_range, s_lo, s_hi);
        if (most.x + e.hi[k] < -(most.y + bc_err(abs(e.hi[k])))) below = true;
        vec2 least = bc_hyperplane_reach(negated, k, u_range, v_range, t_range, s_lo, s_hi);
        if (e.lo[k] - least.x > least.y + bc_err(abs(e.lo[k]))) above = true;
    }
    if (e.mode == BC_EDGE_ONE_SIDED) return below;
    return below && above;
}
