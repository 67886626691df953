// Shared C++/GLSL text (see dialect.hpp): the edge bound (BC_CULL_EDGES).
//
// Per edge of the sheared, moving triangle, its edge function at the
// footprint's rays as a function of the lens position and time jointly: a
// plane in (u, v, t) with a radius that holds the rest of the function over a
// box of (u, v, t) and the whole footprint (docs/kernel.md, "Edge bounds").
// A covered sample has every edge function of the sign of the triangle's
// determinant, so a sample whose plane lies below minus its radius is culled.
// The box is the two-stage bounds' range; the per-sample test is three
// planes.

#define BC_EDGE_NONE 0       // no edge planes: the two-stage bounds alone
#define BC_EDGE_ONE_SIDED 1  // the determinant keeps one sign on the box
#define BC_EDGE_TWO_SIDED 2  // it may change sign: every edge one way or every edge the other

// The oracle is double: its rounding of an edge function is at most about
// 20 double epsilons of (sum |ray|) (sum |V_i|) (sum |V_j|); a bound in any
// precision leaves it BC_MARGIN of them (docs/kernel.md, "Edge bounds").
#define BC_ORACLE_EPSILON 2.220446049250313e-16

// An affine form over the box: a.x + a.y xi_u + a.z xi_v + a.w xi_t with
// every xi in [-1, 1], plus anything within +- r. Products keep their linear
// part and move the rest into r (interval arithmetic on the non-linear terms).
struct BcAffine {
    vec4 a;
    real r;
};

BC_FN BcAffine bc_affine(vec4 a, real r) {
    BcAffine x;
    x.a = a;
    x.r = r;
    return x;
}

// Largest |linear part - constant| over the box.
BC_FN real bc_affine_span(BcAffine x) {
    return abs(x.a.y) + abs(x.a.z) + abs(x.a.w);
}

// A bound on |x| over the box.
BC_FN real bc_affine_bound(BcAffine x) {
    return abs(x.a.x) + bc_affine_span(x) + x.r;
}

BC_FN BcAffine bc_affine_add(BcAffine x, BcAffine y, real sign) {
    // Each coefficient rounds once; the sum of their errors over the box is
    // below the margin of the magnitudes.
    return bc_affine(x.a + sign * y.a, x.r + y.r + bc_err(bc_affine_bound(x) + bc_affine_bound(y)));
}

// x y = x0 y0 + x0 Y + y0 X + X Y (+ the radii's terms), X and Y the linear
// parts. X Y = sum_i x_i y_i xi_i^2 + sum_{i != j} x_i y_j xi_i xi_j: the first
// sum lies in its half plus or minus half its magnitude (xi^2 in [0, 1]), the
// second within (sum |x_i|)(sum |y_j|) - sum |x_i y_i|.
BC_FN BcAffine bc_affine_mul(BcAffine x, BcAffine y) {
    vec3 xs = vec3(x.a.y, x.a.z, x.a.w);
    vec3 ys = vec3(y.a.y, y.a.z, y.a.w);
    real sx = bc_affine_span(x);
    real sy = bc_affine_span(y);
    vec3 diag = xs * ys;
    real diag_sum = diag.x + diag.y + diag.z;
    real diag_abs = abs(diag.x) + abs(diag.y) + abs(diag.z);
    vec3 linear = x.a.x * ys + y.a.x * xs;
    real centre = x.a.x * y.a.x + real(0.5) * diag_sum;
    real r = sx * sy - real(0.5) * diag_abs + (abs(x.a.x) + sx) * y.r + (abs(y.a.x) + sy) * x.r + x.r * y.r;
    real rounding = bc_err(abs(x.a.x * y.a.x) + diag_abs + abs(x.a.x) * sy + abs(y.a.x) * sx + sx * sy + r);
    return bc_affine(vec4(centre, linear), r + rounding);
}

// (1 - t) f0 + t f1 for t = t_m + rho_t xi_t; `error` bounds the rounding of
// f0 and f1 themselves.
BC_FN BcAffine bc_affine_lerp(real f0, real f1, vec2 t_box, real error) {
    real d = f1 - f0;
    return bc_affine(vec4(f0 + d * t_box.x, real(0), real(0), d * t_box.y),
                     error + bc_err(abs(f0) + abs(f1)));
}

