// Shared C++/GLSL text (see dialect.hpp): the clip-space two-stage
// per-footprint bounds of Wu et al. 2015 (BC_CULL_TWO_STAGE): lens bounds,
// then time bounds as lines in (u, t). Footprint conditions A and B are
// stated in dual_space_body.inl and docs/kernel.md. Needs coc_motion_body.inl
// and screen_bound_body.inl (bc_turn).

#define BC_BREAKS_MAX 8

// Where each vertex end meets the footprint's edges: the lens position
// u_j(s) = (s w_j - x_j) / c_j (the thesis's u = F (s w - x) / (R' (w - F))),
// for s = s0 (`near_edge`) and s = s1 (`far_edge`), with a bound on the
// rounding error of each. They are stage 1's bounds and stage 2's roots.
// err[j] < 0 marks c_j = 0 (no such position).
struct BcEdgeCrossings {
    real near_edge[6];
    real far_edge[6];
    real err[6];
};

BC_FN BcEdgeCrossings bc_edge_crossings(BC_IN(MovingTriangle) tri, int axis, real s0, real s1) {
    BcEdgeCrossings x;
    real s_max = max(abs(s0), abs(s1));
    for (int j = 0; j < 6; ++j) {
        real c = tri.c[j][axis];
        x.near_edge[j] = real(0);
        x.far_edge[j] = real(0);
        x.err[j] = real(-1);
        if (c == real(0)) continue;
        real inv_c = real(1) / c;
        real px = tri.p[j][axis];
        real w = tri.p[j].z;
        x.near_edge[j] = (s0 * w - px) * inv_c;
        x.far_edge[j] = (s1 * w - px) * inv_c;
        x.err[j] = bc_err((abs(px) + s_max * abs(w)) * abs(inv_c) + max(abs(x.near_edge[j]), abs(x.far_edge[j])));
        if (!bc_finite(x.near_edge[j]) || !bc_finite(x.far_edge[j]) || !bc_finite(x.err[j])) x.err[j] = bc_huge();
    }
    return x;
}

// Whether the triangle's offsets along this axis change over the shutter.
BC_FN bool bc_axis_moves(BC_IN(MovingTriangle) tri, int axis) {
    bool moves = false;
    for (int i = 0; i < 3; ++i) {
        if (tri.p[i][axis] != tri.p[i + 3][axis] || tri.p[i].z != tri.p[i + 3].z ||
            tri.c[i][axis] != tri.c[i + 3][axis])
            moves = true;
    }
    return moves;
}

// Whether every vertex end's CoC along this axis has one strict sign (the
// triangle stays on one side of the focal plane).
BC_FN bool bc_one_coc_sign(BC_IN(MovingTriangle) tri, int axis) {
    bool positive = true;
    bool negative = true;
    for (int j = 0; j < 6; ++j) {
        if (!(tri.c[j][axis] > real(0))) positive = false;
        if (!(tri.c[j][axis] < real(0))) negative = false;
    }
    return positive || negative;
}

// Stage 1, lens bounds. While every c has one strict sign, u_j(t) is a
// monotone linear fraction of t, so A and B need u <= max_j u_j(s1) and
// u >= min_j u_j(s0) (c > 0; c < 0 swaps s0 and s1). A vertex on or across
// the focal plane (mixed signs, or c = 0) leaves the whole lens.
BC_FN vec2 bc_two_stage_lens_bounds(BC_IN(MovingTriangle) tri, int axis, BC_IN(BcEdgeCrossings) x) {
    vec2 r = vec2(real(-1), real(1));
    if (!bc_one_coc_sign(tri, axis)) return r;
    bool positive = tri.c[0][axis] > real(0);
    real lo = bc_huge();
    real hi = -bc_huge();
    for (int j = 0; j < 6; ++j) {
        if (!(x.err[j] < bc_huge())) return r;
        if (positive) {
            lo = min(lo, x.near_edge[j] - x.err[j]);
            hi = max(hi, x.far_edge[j] + x.err[j]);
        } else {
            lo = min(lo, x.far_edge[j] - x.err[j]);
            hi = max(hi, x.near_edge[j] + x.err[j]);
        }
    }
    return vec2(max(lo, real(-1)), min(hi, real(1)));
}

