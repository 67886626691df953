// Shared C++/GLSL text (see dialect.hpp): the edge bound (BC_CULL_EDGES).
//
// Per edge of the sheared, moving triangle, its edge function at the
// footprint's rays as a function of the lens position and time jointly: a
// polynomial in (u, v, t), computed exactly, whose linear part becomes a
// plane and whose other terms (and the rounding) a radius, over a box of
// (u, v, t) (docs/kernel.md, "Edge bounds"). The edge function is linear in
// the sample's screen position, so each plane also carries the position's
// coefficients: every sample is tested at its own position, not over the
// whole footprint. A covered sample has every edge function of the sign of
// the triangle's determinant, so a sample below a plane by more than its
// radius is culled. The box is the two-stage bounds' range; the per-sample
// test is three planes of five terms.

#define BC_EDGE_NONE 0       // no edge planes: the two-stage bounds alone
#define BC_EDGE_ONE_SIDED 1  // the determinant keeps one sign on the box
#define BC_EDGE_TWO_SIDED 2  // it may change sign: every edge one way or every edge the other
#define BC_EDGE_PIECES 4     // planes per footprint, each over a quarter of the shutter range

// The oracle is double: its rounding of an edge function is at most about
// 20 double epsilons of (sum |ray|) (sum |V_i|) (sum |V_j|); a bound in any
// precision leaves it BC_MARGIN of them (docs/kernel.md, "Edge bounds").
#define BC_ORACLE_EPSILON 2.220446049250313e-16

// A polynomial in the box's coordinates xi_u, xi_v, xi_t (each in [-1, 1]):
// k[a + 2 b + 4 c] is the coefficient of xi_u^a xi_v^b xi_t^c (a, b <= 1,
// c <= 3), and r bounds its distance from the exact function it stands for
// (the rounding so far); m bounds the sum of |k|, so that rounding errors
// are bounded without summing the coefficients again. Edge functions have
// degree 1 in u and in v and 2 in t, the determinant 3 in t. Terms that
// cancel between products cancel here.
struct BcPoly {
    real k[16];
    real r;
    real m;
};

BC_FN BcPoly bc_poly_zero() {
    BcPoly p;
    for (int n = 0; n < 16; ++n) p.k[n] = real(0);
    p.r = real(0);
    p.m = real(0);
    return p;
}

BC_FN BcPoly bc_poly_add(BC_IN(BcPoly) p, BC_IN(BcPoly) q, real sign) {
    BcPoly result;
    for (int n = 0; n < 16; ++n) result.k[n] = p.k[n] + sign * q.k[n];
    result.m = p.m + q.m;
    result.r = p.r + q.r + bc_err(result.m);
    return result;
}

BC_FN BcPoly bc_poly_scale(BC_IN(BcPoly) p, real factor) {
    BcPoly result;
    for (int n = 0; n < 16; ++n) result.k[n] = p.k[n] * factor;
    result.m = p.m * abs(factor);
    result.r = p.r * abs(factor) + bc_err(result.m);
    return result;
}

// p (w0 + w1 xi_t), p of degree <= 2 in t; w_error bounds w's own error.
BC_FN BcPoly bc_poly_times_t(BC_IN(BcPoly) p, vec2 w, real w_error) {
    BcPoly result = bc_poly_zero();
    for (int n = 0; n < 12; ++n) {
        result.k[n] = result.k[n] + p.k[n] * w.x;
        result.k[n + 4] = result.k[n + 4] + p.k[n] * w.y;
    }
    real norm_w = abs(w.x) + abs(w.y);
    result.m = p.m * norm_w;
    result.r = p.r * (norm_w + w_error) + p.m * w_error + bc_err(real(2) * result.m);
    return result;
}