// The planes of the three edges over the footprint [s_lo, s_hi] (already
// padded for the caller's rounding) and the box u in u_range, v in v_range,
// t in t_range. Edge k joins vertices k+1 and k+2; with d_i the offset of
// vertex i from the footprint centre's ray, (X_i - s_x W_i, Y_i - s_y W_i),
// its function at the ray (s_c + delta, 1) is
//   E_k = d_i x d_j + delta_x (d_iy W_j - d_jy W_i) + delta_y (d_jx W_i - d_ix W_j),
// and the determinant is W_0 E_0 + W_1 E_1 + W_2 E_2 at the centre.
// Returns the planes as (coefficients of u, v, t per edge; constant + radius
// and constant - radius per edge), times the determinant's sign when it has one.
struct BcEdgePlanes {
    int mode;        // BC_EDGE_*
    vec2 time;       // the box's shutter range: the planes hold only inside it
    vec3 du;         // per edge: coefficient of u
    vec3 dv;         // of v
    vec3 dt;         // of t
    vec3 hi;         // constant + radius: a covered sample has du u + dv v + dt t + hi >= 0 ...
    vec3 lo;         // constant - radius: ... or (two-sided) every edge <= 0 with this one
};

BC_FN BcEdgePlanes bc_no_edge_planes() {
    BcEdgePlanes e;
    e.mode = BC_EDGE_NONE;
    e.time = vec2(real(0), real(1));
    e.du = vec3(real(0));
    e.dv = vec3(real(0));
    e.dt = vec3(real(0));
    e.hi = vec3(real(0));
    e.lo = vec3(real(0));
    return e;
}

// Centre and half-width of [lo, hi], the half-width grown so that the
// centre +- it still holds both ends after rounding.
BC_FN vec2 bc_box_axis(real lo, real hi) {
    return vec2(real(0.5) * (lo + hi), real(0.5) * (hi - lo) + bc_err(abs(lo) + abs(hi)));
}

// The offsets (d_x, d_y) of vertex i from the ray through the footprint
// centre, and its depth W, as affine forms over the box.
BC_FN void bc_edge_vertex(BC_IN(MovingTriangle) tri, int i, vec2 centre, vec2 u_box, vec2 v_box, vec2 t_box,
                          BC_OUT(BcAffine) dx, BC_OUT(BcAffine) dy, BC_OUT(BcAffine) w) {
    vec3 p0 = tri.p[i];
    vec3 p1 = tri.p[i + 3];
    BcAffine u = bc_affine(vec4(u_box.x, u_box.y, real(0), real(0)), real(0));
    BcAffine v = bc_affine(vec4(v_box.x, real(0), v_box.y, real(0)), real(0));
    BcAffine ex = bc_affine_lerp(p0.x - centre.x * p0.z, p1.x - centre.x * p1.z, t_box,
                                 bc_err(abs(p0.x) + abs(centre.x * p0.z) + abs(p1.x) + abs(centre.x * p1.z)));
    BcAffine ey = bc_affine_lerp(p0.y - centre.y * p0.z, p1.y - centre.y * p1.z, t_box,
                                 bc_err(abs(p0.y) + abs(centre.y * p0.z) + abs(p1.y) + abs(centre.y * p1.z)));
    BcAffine cx = bc_affine_lerp(tri.c[i].x, tri.c[i + 3].x, t_box, real(0));
    BcAffine cy = bc_affine_lerp(tri.c[i].y, tri.c[i + 3].y, t_box, real(0));
    dx = bc_affine_add(ex, bc_affine_mul(u, cx), real(1));
    dy = bc_affine_add(ey, bc_affine_mul(v, cy), real(1));
    w = bc_affine_lerp(p0.z, p1.z, t_box, real(0));
}

// Sum of |x| + |c| over both ends of vertex i, per axis: a bound on the
// oracle's sheared vertex anywhere in the lens and shutter.
BC_FN real bc_vertex_magnitude(BC_IN(MovingTriangle) tri, int i) {
    vec3 p0 = abs(tri.p[i]);
    vec3 p1 = abs(tri.p[i + 3]);
    vec2 c = abs(tri.c[i]) + abs(tri.c[i + 3]);
    return p0.x + p0.y + p0.z + p1.x + p1.y + p1.z + c.x + c.y;
}