// A line below (side = 1) or above (side = -1) the crossing time
// r(u) = N(u) / D(u) of one vertex on [a, b], N = e0 + u c0,
// D = (e0 - e1) + u (c0 - c1), returned as its values at a and b. A linear
// fraction has one curvature wherever D keeps its sign: the mid-point tangent
// lies below it where it is convex and the chord where it is concave (above:
// the other way round). r'' = -2 dc (c0 de - e0 dc) / D^3, so the sign of
// `bend` times D tells which; when rounding leaves the sign in doubt both are
// taken. Where D may vanish on [a, b] nothing better than 0 (below) or 1
// (above) is known. `tol` bounds the error of e0 and of e0 - e1.
BC_FN vec2 bc_crossing_line(real e0, real e1, real c0, real c1, real tol, real a, real b, real side) {
    vec2 fallback = side > real(0) ? vec2(real(0)) : vec2(real(1));
    real dc = c0 - c1;
    real de = e0 - e1;
    real da = de + a * dc;
    real db = de + b * dc;
    if (!(da * db > real(0)) || min(abs(da), abs(db)) <= tol) return fallback;
    real bend = dc * (c0 * de - e0 * dc);
    real bend_error = abs(dc) * ((abs(c0) + abs(dc)) * tol + bc_err(abs(c0 * de) + abs(e0 * dc)));
    bool sure = abs(bend) > bend_error;
    bool convex = bend * da < real(0);
    bool tangent = !sure || (side > real(0)) == convex;
    bool chord = !sure || !tangent;
    // BC_PRECISE: without it Mesa reorders `(r - slope h) - pad` and the
    // shader's line moves by an ULP, which the fit over tiny pieces magnifies.
    BC_PRECISE vec2 line = vec2(side * bc_huge());  // replaced below by the lower (upper) of the candidates
    if (chord) {
        real ia = real(1) / da;
        real ib = real(1) / db;
        real ra = (e0 + a * c0) * ia;
        real rb = (e0 + b * c0) * ib;
        real pad = real(2) * tol * (real(1) + max(abs(ra), abs(rb))) * max(abs(ia), abs(ib)) +
                   bc_err(real(1) + abs(ra) + abs(rb));
        line = vec2(ra, rb) - vec2(side * pad);
    }
    if (tangent) {
        real h = real(0.5) * (b - a);
        real m = a + h;
        real im = real(1) / (de + m * dc);
        real rm = (e0 + m * c0) * im;
        real slope = (c0 - rm * dc) * im;
        real pad = real(2) * tol * abs(im) * ((real(1) + abs(rm)) * (real(1) + h * abs(dc) * abs(im)) + h * abs(slope)) +
                   bc_err(real(1) + abs(rm) + abs(slope) * h);
        BC_PRECISE vec2 t = vec2(rm - slope * h, rm + slope * h) - vec2(side * pad);
        line = side > real(0) ? min(line, t) : max(line, t);
    }
    if (!bc_finite(line.x) || !bc_finite(line.y)) return fallback;
    return line;
}

// Stage 2 on one lens interval [a, b] for condition A written as
// "some offset (e_k + u c_k) <= 0" (B is passed negated). The offsets' signs
// are taken at the interval's middle with tolerance tol (the interval holds no
// root of an offset, or is a single point). The covered times span
//   from 0 if some vertex starts inside, else the earliest crossing of a vertex
//   that ends inside; to 1 if some vertex ends inside, else the latest
//   crossing of a vertex that starts inside;
// nothing if no vertex is ever inside. Returns false for nothing, else in
// `lines` (lower at a, lower at b, upper at a, upper at b).
BC_FN bool bc_covered_times(vec3 e0, vec3 e1, vec3 c0, vec3 c1, vec3 tol0, vec3 tol1, real a, real b,
                            BC_OUT(vec4) lines) {
    lines = vec4(real(0), real(0), real(1), real(1));
    real m = real(0.5) * (a + b);
    bool starts_inside = false;
    bool ends_inside = false;
    vec3 d0;
    vec3 d1;
    for (int i = 0; i < 3; ++i) {
        d0[i] = e0[i] + m * c0[i];
        d1[i] = e1[i] + m * c1[i];
        if (!bc_finite(d0[i]) || !bc_finite(d1[i])) return true;
        if (d0[i] <= tol0[i]) starts_inside = true;
        if (d1[i] <= tol1[i]) ends_inside = true;
    }
    if (!starts_inside && !ends_inside) return false;
    vec2 lower = vec2(bc_huge());
    vec2 upper = vec2(-bc_huge());
    for (int i = 0; i < 3; ++i) {
        // A vertex enters (ends inside, so not when one starts inside) or
        // leaves (starts inside, so not when one ends inside), never both.
        if (!starts_inside && d1[i] <= tol1[i])
            lower = min(lower, bc_crossing_line(e0[i], e1[i], c0[i], c1[i], tol0[i] + tol1[i], a, b, real(1)));
        if (!ends_inside && d0[i] <= tol0[i])
            upper = max(upper, bc_crossing_line(e0[i], e1[i], c0[i], c1[i], tol0[i] + tol1[i], a, b, real(-1)));
    }
    if (!starts_inside) {
        lines.x = lower.x;
        lines.y = lower.y;
    }
    if (!ends_inside) {
        lines.z = upper.x;
        lines.w = upper.y;
    }
    return true;
}

