// Shared C++/GLSL text (see dialect.hpp): the culling kernel.
//
// Model (docs/kernel.md has the derivations):
//  - clip space (x, y, w), w = view depth; vertex i at shutter end k is
//    tri.p[i + 3k], its signed circle of confusion (c_x, c_y) is tri.c[i + 3k];
//  - at time t in [0,1] both interpolate linearly; a lens sample (u, v) in
//    [-1,1]^2 shears a vertex to (x + u c_x, y + v c_y, w);
//  - a sample (s, u, v, t) is covered when the sheared triangle at t contains
//    the ray through screen position s at a depth w >= near.
// Every bound below contains every covered sample: false culls are bugs.

#define BC_CULL_BBOX 0
#define BC_CULL_HULL 1
#define BC_CULL_DUALSPACE 2
#define BC_CULL_CLIP2 3
#define BC_CULL_EDGES 4  // the two-stage bounds and per-edge planes (edge_bounds_body.inl)

#define BC_NEEDS_MOTION 1
#define BC_NEEDS_DEFOCUS 2
#define BC_INVALID 4

#define BC_HULL_MAX 24
#define BC_BREAKS_MAX 8

// Margin policy: every rounded quantity is widened by BC_MARGIN machine
// epsilons of the magnitude it was computed from (docs/kernel.md, "Margins").
#define BC_MARGIN 64

struct MovingTriangle {
    vec3 p[6];  // clip (x, y, w) of vertex i at shutter open (i) and close (i + 3)
    vec2 c[6];  // signed circle of confusion (c_x, c_y), same indexing
};

struct ScreenBound {
    bool empty;                   // the triangle is never in front of the near plane
    vec2 lo;                      // screen box (NDC), widened by the margins
    vec2 hi;
    int hull_count;               // > 0: also inside these edges
    vec3 hull_edge[BC_HULL_MAX];  // inside when dot(edge.xy, s) + edge.z >= 0
};

BC_FN real bc_err(real magnitude) {
    // Relative to the magnitude, plus an absolute floor for results in the
    // subnormal range, where rounding errors stop shrinking with the values.
    return magnitude * (real(BC_MARGIN) * bc_epsilon()) + real(BC_MARGIN) * bc_tiny();
}

// Dialect rule (docs/glsl.md): no function call inside a loop condition
// joined by && or || (Mesa 22 miscompiles `while (k > 0 && f(...))`): test it
// in the body and break.

// a.x b.x + a.y b.y + a.z b.z summed left to right, as GLM does: GLSL's dot()
// may sum in another order (llvmpipe: a.x b.x + (a.y b.y + a.z b.z)), and
// without `precise` Mesa reorders the sum when b.z = 1.
BC_FN real bc_dot3(vec3 a, vec3 b) {
    BC_PRECISE real sum = a.x * b.x + a.y * b.y + a.z * b.z;
    return sum;
}

BC_FN bool bc_finite(real x) {
    return abs(x) <= bc_huge();  // false for NaN and +-Inf
}

// ---- circle of confusion ---------------------------------------------------

// Thin lens: c(w) = a + b w with a = -k R, b = k R / F (projection scale k,
// lens radius R, focus depth F), so c(F) = 0. Returns (a, b).
BC_FN vec2 thin_lens_coc(real projection_scale, real lens_radius, real focus_depth) {
    real a = -projection_scale * lens_radius;
    return vec2(a, -a / focus_depth);
}

BC_FN real coc_at(vec2 coc_ab, real w) {
    return coc_ab.x + coc_ab.y * w;
}

// Controllable defocus after Munkberg et al. 2012: no blur while
// |w - F| <= focus_range (the CoC magnitude shrinks by |b| focus_range, so it
// stays continuous), and the magnitude never exceeds max_coc (foreground clamp).
BC_FN real coc_controlled(vec2 coc_ab, real w, real focus_range, real max_coc) {
    real c = coc_ab.x + coc_ab.y * w;
    real magnitude = min(max(abs(c) - abs(coc_ab.y) * focus_range, real(0)), max_coc);
    return c < real(0) ? -magnitude : magnitude;
}

