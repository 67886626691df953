// Shared C++/GLSL text (see dialect.hpp): the dual-space per-footprint
// bounds of Laine et al. 2011 (BC_CULL_DUALSPACE). Needs coc_motion_body.inl.

// ---- shared pieces of the per-footprint bounds ----------------------------------
//
// For a footprint [s0, s1] along one axis, a covered sample at lens u and time
// t needs (docs/kernel.md, "Footprint conditions"):
//   A: some vertex has  x_i(t) + u c_i(t) - s1 w_i(t) <= 0, and
//   B: some vertex has  x_j(t) + u c_j(t) - s0 w_j(t) >= 0,
// whatever the signs of the w_i. Both offsets are linear in t and in u.

// Restrict tr to {t in [0,1] : (1-t) f0 + t f1 <= 0}. False when empty.
BC_FN bool bc_time_halfline(real f0, real f1, BC_INOUT(vec2) tr) {
    if (f0 <= real(0) && f1 <= real(0)) return true;
    if (f0 > real(0) && f1 > real(0)) return false;
    real r = f0 / (f0 - f1);  // no cancellation: f0 and f1 have opposite signs
    if (f0 > real(0)) tr.x = max(tr.x, r - bc_err(real(1)));
    else tr.y = min(tr.y, r + bc_err(real(1)));
    return tr.x <= tr.y;
}

// Restrict r to {u : a + b u <= s}. False when empty.
BC_FN bool bc_lens_halfline(real a, real b, real s, BC_INOUT(vec2) r) {
    if (b == real(0)) return a <= s;
    real root = (s - a) / b;
    real pad = bc_err((abs(s) + abs(a)) / abs(b) + abs(root));
    if (b > real(0)) r.y = min(r.y, root + pad);
    else r.x = max(r.x, root - pad);
    return r.x <= r.y;
}

// ---- dual-space bounds (Laine et al. 2011) --------------------------------------

// Time: the lens-widened offsets at t = 0 and 1, merged over the vertices; the
// lower envelope of the A offsets is concave in t, so it lies above its chord
// (1-t) m0 + t m1, which must reach <= 0 (B mirrored). Clip space: any w.
BC_FN bool bc_dual_time_bounds(BC_IN(MovingTriangle) tri, int axis, real s0, real s1, BC_OUT(vec2) tr) {
    tr = vec2(real(0), real(1));
    vec2 m = vec2(bc_huge());   // A: min over vertices at t = 0, 1
    vec2 mb = vec2(-bc_huge()); // B: max over vertices at t = 0, 1
    for (int j = 0; j < 6; ++j) {
        int k = j / 3;
        real x = tri.p[j][axis];
        real w = tri.p[j].z;
        real c = abs(tri.c[j][axis]);
        real da = x - s1 * w;
        real db = x - s0 * w;
        real ea = bc_err(abs(x) + abs(s1 * w) + c);
        real eb = bc_err(abs(x) + abs(s0 * w) + c);
        m[k] = min(m[k], da - c - ea);
        mb[k] = max(mb[k], db + c + eb);
    }
    if (!bc_finite(m.x) || !bc_finite(m.y) || !bc_finite(mb.x) || !bc_finite(mb.y)) return true;
    if (!bc_time_halfline(m.x, m.y, tr)) return false;
    return bc_time_halfline(-mb.x, -mb.y, tr);
}

// Lens: with every w > 0, the screen position (x + u c) / w of each vertex end
// is linear in u; the minimum over them is concave, so above its chord between
// u = -1 and u = 1, which must reach <= s1 (the maximum mirrored, >= s0).
BC_FN vec2 bc_dual_lens_bounds(BC_IN(MovingTriangle) tri, int axis, real s0, real s1) {
    vec2 r = vec2(real(-1), real(1));
    for (int j = 0; j < 6; ++j) {
        if (!(tri.p[j].z > real(0))) return r;
    }
    vec2 lo = vec2(bc_huge());   // min screen position at u = -1, +1
    vec2 hi = vec2(-bc_huge());  // max
    real magnitude = real(0);
    for (int j = 0; j < 6; ++j) {
        real x = tri.p[j][axis];
        real c = tri.c[j][axis];
        real w = tri.p[j].z;
        vec2 sx = vec2((x - c) / w, (x + c) / w);
        lo = min(lo, sx);
        hi = max(hi, sx);
        magnitude = max(magnitude, (abs(x) + abs(c)) / w);
    }
    real pad = bc_err(real(4) * magnitude);
    lo = lo - vec2(pad);
    hi = hi + vec2(pad);
    if (!bc_finite(lo.x) || !bc_finite(lo.y) || !bc_finite(hi.x) || !bc_finite(hi.y)) return vec2(real(-1), real(1));
    // chord of the minimum: (lo.x + lo.y)/2 + u (lo.y - lo.x)/2 <= s1
    if (!bc_lens_halfline(real(0.5) * (lo.x + lo.y), real(0.5) * (lo.y - lo.x), s1, r)) return vec2(real(1), real(-1));
    // chord of the maximum >= s0, negated
    if (!bc_lens_halfline(-real(0.5) * (hi.x + hi.y), -real(0.5) * (hi.y - hi.x), -s0, r)) return vec2(real(1), real(-1));
    return r;
}

