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

// Which vertex covers_hit works relative to: the smallest in the L1
// norm, the lowest index on a tie (so v0 for most triangles). Relative to a
// vertex far larger than another, the difference to the small one rounds to
// minus the large one and the small vertex is lost (docs/kernel.md, "The
// oracle's conditioning"); relative to the smallest, every difference keeps
// both ends. Chosen per sample from the vertices at its time and lens
// position, since a vertex small at one shutter end need not be at the other.
BC_FN int bc_oracle_pivot(vec3 v0, vec3 v1, vec3 v2) {
    real m0 = abs(v0.x) + abs(v0.y) + abs(v0.z);
    real m1 = abs(v1.x) + abs(v1.y) + abs(v1.z);
    real m2 = abs(v2.x) + abs(v2.y) + abs(v2.z);
    int pivot = 0;
    if (m1 < m0) {
        pivot = 1;
        m0 = m1;
    }
    if (m2 < m0) pivot = 2;
    return pivot;
}

// The largest |s.x|, |s.y| at which covers_hit takes its edges in the
// sheared frame: 1 / (1024 eps), 8,192 in float (every screen and guard band,
// and motion thousands of screen widths out), 2^42 in double.
BC_FN real bc_shear_limit() { return real(1) / (real(1024) * bc_epsilon()); }

BC_FN bool covers_hit(BC_IN(MovingTriangle) tri, vec2 s, vec2 uv, real t, real near, BC_OUT(real) depth,
                      BC_OUT(vec3) barycentric) {
    depth = real(0);
    barycentric = vec3(real(0));
    vec3 a0 = vertex_at(tri, 0, t, uv);
    vec3 a1 = vertex_at(tri, 1, t, uv);
    vec3 a2 = vertex_at(tri, 2, t, uv);
    // The vertices in cyclic order from the pivot: (v0, v1, v2) is
    // (a_p, a_p+1, a_p+2), which keeps det's sign and maps edge j to edge p+j.
    int pivot = bc_oracle_pivot(a0, a1, a2);
    vec3 v0 = a0;
    vec3 v1 = a1;
    vec3 v2 = a2;
    if (pivot == 1) {
        v0 = a1;
        v1 = a2;
        v2 = a0;
    } else if (pivot == 2) {
        v0 = a2;
        v1 = a0;
        v2 = a1;
    }
    // Everything relative to the pivot v0 (docs/kernel.md, "The oracle's
    // conditioning"): d1 = v1 - v0, d2 = v2 - v0, n = d1 x d2, det M = v0 . n,
    // whose rounding is relative to the triangle's size (bc_det_terms).
    // Where det lies within that rounding the triangle is seen edge-on
    // through the eye and its sign is unknown; with the wrong sign the edge
    // tests would accept the triangle's image behind the eye, a line far
    // beyond it that no bound contains. Such a triangle covers nothing.
    // Rejects NaN too.
    vec3 d1 = v1 - v0;
    vec3 d2 = v2 - v0;
    vec3 n = cross(d1, d2);
    real det = bc_dot3(v0, n);
    real det_error = real(32) * bc_epsilon() * bc_det_terms(abs(v0), abs(d1), abs(d2));
    if (!(abs(det) > det_error)) return false;
    // The edge values e_j = (v_j+1 x v_j+2) . (s, 1) in the frame sheared so
    // that the sample's ray is the w axis, (x, y, w) -> (x - s.x w, y - s.y w,
    // w): a shear of determinant 1 mapping (s, 1) to (0, 0, 1), so
    // e_j = (v'_j+1 x v'_j+2).z exactly. With the pivot's offset from the ray
    // p = (x0 - s.x w0, y0 - s.y w0) and the sheared edges
    // a_i = d_i.x - s.x d_i.w, b_i = d_i.y - s.y d_i.w:
    //   e1 = a2 p.y - b2 p.x,   e2 = p.x b1 - p.y a1,
    //   e0 = (b2 - b1) p.x - (a2 - a1) p.y + (a1 b2 - b1 a2).
    // p is the ray's offset from v0 and the a, b as small as the triangle, so
    // an edge lands within a few eps |s| of where it is whatever the
    // triangle's size or tilt (unsheared, a tilted triangle's d.w times
    // s.x y0 - s.y x0 placed it within eps |s|^2 |d.w| / |d|). Beyond
    // bc_shear_limit the sheared products outgrow what they measure (their
    // cancellation is relative eps |s| |d.w| / |d|), and the unsheared form
    // with q = (s, 1) x v0 is the better conditioned:
    //   e1 = -d2 . q,   e2 = d1 . q,   e0 = (d2 - d1) . q + n . (s, 1).
    real e0;
    real e1;
    real e2;
    if (max(abs(s.x), abs(s.y)) <= bc_shear_limit()) {
        real px = v0.x - s.x * v0.z;
        real py = v0.y - s.y * v0.z;
        real sa1 = d1.x - s.x * d1.z;
        real sb1 = d1.y - s.y * d1.z;
        real sa2 = d2.x - s.x * d2.z;
        real sb2 = d2.y - s.y * d2.z;
        e0 = (sb2 - sb1) * px - (sa2 - sa1) * py + (sa1 * sb2 - sb1 * sa2);
        e1 = sa2 * py - sb2 * px;
        e2 = px * sb1 - py * sa1;
    } else {
        vec3 ray = vec3(s.x, s.y, real(1));
        vec3 q = cross(ray, v0);
        vec3 d21 = d2 - d1;
        e0 = bc_dot3(d21, q) + bc_dot3(n, ray);
        e1 = -bc_dot3(d2, q);
        e2 = bc_dot3(d1, q);
    }
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
    // Edge value j belongs to vertex pivot + j.
    vec3 b = vec3(e0 / sum, e1 / sum, e2 / sum);
    barycentric = b;
    if (pivot == 1) barycentric = vec3(b.z, b.x, b.y);
    else if (pivot == 2) barycentric = vec3(b.y, b.z, b.x);
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