// (x0 + x1 u + x2 t + x3 u t)(y0 + y1 v + y2 t + y3 v t), x_error and
// y_error the factors' own errors.
BC_FN BcPoly bc_poly_times_uv(vec4 x, real x_error, vec4 y, real y_error) {
    BcPoly result = bc_poly_zero();
    result.k[0] = x.x * y.x;              // 1
    result.k[1] = x.y * y.x;              // u
    result.k[2] = x.x * y.y;              // v
    result.k[3] = x.y * y.y;              // u v
    result.k[4] = x.z * y.x + x.x * y.z;  // t
    result.k[5] = x.w * y.x + x.y * y.z;  // u t
    result.k[6] = x.x * y.w + x.z * y.y;  // v t
    result.k[7] = x.y * y.w + x.w * y.y;  // u v t
    result.k[8] = x.z * y.z;              // t^2
    result.k[9] = x.w * y.z;              // u t^2
    result.k[10] = x.z * y.w;             // v t^2
    result.k[11] = x.w * y.w;             // u v t^2
    real nx = abs(x.x) + abs(x.y) + abs(x.z) + abs(x.w);
    real ny = abs(y.x) + abs(y.y) + abs(y.z) + abs(y.w);
    result.m = nx * ny;
    result.r = x_error * (ny + y_error) + nx * y_error + bc_err(real(2) * result.m);
    return result;
}

// y_i w_j - y_j w_i for factors y = y0 + y1 xi_a + y2 xi_t + y3 xi_a xi_t
// (`a` the index of xi_a: 1 for u, 2 for v) and depths w = w0 + w1 xi_t,
// with their errors: the footprint terms n_x, n_y of an edge.
BC_FN BcPoly bc_poly_cross_w(vec4 yi, real yi_error, vec2 wi, real wi_error, vec4 yj, real yj_error, vec2 wj,
                             real wj_error, int a) {
    BcPoly result = bc_poly_zero();
    result.k[0] = yi.x * wj.x - yj.x * wi.x;                                   // 1
    result.k[a] = yi.y * wj.x - yj.y * wi.x;                                   // a
    result.k[4] = (yi.z * wj.x + yi.x * wj.y) - (yj.z * wi.x + yj.x * wi.y);   // t
    result.k[4 + a] = (yi.w * wj.x + yi.y * wj.y) - (yj.w * wi.x + yj.y * wi.y); // a t
    result.k[8] = yi.z * wj.y - yj.z * wi.y;                                   // t^2
    result.k[8 + a] = yi.w * wj.y - yj.w * wi.y;                               // a t^2
    real ni = abs(yi.x) + abs(yi.y) + abs(yi.z) + abs(yi.w);
    real nj = abs(yj.x) + abs(yj.y) + abs(yj.z) + abs(yj.w);
    real mi = abs(wi.x) + abs(wi.y);
    real mj = abs(wj.x) + abs(wj.y);
    result.m = ni * mj + nj * mi;
    result.r = yi_error * (mj + wj_error) + ni * wj_error + yj_error * (mi + wi_error) + nj * wi_error +
               bc_err(real(2) * result.m);
    return result;
}

// The plane kept of p: p = c0 + cu xi_u + cv xi_v + ct xi_t + rest with
// |rest| <= radius over the box. xi_t^2 lies in [0, 1], so its terms give
// half of themselves to the linear part (u t^2 = u / 2 + u (t^2 - 1/2), the
// rest within 1/2); t^3 gives 3/4 t (Chebyshev: |t^3 - 3t/4| <= 1/4); every
// other product of coordinates lies in [-1, 1].
BC_FN vec4 bc_poly_plane(BC_IN(BcPoly) p, BC_OUT(real) radius) {
    vec4 plane = vec4(p.k[0] + real(0.5) * p.k[8], p.k[1] + real(0.5) * p.k[9], p.k[2] + real(0.5) * p.k[10],
                      p.k[4] + real(0.75) * p.k[12]);
    real rest = real(0.5) * (abs(p.k[8]) + abs(p.k[9]) + abs(p.k[10])) + real(0.25) * abs(p.k[12]);
    rest = rest + abs(p.k[3]) + abs(p.k[5]) + abs(p.k[6]) + abs(p.k[7]) + abs(p.k[11]);
    rest = rest + abs(p.k[13]) + abs(p.k[14]) + abs(p.k[15]);
    radius = rest + p.r + bc_err(p.m);
    return plane;
}

// +1 or -1 where p keeps that strict sign over the box with `margin` to
// spare, else 0.
BC_FN real bc_poly_sign(BC_IN(BcPoly) p, real margin) {
    real radius = real(0);
    vec4 plane = bc_poly_plane(p, radius);
    real spread = abs(plane.y) + abs(plane.z) + abs(plane.w) + radius + margin;
    if (plane.x > spread) return real(1);
    if (plane.x < -spread) return real(-1);
    return real(0);
}