BC_FN BcEdgePlanes bc_edge_planes(BC_IN(MovingTriangle) tri, vec2 s_lo, vec2 s_hi, vec2 u_range, vec2 v_range,
                                  vec2 t_range) {
    BcEdgePlanes e = bc_no_edge_planes();
    vec2 u_box = bc_box_axis(u_range.x, u_range.y);
    vec2 v_box = bc_box_axis(v_range.x, v_range.y);
    vec2 t_box = bc_box_axis(t_range.x, t_range.y);
    vec2 sx = bc_box_axis(s_lo.x, s_hi.x);
    vec2 sy = bc_box_axis(s_lo.y, s_hi.y);
    vec2 centre = vec2(sx.x, sy.x);
    BcAffine dx[3];
    BcAffine dy[3];
    BcAffine w[3];
    real m[3];
    for (int i = 0; i < 3; ++i) {
        bc_edge_vertex(tri, i, centre, u_box, v_box, t_box, dx[i], dy[i], w[i]);
        m[i] = bc_vertex_magnitude(tri, i);
    }
    real ray = real(1) + max(abs(s_lo.x), abs(s_hi.x)) + max(abs(s_lo.y), abs(s_hi.y));
    real oracle = real(BC_MARGIN) * real(BC_ORACLE_EPSILON);
    BcAffine det = bc_affine(vec4(real(0)), real(0));
    BcAffine edge[3];
    real radius[3];
    for (int k = 0; k < 3; ++k) {
        int i = (k + 1) % 3;
        int j = (k + 2) % 3;
        edge[k] = bc_affine_add(bc_affine_mul(dx[i], dy[j]), bc_affine_mul(dy[i], dx[j]), real(-1));
        BcAffine nx = bc_affine_add(bc_affine_mul(dy[i], w[j]), bc_affine_mul(dy[j], w[i]), real(-1));
        BcAffine ny = bc_affine_add(bc_affine_mul(dx[j], w[i]), bc_affine_mul(dx[i], w[j]), real(-1));
        real footprint = sx.y * bc_affine_bound(nx) + sy.y * bc_affine_bound(ny);
        radius[k] = edge[k].r + footprint + bc_err(footprint) + oracle * ray * m[i] * m[j];
        det = bc_affine_add(det, bc_affine_mul(w[k], edge[k]), real(1));
    }
    real det_margin = bc_affine_span(det) + det.r + oracle * m[0] * m[1] * m[2];
    real sign = real(0);
    if (det.a.x > det_margin) sign = real(1);
    if (det.a.x < -det_margin) sign = real(-1);
    real flip = sign < real(0) ? real(-1) : real(1);
    for (int k = 0; k < 3; ++k) {
        // The plane in (u, v, t): xi = (u - centre) / half-width per axis.
        vec4 a = flip * edge[k].a;
        real cu = a.y / u_box.y;
        real cv = a.z / v_box.y;
        real ct = a.w / t_box.y;
        real constant = a.x - cu * u_box.x - cv * v_box.x - ct * t_box.x;
        // Rounding of the conversion and of the caller's evaluation.
        real slack = bc_err(abs(a.x) + real(2) * (abs(cu) * (abs(u_box.x) + u_box.y) + abs(cv) * (abs(v_box.x) + v_box.y) +
                                                 abs(ct) * (abs(t_box.x) + t_box.y)) + radius[k]);
        real r = radius[k] + slack;
        e.du[k] = cu;
        e.dv[k] = cv;
        e.dt[k] = ct;
        e.hi[k] = constant + r;
        e.lo[k] = constant - r;
        bool finite = bc_finite(cu) && bc_finite(cv) && bc_finite(ct) && bc_finite(e.hi[k]) && bc_finite(e.lo[k]);
        if (!finite) return bc_no_edge_planes();
    }
    if (!bc_finite(det_margin) || !bc_finite(det.a.x)) sign = real(0);
    e.mode = sign != real(0) ? BC_EDGE_ONE_SIDED : BC_EDGE_TWO_SIDED;
    e.time = vec2(t_box.x - t_box.y, t_box.x + t_box.y);
    return e;
}

// Whether a sample at lens uv and time t can be covered by the edges' account.
BC_FN bool bc_edge_planes_pass(BC_IN(BcEdgePlanes) e, vec2 uv, real t) {
    if (e.mode == BC_EDGE_NONE) return true;
    if (t < e.time.x || t > e.time.y) return false;
    vec3 value = e.du * uv.x + e.dv * uv.y + e.dt * t;
    vec3 hi = value + e.hi;
    if (min(hi.x, min(hi.y, hi.z)) >= real(0)) return true;
    if (e.mode == BC_EDGE_ONE_SIDED) return false;
    vec3 lo = value + e.lo;
    return !(max(lo.x, max(lo.y, lo.z)) > real(0));
}