// Best line below (sign = 1) or above (sign = -1) the points (u_j, value_j)
// that are set (|value| < huge), maximising (minimising) it at the middle of
// [lo, hi]: the edge of the lower (upper) convex hull that spans the middle.
// Returns (offset, slope): line(u) = offset + slope u.
BC_FN vec2 bc_fit_line(real u[BC_BREAKS_MAX], real value[BC_BREAKS_MAX], int n, real sign, real lo, real hi) {
    int hull[BC_BREAKS_MAX];
    int h = 0;
    for (int j = 0; j < n; ++j) {
        if (!(abs(value[j]) < bc_huge())) continue;
        vec2 pj = vec2(u[j], sign * value[j]);
        while (h >= 2) {
            if (!(bc_turn(vec2(u[hull[h - 2]], sign * value[hull[h - 2]]),
                          vec2(u[hull[h - 1]], sign * value[hull[h - 1]]), pj) <= real(0)))
                break;
            h = h - 1;
        }
        hull[h] = j;
        h = h + 1;
    }
    if (h == 0) return vec2(real(0));
    real mid = real(0.5) * (lo + hi);
    int k = 0;
    while (k + 2 < h && u[hull[k + 1]] < mid) k = k + 1;
    if (h == 1) return vec2(value[hull[0]], real(0));
    real ua = u[hull[k]];
    real ub = u[hull[k + 1]];
    real va = value[hull[k]];
    real vb = value[hull[k + 1]];
    real slope = (vb - va) / (ub - ua);
    real offset = va - slope * ua;
    // rounding of the hull's turns and of this line: widen away from the points
    real pad = bc_err(real(2) + abs(va) + abs(vb) + abs(slope) * (real(2) + abs(ua) + abs(ub)));
    if (!bc_finite(slope) || !bc_finite(offset) || !bc_finite(pad)) return vec2(sign > real(0) ? -bc_huge() : bc_huge(), real(0));
    return vec2(offset - sign * pad, slope);
}

// Stage 2 for one condition ("some offset e_k + u c_k <= 0", k over the three
// vertices at t = 0 and t = 1): split the lens range at the offsets' roots,
// bound the covered times on every piece, and fit one line below their lower
// ends and one above their upper ends. Narrows `lens` to where the condition
// can hold. False: it holds nowhere in the lens range.
BC_FN bool bc_condition_lines(vec3 e0, vec3 e1, vec3 c0, vec3 c1, vec3 tol0, vec3 tol1, vec3 roots0, vec3 roots1,
                              vec3 root_err0, vec3 root_err1, BC_INOUT(vec2) lens, BC_OUT(vec4) lines) {
    lines = vec4(real(0), real(0), real(1), real(0));
    vec4 r;
    bool defocus = false;
    for (int i = 0; i < 3; ++i) {
        if (c0[i] != real(0) || c1[i] != real(0)) defocus = true;
    }
    if (!defocus) {
        // The offsets do not depend on u: one constant interval.
        if (!bc_covered_times(e0, e1, c0, c1, tol0, tol1, real(0), real(0), r)) return false;
        lines = vec4(r.x, real(0), r.z, real(0));
        return true;
    }
    // Break points: the lens range and the roots inside it, sorted.
    real u[BC_BREAKS_MAX];
    int n = 0;
    u[n] = lens.x;
    n = n + 1;
    real root_error = real(0);
    for (int j = 0; j < 6; ++j) {
        int i = j % 3;
        real err = j < 3 ? root_err0[i] : root_err1[i];
        if (err < real(0)) continue;  // c = 0: this offset has no root
        real root = j < 3 ? roots0[i] : roots1[i];
        if (!(root > lens.x && root < lens.y)) continue;
        bool known = false;
        for (int q = 0; q < n; ++q) {
            if (u[q] == root) known = true;
        }
        if (known) continue;
        root_error = max(root_error, err);
        int q = n;
        while (q > 1 && u[q - 1] > root) {
            u[q] = u[q - 1];
            q = q - 1;
        }
        u[q] = root;
        n = n + 1;
    }
    u[n] = lens.y;
    n = n + 1;
    real lower[BC_BREAKS_MAX];
    real upper[BC_BREAKS_MAX];
    for (int j = 0; j < n; ++j) {
        lower[j] = bc_huge();
        upper[j] = -bc_huge();
    }
    // Every open piece between break points. A root computed with an error of
    // root_error shifts a piece's end: its lines widen by slope * root_error.
    for (int j = 0; j + 1 < n; ++j) {
        real a = u[j];
        real b = u[j + 1];
        if (!(b > a)) continue;
        if (!bc_covered_times(e0, e1, c0, c1, tol0, tol1, a, b, r)) continue;
        real widen_lo = abs(r.y - r.x) / (b - a) * root_error;
        real widen_hi = abs(r.w - r.z) / (b - a) * root_error;
        lower[j] = min(lower[j], r.x - widen_lo);
        lower[j + 1] = min(lower[j + 1], r.y - widen_lo);
        upper[j] = max(upper[j], r.z + widen_hi);
        upper[j + 1] = max(upper[j + 1], r.w + widen_hi);
    }
    // A break point between two pieces that hold nothing can still hold the
    // condition exactly on it; elsewhere the closed pieces' lines cover it.
    for (int j = 0; j < n; ++j) {
        if (lower[j] < bc_huge()) continue;
        if (bc_covered_times(e0, e1, c0, c1, tol0, tol1, u[j], u[j], r)) {
            lower[j] = r.x;
            upper[j] = r.z;
        }
    }
    int first = -1;
    int last = -1;
    for (int j = 0; j < n; ++j) {
        if (lower[j] < bc_huge()) {
            if (first < 0) first = j;
            last = j;
        }
    }
    if (first < 0) return false;
    lens = vec2(max(lens.x, u[first] - root_error), min(lens.y, u[last] + root_error));
    vec2 lo_line = bc_fit_line(u, lower, n, real(1), lens.x, lens.y);
    vec2 hi_line = bc_fit_line(u, upper, n, real(-1), lens.x, lens.y);
    real widen = root_error * max(abs(lo_line.y), abs(hi_line.y));
    lines = vec4(lo_line.x - widen, lo_line.y, hi_line.x + widen, hi_line.y);
    return true;
}