// The planes of the three edges over one piece of the box (bc_edge_bounds).
struct BcEdgePlanes {
    int mode;    // BC_EDGE_*
    vec2 time;   // the box's shutter range: the planes hold only inside it
    vec3 du;     // per edge: coefficient of u
    vec3 dv;     // of v
    vec3 dt;     // of t
    vec3 dx;     // of the sample's screen x
    vec3 dy;     // of its screen y
    vec3 hi;     // constant + radius: a covered sample at s has du u + dv v + dt t + dx s.x + dy s.y + hi >= 0
                 // for every edge ...
    vec3 lo;     // constant - radius: ... or (two-sided only) <= 0 with lo for every edge
    vec3 spread; // |dx| h_x + |dy| h_y (rounded up): the planes' reach over the footprint from its centre
};

BC_FN BcEdgePlanes bc_no_edge_planes() {
    BcEdgePlanes e;
    e.mode = BC_EDGE_NONE;
    e.time = vec2(real(0), real(1));
    e.du = vec3(real(0));
    e.dv = vec3(real(0));
    e.dt = vec3(real(0));
    e.dx = vec3(real(0));
    e.dy = vec3(real(0));
    e.hi = vec3(real(0));
    e.lo = vec3(real(0));
    e.spread = vec3(real(0));
    return e;
}

// Centre and half-width of [lo, hi], the half-width grown so that the
// centre +- it still holds both ends after rounding.
BC_FN vec2 bc_box_axis(real lo, real hi) {
    return vec2(real(0.5) * (lo + hi), real(0.5) * (hi - lo) + bc_err(abs(lo) + abs(hi)));
}

// (1 - t) f0 + t f1 at t = t_box.x + t_box.y xi_t, as (constant, coefficient of xi_t).
BC_FN vec2 bc_lerp_t(real f0, real f1, vec2 t_box) {
    real d = f1 - f0;
    return vec2(f0 + d * t_box.x, d * t_box.y);
}

// Vertex i's offset along one axis from the ray through the footprint
// centre, d = (x - s w) + u c at lens u = box.x + box.y xi and time t, as
// (1, xi, xi_t, xi xi_t) coefficients; its error bound goes to `error`.
BC_FN vec4 bc_edge_offset(BC_IN(MovingTriangle) tri, int i, int axis, real s, vec2 box, vec2 t_box,
                          BC_OUT(real) error) {
    vec3 p0 = tri.p[i];
    vec3 p1 = tri.p[i + 3];
    vec2 e = bc_lerp_t(p0[axis] - s * p0.z, p1[axis] - s * p1.z, t_box);
    vec2 c = bc_lerp_t(tri.c[i][axis], tri.c[i + 3][axis], t_box);
    real c_size = abs(tri.c[i][axis]) + abs(tri.c[i + 3][axis]);
    error = bc_err(real(2) * (abs(p0[axis]) + abs(s * p0.z) + abs(p1[axis]) + abs(s * p1.z)) +
                   real(2) * c_size * (abs(box.x) + box.y));
    return vec4(e.x + box.x * c.x, box.y * c.x, e.y + box.x * c.y, box.y * c.y);
}

// Sum of |x| + |c| over both ends of vertex i, per axis: a bound on the
// oracle's sheared vertex anywhere in the lens and shutter.
BC_FN real bc_vertex_magnitude(BC_IN(MovingTriangle) tri, int i) {
    vec3 p0 = abs(tri.p[i]);
    vec3 p1 = abs(tri.p[i + 3]);
    vec2 c = abs(tri.c[i]) + abs(tri.c[i + 3]);
    return p0.x + p0.y + p0.z + p1.x + p1.y + p1.z + c.x + c.y;
}

// The coefficient of delta (one screen axis) in an edge function on one
// piece of the shutter: n's plane over the box (a, its radius n_radius) at
// the piece's centre xi_t = centre, and in .y a bound on how far n strays
// from it over the piece (xi_t within half_width of the centre).
BC_FN vec2 bc_screen_slope(vec4 a, real n_radius, real centre, real half_width) {
    real slope = a.x + a.w * centre;
    real stray = abs(a.y) + abs(a.z) + abs(a.w) * half_width + n_radius;
    return vec2(slope, stray + bc_err(abs(a.x) + abs(a.w) + stray));
}