// ---- motion, classification ------------------------------------------------

BC_FN vec3 vertex_at(BC_IN(MovingTriangle) tri, int i, real t, vec2 uv) {
    vec3 p = (real(1) - t) * tri.p[i] + t * tri.p[i + 3];
    vec2 c = (real(1) - t) * tri.c[i] + t * tri.c[i + 3];
    return vec3(p.x + uv.x * c.x, p.y + uv.y * c.y, p.z);
}

BC_FN bool triangle_is_finite(BC_IN(MovingTriangle) tri) {
    for (int j = 0; j < 6; ++j) {
        if (!bc_finite(tri.p[j].x) || !bc_finite(tri.p[j].y) || !bc_finite(tri.p[j].z) ||
            !bc_finite(tri.c[j].x) || !bc_finite(tri.c[j].y))
            return false;
    }
    return true;
}

// What a triangle needs: 0 = static and in focus (plain rasterization),
// BC_NEEDS_MOTION and/or BC_NEEDS_DEFOCUS, or BC_INVALID for NaN/Inf input.
BC_FN int classify(BC_IN(MovingTriangle) tri) {
    if (!triangle_is_finite(tri)) return BC_INVALID;
    int needs = 0;
    for (int i = 0; i < 3; ++i) {
        if (tri.p[i] != tri.p[i + 3] || tri.c[i] != tri.c[i + 3]) needs |= BC_NEEDS_MOTION;
    }
    for (int j = 0; j < 6; ++j) {
        if (tri.c[j] != vec2(real(0))) needs |= BC_NEEDS_DEFOCUS;
    }
    return needs;
}

// ---- the exact coverage test (the oracle) ------------------------------------

// Homogeneous 2D rasterization (Olano and Greer 1997): with the sheared
// vertices V_i as columns of M, the ray through (s, 1) meets the triangle in
// front of the eye iff all components of adj(M) (s, 1) share the sign of
// det(M). The hit depth is det / sum(adj(M) (s, 1)). Correct for vertices
// behind the eye; samples whose hit lies closer than `near` are not covered.
BC_FN bool covers(BC_IN(MovingTriangle) tri, vec2 s, vec2 uv, real t, real near, BC_OUT(real) depth) {
    depth = real(0);
    vec3 v0 = vertex_at(tri, 0, t, uv);
    vec3 v1 = vertex_at(tri, 1, t, uv);
    vec3 v2 = vertex_at(tri, 2, t, uv);
    vec3 ray = vec3(s.x, s.y, real(1));
    vec3 n12 = cross(v1, v2);
    real e0 = bc_dot3(n12, ray);
    real e1 = bc_dot3(cross(v2, v0), ray);
    real e2 = bc_dot3(cross(v0, v1), ray);
    real det = bc_dot3(v0, n12);
    if (!(det != real(0))) return false;  // zero area seen edge-on (or NaN)
    if (det < real(0)) {
        e0 = -e0;
        e1 = -e1;
        e2 = -e2;
        det = -det;
    }
    if (!(e0 >= real(0) && e1 >= real(0) && e2 >= real(0))) return false;
    real sum = e0 + e1 + e2;
    if (!(sum > real(0))) return false;
    depth = det / sum;
    return depth >= near;
}

// The exact test sees a sheared vertex (x + u c, y + v c, w). Where the
// shear is more than BC_SWAMP_RATIO times the vertex's own (x, y, w), the
// double oracle's rounding of x + u c (relative error 2^-53) erases most of
// the vertex; with two such vertices at one time the edge between them is
// their cross product, whose true value (~ |c| (|x| + |w|)) is then far below
// its rounding error (~ 2^-53 c^2), and the oracle's sign tests (its verdict)
// are decided by rounding anywhere on the screen. No bound can contain such
// answers: screen_bound and sample_bounds keep every sample (docs/kernel.md,
// "Where the oracle is decided by rounding"). Vertices are checked at the
// shutter ends, where the stress families put them; the positions between
// interpolate away from the ends' magnitudes.
#define BC_SWAMP_RATIO 1.0e9

