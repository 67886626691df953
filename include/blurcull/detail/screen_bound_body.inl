// Shared C++/GLSL text (see dialect.hpp): the per-triangle screen bound (the
// clipped, CoC-grown box and the convex hull) and its tests. Needs
// coc_motion_body.inl and oracle_body.inl. The cull modes are defined here
// because screen_bound is the first function that reads them.

// Which bounds screen_bound and sample_bounds compute (docs/kernel.md).
#define BC_CULL_BBOX 0
#define BC_CULL_HULL 1
#define BC_CULL_DUALSPACE 2
#define BC_CULL_TWO_STAGE 3
#define BC_CULL_EDGES 4  // the two-stage bounds and a plane per edge in (u, v, t) (edge_bounds_body.inl)
#define BC_CULL_HYPERPLANE 5  // the two-stage bounds and one hyperplane per edge per tile (hyperplane_body.inl)

// What a cull method needs, as flags (cull_traits): the bodies and the
// backends read these, never lists of methods, so a new method is one line
// of cull_traits, the body of what it adds, and its registry entry.
#define BC_CULL_BUILDS_HULL 1                // screen_bound adds the convex hull to the box
#define BC_CULL_DUAL_SPACE_AXES 2            // lens and time per footprint axis by dual_space_body.inl
#define BC_CULL_TWO_STAGE_AXES 4             // lens and time per footprint axis by two_stage_body.inl
#define BC_CULL_EDGE_PLANES_PER_BLOCK 8      // edge planes in (u, v, t) over the axes' box (edge_bounds_body.inl);
                                             // a tile's planes hold for its footprints, and may be left out
#define BC_CULL_HYPERPLANES_PER_TILE 16      // one hyperplane per edge in (x, y, u, v, t) per tile and the
                                             // tile test on each footprint's box (hyperplane_body.inl)
// Any per-footprint lens and time bound; any planes on top of it.
#define BC_CULL_BOUNDS_SAMPLES (BC_CULL_DUAL_SPACE_AXES | BC_CULL_TWO_STAGE_AXES)
#define BC_CULL_ADDS_PLANES (BC_CULL_EDGE_PLANES_PER_BLOCK | BC_CULL_HYPERPLANES_PER_TILE)

// The flags of cull method `cull` (BC_CULL_*); 0 (the box alone) for an unknown id.
BC_FN int cull_traits(int cull) {
    if (cull == BC_CULL_HULL) return BC_CULL_BUILDS_HULL;
    if (cull == BC_CULL_DUALSPACE) return BC_CULL_DUAL_SPACE_AXES;
    if (cull == BC_CULL_TWO_STAGE) return BC_CULL_BUILDS_HULL | BC_CULL_TWO_STAGE_AXES;
    if (cull == BC_CULL_EDGES) return BC_CULL_BUILDS_HULL | BC_CULL_TWO_STAGE_AXES | BC_CULL_EDGE_PLANES_PER_BLOCK;
    if (cull == BC_CULL_HYPERPLANE) return BC_CULL_BUILDS_HULL | BC_CULL_TWO_STAGE_AXES | BC_CULL_HYPERPLANES_PER_TILE;
    return 0;
}

#define BC_HULL_MAX 24

struct ScreenBound {
    bool empty;                   // the triangle is never in front of the near plane
    vec2 lo;                      // screen box (NDC), widened by the margins
    vec2 hi;
    int hull_count;               // > 0: also inside these edges
    vec3 hull_edge[BC_HULL_MAX];  // inside when dot(edge.xy, s) + edge.z >= 0
};

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
    // Crossings need a point behind the plane: most triangles have none,
    // and the 66 pairs are then skipped (they would add nothing).
    bool any_behind = false;
    for (int i = 0; i < 6; ++i) any_behind = any_behind || tri.p[i].z < near;
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
            if (!any_behind) break;
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
    // Each point is tested itself (max() would drop a NaN): a GPU may flush a
    // denormal w to 0 in the division after the comparison above kept it
    // (docs/glsl.md, M4), making 0 / 0.
    real limit = real(0.25) * sqrt(bc_huge());
    for (int j = 0; j < n; ++j) {
        if (!(abs(pts[j].x) <= limit) || !(abs(pts[j].y) <= limit)) return;
    }
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
        // Exact turns keep h <= n + 1; turns a GPU rounds inconsistently
        // (a denormal flushed in one and kept in another) need not: the box alone.
        if (h > BC_HULL_MAX) return;
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