// Edge k's plane in (u, v, t, s) from its polynomial over the box (xi =
// (u - centre) / half-width per axis) and its screen slopes (bc_screen_slope,
// over the footprint s = centre + delta, |delta| <= half-width per axis),
// into slot k of e, its radius grown by `extra`. False if not finite.
BC_FN bool bc_edge_plane(BC_IN(BcPoly) f, real extra, vec2 slope_x, vec2 slope_y, vec2 u_box, vec2 v_box,
                         vec2 t_box, vec2 sx, vec2 sy, int k, BC_INOUT(BcEdgePlanes) e) {
    real radius = real(0);
    vec4 a = bc_poly_plane(f, radius);
    real cu = a.y / u_box.y;
    real cv = a.z / v_box.y;
    real ct = a.w / t_box.y;
    real cx = slope_x.x;
    real cy = slope_y.x;
    // delta (n - slope): what the slopes leave of the screen terms.
    radius = radius + sx.y * slope_x.y + sy.y * slope_y.y;
    real constant = a.x - cu * u_box.x - cv * v_box.x - ct * t_box.x - cx * sx.x - cy * sy.x;
    real reach_x = abs(cx) * (abs(sx.x) + sx.y);
    real reach_y = abs(cy) * (abs(sy.x) + sy.y);
    // Rounding of the conversion and of the caller's evaluation (at any s of
    // the footprint, or at its centre with the spread added).
    real slack = bc_err(abs(a.x) + real(2) * (abs(cu) * (abs(u_box.x) + u_box.y) + abs(cv) * (abs(v_box.x) + v_box.y) +
                                             abs(ct) * (abs(t_box.x) + t_box.y) + reach_x + reach_y) +
                        radius + extra);
    real r = radius + extra + slack;
    real spread = abs(cx) * sx.y + abs(cy) * sy.y;
    e.du[k] = cu;
    e.dv[k] = cv;
    e.dt[k] = ct;
    e.dx[k] = cx;
    e.dy[k] = cy;
    e.hi[k] = constant + r;
    e.lo[k] = constant - r;
    e.spread[k] = spread + bc_err(spread);
    return bc_finite(cu) && bc_finite(cv) && bc_finite(ct) && bc_finite(e.hi[k]) && bc_finite(e.lo[k]) &&
           bc_finite(e.spread[k]);
}

// The three edges' functions over the footprint [s_lo, s_hi] (padded for
// the caller's rounding already) and the box u in u_range, v in v_range,
// t in t_range, as polynomials in the box's coordinates; see bc_edge_functions.
struct BcEdgeFunctions {
    BcPoly f[3];    // per edge: its function at the footprint centre's ray (times the determinant's sign if known)
    vec4 nx[3];     // per edge: the plane of n_x over the box (bc_poly_plane; times the sign likewise) ...
    vec4 ny[3];     // ... and of n_y
    vec3 nx_radius; // their radii
    vec3 ny_radius;
    vec3 extra;     // per edge: the oracle's rounding, added to the radius
    int mode;       // BC_EDGE_ONE_SIDED or BC_EDGE_TWO_SIDED
    vec2 u_box;     // the box: centre and half-width per axis
    vec2 v_box;
    vec2 t_box;
    vec2 sx;        // the footprint: centre and half-width per screen axis
    vec2 sy;
};