// Stage 2, time bounds as lines in (u, t), per footprint condition: A (the
// offsets from the footprint's far edge s1 reach <= 0) and B (those from its
// near edge s0 reach >= 0, passed negated). A covered sample satisfies both,
// so it lies between both pairs of lines. Narrows `lens`. False: nothing can
// be covered.
BC_FN bool bc_two_stage_time_bounds(BC_IN(MovingTriangle) tri, int axis, real s0, real s1, BC_IN(BcEdgeCrossings) x,
                     BC_INOUT(vec2) lens, BC_OUT(vec4) lines_a, BC_OUT(vec4) lines_b) {
    vec3 ea0;  // condition A: x - s1 w (+ u c) <= 0, roots u_j(s1)
    vec3 ea1;
    vec3 eb0;  // condition B, negated: s0 w - x (- u c) <= 0, roots u_j(s0)
    vec3 eb1;
    vec3 c0;
    vec3 c1;
    vec3 ta0;
    vec3 ta1;
    vec3 tb0;
    vec3 tb1;
    real umax = max(real(1), max(abs(lens.x), abs(lens.y)));
    for (int i = 0; i < 3; ++i) {
        vec3 p0 = tri.p[i];
        vec3 p1 = tri.p[i + 3];
        c0[i] = tri.c[i][axis];
        c1[i] = tri.c[i + 3][axis];
        ea0[i] = p0[axis] - s1 * p0.z;
        ea1[i] = p1[axis] - s1 * p1.z;
        eb0[i] = s0 * p0.z - p0[axis];
        eb1[i] = s0 * p1.z - p1[axis];
        ta0[i] = bc_err(abs(p0[axis]) + abs(s1 * p0.z) + abs(c0[i]) * umax);
        ta1[i] = bc_err(abs(p1[axis]) + abs(s1 * p1.z) + abs(c1[i]) * umax);
        tb0[i] = bc_err(abs(p0[axis]) + abs(s0 * p0.z) + abs(c0[i]) * umax);
        tb1[i] = bc_err(abs(p1[axis]) + abs(s0 * p1.z) + abs(c1[i]) * umax);
    }
    vec3 err0 = vec3(x.err[0], x.err[1], x.err[2]);
    vec3 err1 = vec3(x.err[3], x.err[4], x.err[5]);
    lines_b = vec4(real(0), real(0), real(1), real(0));
    if (!bc_condition_lines(ea0, ea1, c0, c1, ta0, ta1, vec3(x.far_edge[0], x.far_edge[1], x.far_edge[2]),
                            vec3(x.far_edge[3], x.far_edge[4], x.far_edge[5]), err0, err1, lens, lines_a))
        return false;
    return bc_condition_lines(eb0, eb1, -c0, -c1, tb0, tb1, vec3(x.near_edge[0], x.near_edge[1], x.near_edge[2]),
                              vec3(x.near_edge[3], x.near_edge[4], x.near_edge[5]), err0, err1, lens, lines_b);
}