// Per-triangle screen bound: the clipped, CoC-grown box; for a cull whose
// traits hold BC_CULL_BUILDS_HULL also the convex hull when no vertex is behind the near plane.
// Non-finite input or results give the whole screen (never a cull).
BC_FN ScreenBound screen_bound(BC_IN(MovingTriangle) tri, real near, int cull) {
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
    if ((cull_traits(cull) & BC_CULL_BUILDS_HULL) != 0 && !b.empty) bc_build_hull(tri, near, b);
    return b;
}

// Screen box (lo.x, lo.y, hi.x, hi.y) of the samples with time in
// [time.x, time.y], u in [u_range.x, u_range.y] and v in [v_range.x,
// v_range.y] (sub-ranges of [0, 1] and [-1, 1]). At such a (t, u) a vertex's
// clip (x + u c_x, w) is bilinear in (t, u), so it lies in the convex hull of
// its four corner points (time ends by lens ends); with every corner in front
// of the near plane x / w is extremal at one of the 12 corners of the
// triangle; y likewise with v. A corner behind it: bc_axis_extent's
// whole-shutter extents (they clip). Both axes in one pass: they share each
// corner's w and its reciprocal.
BC_FN vec4 bc_stratum_extent(BC_IN(MovingTriangle) tri, real near_plane, vec2 time, vec2 u_range, vec2 v_range) {
    real near = near_plane - bc_err(near_plane);
    vec2 lo = vec2(bc_huge());
    vec2 hi = vec2(-bc_huge());
    vec2 magnitude = vec2(real(0));
    for (int i = 0; i < 3; ++i) {
        // What the corners are computed from: their rounding is relative to it.
        vec2 size = abs(vec2(tri.p[i].x, tri.p[i].y)) + abs(vec2(tri.p[i + 3].x, tri.p[i + 3].y)) + abs(tri.c[i]) +
                    abs(tri.c[i + 3]);
        real depth_size = abs(tri.p[i].z) + abs(tri.p[i + 3].z);
        for (int e = 0; e < 2; ++e) {
            real t = e == 0 ? time.x : time.y;
            vec2 x = (real(1) - t) * vec2(tri.p[i].x, tri.p[i].y) + t * vec2(tri.p[i + 3].x, tri.p[i + 3].y);
            vec2 c = (real(1) - t) * tri.c[i] + t * tri.c[i + 3];
            real w = (real(1) - t) * tri.p[i].z + t * tri.p[i + 3].z;
            if (!(w >= near)) {
                vec2 ex = bc_axis_extent(tri, 0, near_plane);
                vec2 ey = bc_axis_extent(tri, 1, near_plane);
                return vec4(ex.x, ey.x, ex.y, ey.y);
            }
            // One division per corner pair (the product's rounding is in the margin).
            real inv_w = real(1) / w;
            vec2 s0 = (x + vec2(u_range.x, v_range.x) * c) * inv_w;
            vec2 s1 = (x + vec2(u_range.y, v_range.y) * c) * inv_w;
            lo = min(lo, min(s0, s1));
            hi = max(hi, max(s0, s1));
            magnitude = max(magnitude, (size + max(abs(s0), abs(s1)) * depth_size) * inv_w);
        }
    }
    // Twice bc_axis_extent's margin: the corners' interpolation and the
    // division by an interpolated w round too.
    vec4 box = vec4(-bc_huge(), -bc_huge(), bc_huge(), bc_huge());
    for (int axis = 0; axis < 2; ++axis) {
        real pad = bc_err(real(8) * magnitude[axis] + real(2) * max(abs(lo[axis]), abs(hi[axis])));
        real a = lo[axis] - pad;
        real b = hi[axis] + pad;
        if (bc_finite(a) && bc_finite(b) && bc_finite(pad)) {
            box[axis] = a;
            box[axis + 2] = b;
        }
    }
    return box;
}