// Edge k joins vertices i = k+1 and j = k+2; with d the vertices' offsets
// from the ray through the footprint centre s_c, its function at the ray
// (s_c + delta, 1) is
//   E_k = d_i x d_j + delta_x n_x + delta_y n_y,
//   n_x = d_iy W_j - d_jy W_i,  n_y = d_jx W_i - d_ix W_j,
// and the determinant is W_0 E_0 + W_1 E_1 + W_2 E_2 (E at the centre).
// E_k is linear in delta: the per-sample test takes delta's coefficients
// from the planes of n_x and n_y (bc_screen_slope). With the determinant's
// sign known on the box, each edge function times it must be >= 0 at a
// covered sample (one-sided); otherwise all >= 0 or all <= 0 (two-sided).
BC_FN BcEdgeFunctions bc_edge_functions(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, vec2 u_range,
                                        vec2 v_range, vec2 t_range) {
    BcEdgeFunctions result;
    result.u_box = bc_box_axis(u_range.x, u_range.y);
    result.v_box = bc_box_axis(v_range.x, v_range.y);
    result.t_box = bc_box_axis(t_range.x, t_range.y);
    vec2 sx = bc_box_axis(s_lo.x, s_hi.x);
    vec2 sy = bc_box_axis(s_lo.y, s_hi.y);
    result.sx = sx;
    result.sy = sy;
    vec4 dx[3];
    vec4 dy[3];
    vec2 w[3];
    vec3 dx_error = vec3(real(0));
    vec3 dy_error = vec3(real(0));
    vec3 w_error = vec3(real(0));
    real m[3];
    for (int i = 0; i < 3; ++i) {
        real ex = real(0);
        real ey = real(0);
        dx[i] = bc_edge_offset(tri, i, 0, sx.x, result.u_box, result.t_box, ex);
        dy[i] = bc_edge_offset(tri, i, 1, sy.x, result.v_box, result.t_box, ey);
        dx_error[i] = ex;
        dy_error[i] = ey;
        w[i] = bc_lerp_t(tri.p[i].z, tri.p[i + 3].z, result.t_box);
        w_error[i] = bc_err(abs(tri.p[i].z) + abs(tri.p[i + 3].z));
        m[i] = bc_vertex_magnitude(tri, i);
    }
    real ray = real(1) + max(abs(s_lo.x), abs(s_hi.x)) + max(abs(s_lo.y), abs(s_hi.y));
    real oracle = real(BC_MARGIN) * real(BC_ORACLE_EPSILON);
    BcPoly det = bc_poly_zero();
    for (int k = 0; k < 3; ++k) {
        int i = (k + 1) % 3;
        int j = (k + 2) % 3;
        result.f[k] = bc_poly_add(bc_poly_times_uv(dx[i], dx_error[i], dy[j], dy_error[j]),
                               bc_poly_times_uv(dx[j], dx_error[j], dy[i], dy_error[i]), real(-1));
        det = bc_poly_add(det, bc_poly_times_t(result.f[k], w[k], w_error[k]), real(1));
        result.extra[k] = oracle * ray * m[i] * m[j];
    }
    real sign = bc_poly_sign(det, oracle * m[0] * m[1] * m[2]);
    bool one_sided = sign != real(0);
    result.mode = one_sided ? BC_EDGE_ONE_SIDED : BC_EDGE_TWO_SIDED;
    // Two-sided: the functions themselves (either sign of all three will do).
    if (!one_sided) sign = real(1);
    for (int k = 0; k < 3; ++k) {
        int i = (k + 1) % 3;
        int j = (k + 2) % 3;
        BcPoly nx = bc_poly_cross_w(dy[i], dy_error[i], w[i], w_error[i], dy[j], dy_error[j], w[j], w_error[j], 2);
        BcPoly ny = bc_poly_cross_w(dx[j], dx_error[j], w[j], w_error[j], dx[i], dx_error[i], w[i], w_error[i], 1);
        // Scaling by +-1 is exact.
        if (one_sided) result.f[k] = bc_poly_scale(result.f[k], sign);
        real rx = real(0);
        real ry = real(0);
        result.nx[k] = sign * bc_poly_plane(nx, rx);
        result.ny[k] = sign * bc_poly_plane(ny, ry);
        result.nx_radius[k] = rx;
        result.ny_radius[k] = ry;
    }
    return result;
}