// Whether the bounds can say anything: every value finite (else BC_INVALID's
// fallback), and no two vertices at one shutter end swamped by their lens
// shear. One pass, sharing the finiteness test's loads and abs().
BC_FN bool bc_triangle_boundable(BC_IN(MovingTriangle) tri) {
    int swamped_open = 0;
    int swamped_close = 0;
    for (int j = 0; j < 6; ++j) {
        vec3 p = tri.p[j];
        vec2 c = tri.c[j];
        if (!bc_finite(p.x) || !bc_finite(p.y) || !bc_finite(p.z) || !bc_finite(c.x) || !bc_finite(c.y)) return false;
        if (abs(c.x) + abs(c.y) > real(BC_SWAMP_RATIO) * (abs(p.x) + abs(p.y) + abs(p.z))) {
            if (j < 3) swamped_open = swamped_open + 1;
            else swamped_close = swamped_close + 1;
        }
    }
    return swamped_open < 2 && swamped_close < 2;
}

// ---- screen bounds -------------------------------------------------------------

// Screen extent along one axis of everything the triangle can show in front of
// the near plane. Along the axis the triangle at any (t, u) lies in the convex
// hull of the 12 points (x_ik +- |c_ik|, w_ik); its part with w >= near has
// as vertices those points with w >= near and the crossings of point pairs
// with w = near (the thesis's 6 edges and 3 motion paths, plus the lens and
// the diagonals, which its motion makes necessary). x / w is extremal there.
// Returns (lo, hi); lo > hi when nothing is in front of the near plane.
BC_FN vec2 bc_axis_extent(BC_IN(MovingTriangle) tri, int axis, real near_plane) {
    // The oracle rounds a hit depth just short of the near plane up to it, so
    // the extent is taken in front of a plane a margin closer to the eye.
    real near = near_plane - bc_err(near_plane);
    real lo = bc_huge();
    real hi = -bc_huge();
    real magnitude = real(0);
    for (int j = 0; j < 12; ++j) {
        int ij = j / 2;
        real xj = tri.p[ij][axis] + (j % 2 == 0 ? real(-1) : real(1)) * abs(tri.c[ij][axis]);
        real wj = tri.p[ij].z;
        real mj = abs(tri.p[ij][axis]) + abs(tri.c[ij][axis]);
        if (wj >= near) {
            real sx = xj / wj;
            lo = min(lo, sx);
            hi = max(hi, sx);
            magnitude = max(magnitude, mj / wj);
        }
        for (int m = j + 1; m < 12; ++m) {
            int im = m / 2;
            real wm = tri.p[im].z;
            if ((wj < near && wm > near) || (wj > near && wm < near)) {
                real xm = tri.p[im][axis] + (m % 2 == 0 ? real(-1) : real(1)) * abs(tri.c[im][axis]);
                real mm = abs(tri.p[im][axis]) + abs(tri.c[im][axis]);
                real f = (near - wj) / (wm - wj);
                real sx = (xj + f * (xm - xj)) / near;
                lo = min(lo, sx);
                hi = max(hi, sx);
                magnitude = max(magnitude, (mj + mm) / near);
            }
        }
    }
    if (lo > hi) return vec2(real(1), real(-1));
    real pad = bc_err(real(4) * magnitude + max(abs(lo), abs(hi)));
    lo = lo - pad;
    hi = hi + pad;
    if (!bc_finite(lo) || !bc_finite(hi) || !bc_finite(pad)) return vec2(-bc_huge(), bc_huge());
    return vec2(lo, hi);
}