// The screen box of the samples in one stratum of lens and shutter: time in
// [time.x, time.y], u in [u_range.x, u_range.y], v in [v_range.x, v_range.y],
// as (lo.x, lo.y, hi.x, hi.y); lo.x > hi.x when the stratum holds nothing.
// whole: screen_bound(tri, near, cull) for any cull, whose box it narrows.
// Fallback, whole's box: whole empty, near <= 0, a triangle screen_bound
// does not bound.
BC_FN vec4 stratum_screen_box(BC_IN(MovingTriangle) tri, real near, BC_IN(ScreenBound) whole, vec2 time, vec2 u_range,
                              vec2 v_range) {
    if (whole.empty) return vec4(real(1), real(1), real(-1), real(-1));
    vec4 box = vec4(whole.lo.x, whole.lo.y, whole.hi.x, whole.hi.y);
    if (!(near > real(0)) || !bc_triangle_boundable(tri)) return box;
    vec4 e = bc_stratum_extent(tri, near, time, u_range, v_range);
    box = vec4(max(box.x, e.x), max(box.y, e.y), min(box.z, e.z), min(box.w, e.w));
    if (box.x > box.z || box.y > box.w) return vec4(real(1), real(1), real(-1), real(-1));
    return box;
}

// The smallest |det| of the sheared vertices over time in [time.x, time.y]
// for one lens corner, from det's values f0..f3 at the range's ends and
// thirds, or 0 when the range may hold a sign change: det is a cubic in t
// (each sheared coordinate is linear in t), so it lies between the smallest
// and largest of its four Bernstein coefficients on the range.
BC_FN real bc_cubic_floor(real f0, real f1, real f2, real f3) {
    real b1 = (real(-5) * f0 + real(18) * f1 - real(9) * f2 + real(2) * f3) / real(6);
    real b2 = (real(2) * f0 - real(9) * f1 + real(18) * f2 - real(5) * f3) / real(6);
    real lo = min(min(f0, f3), min(b1, b2));
    real hi = max(max(f0, f3), max(b1, b2));
    if (lo > real(0)) return lo;
    if (hi < real(0)) return -hi;
    return real(0);
}

// The smallest |det| of the sheared vertices (as covers computes det:
// v0 . (v1 x v2), each vertex as vertex_at gives it) over time in
// [time.x, time.y] and the lens box u_range x v_range, or 0 when it may
// vanish there. det is bilinear in (u, v) (each term has one x and one y
// entry), so its extremes over the lens box are at the box's corners; per
// corner, bc_cubic_floor in t. The vertices at each of the four times are
// interpolated once for the four corners.
BC_FN real bc_det_floor(BC_IN(MovingTriangle) tri, vec2 time, vec2 u_range, vec2 v_range) {
    real h = time.y - time.x;
    real f[16];
    for (int n = 0; n < 4; ++n) {
        real t = n == 0 ? time.x : (n == 3 ? time.y : time.x + real(n) * h / real(3));
        vec3 p[3];
        vec2 c[3];
        for (int i = 0; i < 3; ++i) {
            p[i] = (real(1) - t) * tri.p[i] + t * tri.p[i + 3];
            c[i] = (real(1) - t) * tri.c[i] + t * tri.c[i + 3];
        }
        for (int k = 0; k < 4; ++k) {
            real u = (k % 2) == 0 ? u_range.x : u_range.y;
            real v = k < 2 ? v_range.x : v_range.y;
            vec3 v0 = vec3(p[0].x + u * c[0].x, p[0].y + v * c[0].y, p[0].z);
            vec3 v1 = vec3(p[1].x + u * c[1].x, p[1].y + v * c[1].y, p[1].z);
            vec3 v2 = vec3(p[2].x + u * c[2].x, p[2].y + v * c[2].y, p[2].z);
            f[k * 4 + n] = bc_dot3(v0, cross(v1, v2));
        }
    }
    real d = bc_huge();
    for (int k = 0; k < 4; ++k) d = min(d, bc_cubic_floor(f[k * 4], f[k * 4 + 1], f[k * 4 + 2], f[k * 4 + 3]));
    return d;
}