// p on the part xi_t = centre + half_width xi' of the box, as a polynomial in xi'
// (|centre| + half_width <= 1 + a rounding pad): (centre + half_width xi')^c expanded.
BC_FN BcPoly bc_poly_recentre_t(BC_IN(BcPoly) p, real centre, real half_width) {
    BcPoly result;
    for (int g = 0; g < 4; ++g) {
        real k0 = p.k[g];
        real k1 = p.k[g + 4];
        real k2 = p.k[g + 8];
        real k3 = p.k[g + 12];
        result.k[g] = k0 + centre * (k1 + centre * (k2 + centre * k3));
        result.k[g + 4] = half_width * (k1 + centre * (real(2) * k2 + real(3) * centre * k3));
        result.k[g + 8] = half_width * half_width * (k2 + real(3) * centre * k3);
        result.k[g + 12] = half_width * half_width * half_width * k3;
    }
    real reach = max(real(1), abs(centre) + half_width);  // bounds |centre + half_width xi'|^c, c <= 3
    result.m = p.m * reach * reach * reach;
    result.r = p.r + bc_err(real(8) * result.m);
    return result;
}

// The shutter range of the two-stage bounds cut into BC_EDGE_PIECES equal
// pieces, each with planes of its own, from the edge functions over the
// whole range re-centred on the piece: the terms in t^2 that a plane cannot
// follow shrink with the square of a piece's length. Neighbouring pieces
// share their end exactly, so every time in the range has a piece.
// A triangle that does not move gets one piece: its functions are constant in t.
struct BcEdgeBounds {
    int pieces;  // pieces in use, 1 or BC_EDGE_PIECES
    BcEdgePlanes piece[BC_EDGE_PIECES];
};

BC_FN BcEdgeBounds bc_no_edge_bounds() {
    BcEdgeBounds b;
    b.pieces = 1;
    for (int k = 0; k < BC_EDGE_PIECES; ++k) b.piece[k] = bc_no_edge_planes();
    return b;
}

BC_FN BcEdgeBounds bc_edge_bounds(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, vec2 u_range, vec2 v_range,
                                  vec2 t_range) {
    BcEdgeBounds b = bc_no_edge_bounds();
    bool moves = false;
    for (int j = 0; j < 3; ++j) {
        if (tri.p[j] != tri.p[j + 3] || tri.c[j] != tri.c[j + 3]) moves = true;
    }
    b.pieces = moves ? BC_EDGE_PIECES : 1;
    BcEdgeFunctions fn = bc_edge_functions(tri, s_lo, s_hi, u_range, v_range, t_range);
    vec2 t_box = fn.t_box;
    // A piece's ends are rounded: in box coordinates they can move by this much.
    real pad = bc_err(abs(t_box.x) + t_box.y) / t_box.y;
    real half_width = real(1) / real(b.pieces);
    real start = t_range.x;
    for (int q = 0; q < b.pieces; ++q) {
        real centre = real(-1) + half_width * real(2 * q + 1);
        real end = q + 1 == b.pieces ? t_range.y : t_box.x + t_box.y * (centre + half_width);
        end = max(start, min(end, t_range.y));
        BcEdgePlanes e = bc_no_edge_planes();
        vec2 piece_box = vec2(t_box.x + t_box.y * centre, t_box.y * (half_width + pad));
        for (int k = 0; k < 3; ++k) {
            BcPoly f = bc_poly_recentre_t(fn.f[k], centre, half_width + pad);
            vec2 slope_x = bc_screen_slope(fn.nx[k], fn.nx_radius[k], centre, half_width + pad);
            vec2 slope_y = bc_screen_slope(fn.ny[k], fn.ny_radius[k], centre, half_width + pad);
            if (!bc_edge_plane(f, fn.extra[k], slope_x, slope_y, fn.u_box, fn.v_box, piece_box, fn.sx, fn.sy, k, e))
                return bc_no_edge_bounds();
        }
        e.mode = fn.mode;
        e.time = vec2(start, end);
        b.piece[q] = e;
        start = end;
    }
    return b;
}

// The piece of b whose shutter range holds t, or -1 if none does (then no
// sample at t can be covered: the range is the two-stage bounds').
BC_FN int bc_edge_piece(BC_IN(BcEdgeBounds) b, real t) {
    if (t < b.piece[0].time.x) return -1;
    int k = 0;
    while (k + 1 < b.pieces) {
        if (t <= b.piece[k].time.y) break;
        k = k + 1;
    }
    if (t > b.piece[k].time.y) return -1;
    return k;
}