BC_FN bool bc_point_less(vec2 a, vec2 b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

BC_FN real bc_turn(vec2 o, vec2 a, vec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Convex hull (McGuire et al. 2010) of the lens-shifted vertices at both shutter
// ends; needs every vertex in front of the near plane (projection keeps
// convexity only there). Andrew's monotone chain over at most 24 points.
BC_FN void bc_build_hull(BC_IN(MovingTriangle) tri, real near, BC_INOUT(ScreenBound) b) {
    b.hull_count = 0;
    for (int j = 0; j < 6; ++j) {
        if (!(tri.p[j].z >= near) || !(tri.p[j].z > real(0))) return;
    }
    vec2 pts[BC_HULL_MAX];
    int n = 0;
    real magnitude = real(0);
    for (int j = 0; j < 6; ++j) {
        vec2 c = abs(tri.c[j]);
        int corners = (c.x == real(0) && c.y == real(0)) ? 1 : 4;
        for (int q = 0; q < corners; ++q) {
            vec2 lens = vec2(q % 2 == 0 ? real(-1) : real(1), q / 2 == 0 ? real(-1) : real(1));
            vec2 sp = vec2(tri.p[j].x + lens.x * c.x, tri.p[j].y + lens.y * c.y) / tri.p[j].z;
            // insertion sort by (x, y)
            int k = n;
            while (k > 0) {
                if (!bc_point_less(sp, pts[k - 1])) break;
                pts[k] = pts[k - 1];
                k = k - 1;
            }
            pts[k] = sp;
            n = n + 1;
        }
        magnitude = max(magnitude, (abs(tri.p[j].x) + abs(tri.p[j].y) + c.x + c.y) / tri.p[j].z);
    }
    // Turns of points beyond sqrt(huge) / 4 can overflow to NaN, which pops
    // nothing and would overrun hull[]: the box alone bounds such triangles.
    real extent = real(0);
    for (int j = 0; j < n; ++j) extent = max(extent, max(abs(pts[j].x), abs(pts[j].y)));
    if (!(extent <= real(0.25) * sqrt(bc_huge()))) return;
    vec2 hull[BC_HULL_MAX + 1];
    int h = 0;
    for (int j = 0; j < n; ++j) {  // lower chain
        while (h >= 2) {
            if (!(bc_turn(hull[h - 2], hull[h - 1], pts[j]) <= real(0))) break;
            h = h - 1;
        }
        hull[h] = pts[j];
        h = h + 1;
    }
    int lower = h + 1;
    for (int j = n - 2; j >= 0; --j) {  // upper chain
        while (h >= lower) {
            if (!(bc_turn(hull[h - 2], hull[h - 1], pts[j]) <= real(0))) break;
            h = h - 1;
        }
        hull[h] = pts[j];
        h = h + 1;
    }
    h = h - 1;  // the last point repeats the first
    if (h < 3) return;  // degenerate: the box alone bounds it
    real scale = bc_err(real(4) * magnitude + real(1));
    for (int k = 0; k < h; ++k) {
        vec2 a = hull[k];
        vec2 e = hull[k + 1] - a;
        vec2 n2 = vec2(-e.y, e.x);  // inward normal of a counter-clockwise hull
        real d = -dot(n2, a);
        // Rounded turns can keep a slightly concave chain, whose edges would
        // cut off some point: move each edge out until every point is inside.
        for (int j = 0; j < n; ++j) d = max(d, -dot(n2, pts[j]));
        d = d + (abs(n2.x) + abs(n2.y)) * scale;
        if (!bc_finite(d)) return;  // the margin overflowed: the box alone (hull_count stays 0)
        b.hull_edge[k] = vec3(n2.x, n2.y, d);
    }
    b.hull_count = h;
}

// Per-triangle screen bound: the clipped, CoC-grown box; with method
// BC_CULL_HULL also the convex hull when no vertex is behind the near plane.
// Non-finite input or results give the whole screen (never a cull).
BC_FN ScreenBound screen_bound(BC_IN(MovingTriangle) tri, real near, int method) {
    ScreenBound b;
    b.empty = false;
    b.lo = vec2(-bc_huge());
    b.hi = vec2(bc_huge());
    b.hull_count = 0;
    for (int k = 0; k < BC_HULL_MAX; ++k) b.hull_edge[k] = vec3(real(0));
    if (!(near > real(0)) || !bc_triangle_boundable(tri)) return b;
    vec2 ex = bc_axis_extent(tri, 0, near);
    vec2 ey = bc_axis_extent(tri, 1, near);
    b.lo = vec2(ex.x, ey.x);
    b.hi = vec2(ex.y, ey.y);
    b.empty = ex.x > ex.y || ey.x > ey.y;
    if ((method == BC_CULL_HULL || method == BC_CULL_CLIP2 || method == BC_CULL_EDGES) && !b.empty) bc_build_hull(tri, near, b);
    return b;
}

#define BC_FOOTPRINT_OUTSIDE 0
#define BC_FOOTPRINT_PARTIAL 1
#define BC_FOOTPRINT_INSIDE 2

// Where a screen rectangle [lo, hi] lies relative to the bound: entirely
// outside (no sample in it can pass screen_contains), entirely inside (every
// sample passes; a renderer may skip the per-sample test), or partly.
BC_FN int screen_footprint(BC_IN(ScreenBound) b, vec2 lo, vec2 hi) {
    if (b.empty || hi.x < b.lo.x || lo.x > b.hi.x || hi.y < b.lo.y || lo.y > b.hi.y) return BC_FOOTPRINT_OUTSIDE;
    bool inside = lo.x >= b.lo.x && hi.x <= b.hi.x && lo.y >= b.lo.y && hi.y <= b.hi.y;
    for (int k = 0; k < b.hull_count; ++k) {
        vec3 e = b.hull_edge[k];
        // The rectangle's corner farthest inside and farthest outside this edge.
        real best = e.z + max(e.x * lo.x, e.x * hi.x) + max(e.y * lo.y, e.y * hi.y);
        real worst = e.z + min(e.x * lo.x, e.x * hi.x) + min(e.y * lo.y, e.y * hi.y);
        // Outside only with room for rounding: a sample's own test sums differently.
        real slack = bc_err(abs(e.x) * max(abs(lo.x), abs(hi.x)) + abs(e.y) * max(abs(lo.y), abs(hi.y)) + abs(e.z));
        if (best < -slack) return BC_FOOTPRINT_OUTSIDE;
        if (!(worst >= real(0))) inside = false;
    }
    return inside ? BC_FOOTPRINT_INSIDE : BC_FOOTPRINT_PARTIAL;
}

BC_FN bool screen_contains(BC_IN(ScreenBound) b, vec2 s) {
    if (b.empty) return false;
    if (s.x < b.lo.x || s.x > b.hi.x || s.y < b.lo.y || s.y > b.hi.y) return false;
    for (int k = 0; k < b.hull_count; ++k) {
        if (b.hull_edge[k].x * s.x + b.hull_edge[k].y * s.y + b.hull_edge[k].z < real(0)) return false;
    }
    return true;
}

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
BC_FN bool bc_dual_time(BC_IN(MovingTriangle) tri, int axis, real s0, real s1, BC_OUT(vec2) tr) {
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
BC_FN vec2 bc_dual_lens(BC_IN(MovingTriangle) tri, int axis, real s0, real s1) {
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

// ---- clip-space two-stage bounds --------------------------------------------------

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
BC_FN vec2 bc_stage1(BC_IN(MovingTriangle) tri, int axis, BC_IN(BcEdgeCrossings) x) {
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
BC_FN bool bc_stage2(BC_IN(MovingTriangle) tri, int axis, real s0, real s1, BC_IN(BcEdgeCrossings) x,
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
