// Shared C++/GLSL text (see dialect.hpp): the kernel's model, its rounding
// margins, the circle of confusion, motion and classification. The other
// kernel bodies (oracle, screen_bound, dual_space, two_stage, sample_bounds)
// build on it, in that order.
//
// Model (docs/kernel.md has the derivations):
//  - clip space (x, y, w), w = view depth; vertex i at shutter end k is
//    tri.p[i + 3k], its signed circle of confusion (c_x, c_y) is tri.c[i + 3k];
//  - at time t in [0,1] both interpolate linearly; a lens sample (u, v) in
//    [-1,1]^2 shears a vertex to (x + u c_x, y + v c_y, w);
//  - a sample (s, u, v, t) is covered when the sheared triangle at t contains
//    the ray through screen position s at a depth w >= near.
// Every bound below contains every covered sample: false culls are bugs.

#define BC_NEEDS_MOTION 1
#define BC_NEEDS_DEFOCUS 2
#define BC_INVALID 4

// Margin policy: every rounded quantity is widened by BC_MARGIN machine
// epsilons of the magnitude it was computed from (docs/kernel.md, "Margins").
#define BC_MARGIN 64

struct MovingTriangle {
    vec3 p[6];  // clip (x, y, w) of vertex i at shutter open (i) and close (i + 3)
    vec2 c[6];  // signed circle of confusion (c_x, c_y), same indexing
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

// The signed CoC c(w) = a + b w of the thin lens (a, b) = coc_ab at view depth w.
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

// Vertex i (0..2) at shutter time t in [0, 1], sheared by lens position uv:
// clip (x + u c_x, y + v c_y, w), positions and CoC interpolated linearly.
BC_FN vec3 vertex_at(BC_IN(MovingTriangle) tri, int i, real t, vec2 uv) {
    vec3 p = (real(1) - t) * tri.p[i] + t * tri.p[i + 3];
    vec2 c = (real(1) - t) * tri.c[i] + t * tri.c[i + 3];
    return vec3(p.x + uv.x * c.x, p.y + uv.y * c.y, p.z);
}

// Whether every position and CoC of the triangle is finite (no NaN, no Inf).
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
