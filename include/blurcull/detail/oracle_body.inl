// Shared C++/GLSL text (see dialect.hpp): the exact coverage test (the
// oracle every bound must contain), and when the bounds can say anything about
// it. Needs coc_motion_body.inl.

// ---- the exact coverage test (the oracle) ------------------------------------

// Homogeneous 2D rasterization (Olano and Greer 1997): with the sheared
// vertices V_i as columns of M, the ray through (s, 1) meets the triangle in
// front of the eye iff all components of adj(M) (s, 1) share the sign of
// det(M). The hit depth is det / sum(adj(M) (s, 1)), and the hit point is
// sum_i b_i V_i with b = adj(M) (s, 1) / sum: its barycentric coordinates,
// which the affine map from the sheared triangle back to the world-space
// triangle at time t keeps. Correct for vertices behind the eye; samples whose
// hit lies closer than `near` are not covered.
// a0 . (a1 x a2) with its terms added instead of cancelled, on magnitudes:
// the scale of that product's rounding error.
BC_FN real bc_det_terms(vec3 a0, vec3 a1, vec3 a2) {
    return a0.x * (a1.y * a2.z + a2.y * a1.z) + a0.y * (a1.z * a2.x + a2.z * a1.x) +
           a0.z * (a1.x * a2.y + a2.x * a1.y);
}

BC_FN bool covers_hit(BC_IN(MovingTriangle) tri, vec2 s, vec2 uv, real t, real near, BC_OUT(real) depth,
                      BC_OUT(vec3) barycentric) {
    depth = real(0);
    barycentric = vec3(real(0));
    vec3 v0 = vertex_at(tri, 0, t, uv);
    vec3 v1 = vertex_at(tri, 1, t, uv);
    vec3 v2 = vertex_at(tri, 2, t, uv);
    vec3 ray = vec3(s.x, s.y, real(1));
    // Everything relative to v0 (docs/kernel.md, "The oracle's
    // conditioning"): with d1 = v1 - v0,
    // d2 = v2 - v0, n = d1 x d2 and q = ray x v0, in exact arithmetic
    //   e1 = (v2 x v0) . ray = -d2 . q,   e2 = (v0 x v1) . ray = d1 . q,
    //   e0 = (v1 x v2) . ray = (d2 - d1) . q + n . ray,   det = v0 . n.
    // q cancels to the ray's offset from v0, so an edge lands within about
    // eps |s| of where it is, whatever the triangle's size; the products of
    // absolute vertices placed a short edge within eps (1 + |s|)^3 / length.
    vec3 d1 = v1 - v0;
    vec3 d2 = v2 - v0;
    vec3 n = cross(d1, d2);
    // det M, the facing: its rounding is relative to the triangle's size.
    // Where it lies within that rounding the triangle is seen edge-on through
    // the eye and its sign is unknown; with the wrong sign the edge tests
    // would accept the triangle's image behind the eye, a line far beyond
    // it that no bound contains. Such a triangle covers nothing. Rejects
    // NaN too.
    real det = bc_dot3(v0, n);
    real det_error = real(32) * bc_epsilon() * bc_det_terms(abs(v0), abs(d1), abs(d2));
    if (!(abs(det) > det_error)) return false;
    vec3 q = cross(ray, v0);
    vec3 d21 = d2 - d1;
    real e0 = bc_dot3(d21, q) + bc_dot3(n, ray);
    real e1 = -bc_dot3(d2, q);
    real e2 = bc_dot3(d1, q);
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
    barycentric = vec3(e0 / sum, e1 / sum, e2 / sum);
    return depth >= near;
}

// covers_hit without the barycentric coordinates: the same arithmetic, so the
// same verdict and depth bit for bit.
BC_FN bool covers(BC_IN(MovingTriangle) tri, vec2 s, vec2 uv, real t, real near, BC_OUT(real) depth) {
    vec3 barycentric;
    return covers_hit(tri, s, uv, t, near, depth, barycentric);
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