// The scale of a depth floor (depth_floor below): a number in [0, 1] such
// that every sample covers() covers with time in [time.x, time.y], u in
// u_range, v in v_range and |sx|, |sy| <= screen_extent gets a depth at
// least its triangle's smallest vertex depth at the sample's time times it.
// With D the smallest |det| of the sheared vertices over that box and Err a
// bound on the rounding of covers' edge values and det there, the computed
// depth is at least W D / (D + Err), W the smallest vertex depth
// (docs/kernel.md, "Depth floors"). 0 (nothing can be said) where a vertex
// is at or behind the eye, the triangle may be seen edge-on in the box, or
// a value is not finite.
BC_FN real depth_floor_scale(BC_IN(MovingTriangle) tri, vec2 time, vec2 u_range, vec2 v_range, real screen_extent) {
    real eps = bc_epsilon();
    if (!triangle_is_finite(tri) || !bc_finite(screen_extent)) return real(0);
    // Bounds on |x|, |y|, |w| of each sheared vertex (lens coordinates in
    // [-1, 1]), and its depth at the range's ends (w is linear in t).
    vec3 size[3];
    for (int i = 0; i < 3; ++i) {
        vec3 a = tri.p[i];
        vec3 b = tri.p[i + 3];
        real w0 = (real(1) - time.x) * a.z + time.x * b.z;
        real w1 = (real(1) - time.y) * a.z + time.y * b.z;
        if (!(min(w0, w1) > real(0))) return real(0);
        size[i] = vec3(max(abs(a.x) + abs(tri.c[i].x), abs(b.x) + abs(tri.c[i + 3].x)),
                       max(abs(a.y) + abs(tri.c[i].y), abs(b.y) + abs(tri.c[i + 3].y)), max(abs(a.z), abs(b.z)));
    }
    // P bounds |v0| . (|v1| x |v2|), the terms of det; A_i those of edge value
    // i at a ray (sx, sy, 1); Err = sum |w_i| A_i + P, times the roundings.
    real r = max(screen_extent, real(1));
    real err = real(0);
    real terms = real(0);
    for (int i = 0; i < 3; ++i) {
        vec3 a = size[(i + 1) % 3];
        vec3 b = size[(i + 2) % 3];
        vec3 n = vec3(a.y * b.z + a.z * b.y, a.z * b.x + a.x * b.z, a.x * b.y + a.y * b.x);
        err = err + size[i].z * ((n.x + n.y) * r + n.z);
        if (i == 0) terms = bc_dot3(size[0], n);
    }
    err = (err + terms) * (real(64) * eps);
    // D, less the rounding of its own computation (vertices, products, the
    // coefficients' sums).
    real d = bc_det_floor(tri, time, u_range, v_range) - terms * (real(1024) * eps);
    if (!(d > real(0)) || !bc_finite(err)) return real(0);
    real scale = (real(1) - real(16) * eps) * (d / (d + err));
    return bc_finite(scale) ? clamp(scale, real(0), real(1)) : real(0);
}

// A lower bound on the depth covers() gives any covered sample of the
// triangle with time in [time.x, time.y]: its smallest vertex depth at the
// range's ends times `scale`, depth_floor_scale over a box of time, lens and
// screen that holds the samples'. A renderer whose stored depths for those
// samples are all below it can skip them: the strict depth test fails on
// every one. 0 where a vertex is at or behind the eye.
BC_FN real depth_floor(BC_IN(MovingTriangle) tri, vec2 time, real scale) {
    real w = bc_huge();
    for (int i = 0; i < 3; ++i) {
        w = min(w, (real(1) - time.x) * tri.p[i].z + time.x * tri.p[i + 3].z);
        w = min(w, (real(1) - time.y) * tri.p[i].z + time.y * tri.p[i + 3].z);
    }
    if (!(w > real(0)) || !(scale > real(0))) return real(0);
    return w * scale;
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

// Whether screen position s (NDC) lies inside the bound: false means no
// sample at s can be covered.
BC_FN bool screen_contains(BC_IN(ScreenBound) b, vec2 s) {
    if (b.empty) return false;
    if (s.x < b.lo.x || s.x > b.hi.x || s.y < b.lo.y || s.y > b.hi.y) return false;
    for (int k = 0; k < b.hull_count; ++k) {
        if (b.hull_edge[k].x * s.x + b.hull_edge[k].y * s.y + b.hull_edge[k].z < real(0)) return false;
    }
    return true;
}