// Whether a sample at screen position s (in the footprint the bounds were
// made for), lens uv and time t can be covered by the edges' account: the
// planes of the piece whose shutter range holds t, at the sample's own
// position. With widen = 1 and s the footprint's centre, for any sample of
// the footprint (its position unknown).
BC_FN bool bc_edge_bounds_pass_at(BC_IN(BcEdgeBounds) b, vec2 s, vec2 uv, real t, real widen) {
    if (b.piece[0].mode == BC_EDGE_NONE) return true;
    int k = bc_edge_piece(b, t);
    if (k < 0) return false;
    // The piece's fields read in place (a copy of the piece per sample costs
    // as much as the test).
    vec3 value = b.piece[k].du * uv.x + b.piece[k].dv * uv.y + b.piece[k].dt * t + b.piece[k].dx * s.x +
                 b.piece[k].dy * s.y;
    vec3 reach = widen * b.piece[k].spread;
    vec3 hi = value + (b.piece[k].hi + reach);
    if (min(hi.x, min(hi.y, hi.z)) >= real(0)) return true;
    if (b.piece[k].mode == BC_EDGE_ONE_SIDED) return false;
    vec3 lo = value + (b.piece[k].lo - reach);
    return !(max(lo.x, max(lo.y, lo.z)) > real(0));
}

// Edge e's plane value du u + dv v + dt t + dx s.x + dy s.y summed as
// bc_edge_bounds_pass_at sums it, at one point.
BC_FN real bc_edge_plane_value(BC_IN(BcEdgePlanes) p, int e, vec2 s, vec2 uv, real t) {
    return p.du[e] * uv.x + p.dv[e] * uv.y + p.dt[e] * t + p.dx[e] * s.x + p.dy[e] * s.y;
}

// Whether bc_edge_bounds_pass_at (widen 0) fails for every sample whose
// piece is p, whose screen position lies in [s_lo, s_hi] and whose lens lies
// in u_range x v_range: then a renderer whose samples are sorted by time may
// skip the piece's run of them. Rounding is monotone, so each edge's value,
// summed in the same order, is largest and smallest at the corners of the box
// (lens, footprint, the piece's time range) its coefficients' signs choose;
// with those finite, no sample's sums overflow into a NaN. One-sided: some
// edge below 0 at its largest; two-sided also some edge's lo side above 0 at
// its smallest (docs/kernel.md, "Edge bounds").
BC_FN bool bc_edge_piece_culls_box(BC_IN(BcEdgePlanes) p, vec2 s_lo, vec2 s_hi, vec2 u_range, vec2 v_range) {
    if (p.mode == BC_EDGE_NONE) return false;
    bool below = false;
    bool above = false;
    for (int e = 0; e < 3; ++e) {
        vec2 s_top = vec2(p.dx[e] >= real(0) ? s_hi.x : s_lo.x, p.dy[e] >= real(0) ? s_hi.y : s_lo.y);
        vec2 s_bottom = vec2(p.dx[e] >= real(0) ? s_lo.x : s_hi.x, p.dy[e] >= real(0) ? s_lo.y : s_hi.y);
        vec2 uv_top = vec2(p.du[e] >= real(0) ? u_range.y : u_range.x, p.dv[e] >= real(0) ? v_range.y : v_range.x);
        vec2 uv_bottom = vec2(p.du[e] >= real(0) ? u_range.x : u_range.y, p.dv[e] >= real(0) ? v_range.x : v_range.y);
        real t_top = p.dt[e] >= real(0) ? p.time.y : p.time.x;
        real t_bottom = p.dt[e] >= real(0) ? p.time.x : p.time.y;
        real top = bc_edge_plane_value(p, e, s_top, uv_top, t_top);
        real bottom = bc_edge_plane_value(p, e, s_bottom, uv_bottom, t_bottom);
        if (!bc_finite(top) || !bc_finite(bottom)) return false;
        // The reach at widen 0 (+0) added as the per-sample test adds it.
        real reach = real(0) * p.spread[e];
        real hi = top + (p.hi[e] + reach);
        real lo = bottom + (p.lo[e] - reach);
        if (!bc_finite(hi) || !bc_finite(lo)) return false;
        if (hi < real(0)) below = true;
        if (lo > real(0)) above = true;
    }
    if (p.mode == BC_EDGE_ONE_SIDED) return below;
    return below && above;
}
