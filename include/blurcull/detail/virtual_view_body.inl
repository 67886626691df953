// Shared C++/GLSL text (see dialect.hpp): the virtual viewpoint of a cluster
// of reflector pixels (Xie, Sun, Wang 2013, section 3.3).
//
// The view looks along the mean specular direction f of the cluster. Its eye
// starts at the mean position m and backs off to e = m - t f. The frustum is
// square: a point p with view coordinates (x, y, z) = ((p - e).right,
// (p - e).up, (p - e).f) is inside when max(|x|, |y|) <= z tan(fov / 2).
// Backing off leaves x and y unchanged and adds t to z, so point i is inside
// for every t >= t_i = max(|x_i|, |y_i|) / tan(fov / 2) - z_i (coordinates
// relative to m), and the smallest back-off is t = max(0, max_i t_i): a closed
// form, one pass, no search (docs/secondary-rays.md, "Virtual viewpoint").
// A point must also be at least min_near in front of the eye, so
// t_i = max(max(|x_i|, |y_i|) / tan(fov / 2), min_near) - z_i.
//
// Use: sums = cluster_sums_add over the cluster's pixels (first pass), fit =
// virtual_view_begin(sums, ...), fit = virtual_view_add(fit, p, d) for every
// pixel (second pass, any order), view = virtual_view_finish(fit).

// Flags of VirtualView (a bit set; 0 = usable).
#define BC_VIEW_OK 0
// No pixel, or the specular directions sum to zero (no mean direction).
#define BC_VIEW_EMPTY 1
// tan_half_fov or min_near not a positive finite number.
#define BC_VIEW_BAD_PARAMETERS 2
// Some pixel's specular direction leaves the frustum: its ray escapes every
// viewpoint on this axis, whatever the back-off. The caller splits the
// cluster or traces those rays another way.
#define BC_VIEW_DIRECTION_OUTSIDE 4
// A position or direction was NaN or infinite.
#define BC_VIEW_NOT_FINITE 8

struct VirtualView {
    vec3 eye;           // scene units
    vec3 forward;       // unit: the mean specular direction
    vec3 right;         // unit, perpendicular to forward; image x
    vec3 up;            // unit, image y; right x up = forward
    real tan_half_fov;  // tan(fov / 2) of the square frustum
    real near;          // view depth of the cluster's closest pixel (near plane)
    real backoff;       // t: distance from the mean position back to the eye
    int flags;          // BC_VIEW_* bits
};

// The state between the two passes of the fit.
struct VirtualViewFit {
    vec3 origin;  // mean position m
    vec3 forward;
    vec3 right;
    vec3 up;
    real tan_half_fov;
    real min_near;
    real backoff;    // max(0, max_i t_i) so far
    real depth_min;  // min_i z_i so far (relative to m)
    real magnitude;  // largest |term| of any t_i, for the rounding margin
    int flags;
};

// An orthonormal (right, up) for a unit forward, continuous except where
// forward.z changes sign (Duff et al., "Building an orthonormal basis,
// revisited", JCGT 6(1) 2017), with right x up = forward.
BC_FN void virtual_view_basis(vec3 forward, BC_OUT(vec3) right, BC_OUT(vec3) up) {
    real sign = forward.z >= real(0) ? real(1) : -real(1);
    BC_PRECISE real a = -real(1) / (sign + forward.z);
    BC_PRECISE real b = forward.x * forward.y * a;
    BC_PRECISE real rx = real(1) + sign * forward.x * forward.x * a;
    BC_PRECISE real uy = sign + forward.y * forward.y * a;
    right = vec3(rx, sign * b, -sign * forward.x);
    up = vec3(b, uy, -forward.y);
}

// First step of a fit along a given view axis (any length, normalised here)
// instead of the mean direction: e.g. the facet's normal (dodecahedron_normal)
// when the mean direction leaves some ray outside. Every direction of one
// facet is within 37.38 degrees of its normal, so along the normal a field of
// view of at least 74.76 degrees contains them all. Parameters and flags as
// in virtual_view_begin; a zero or non-finite axis gives BC_VIEW_EMPTY or
// BC_VIEW_NOT_FINITE.
BC_FN VirtualViewFit virtual_view_begin_along(BC_IN(ClusterSums) sums, vec3 axis, real tan_half_fov, real min_near) {
    VirtualViewFit f;
    f.flags = BC_VIEW_OK;
    f.origin = cluster_mean_position(sums);
    f.tan_half_fov = tan_half_fov;
    f.min_near = min_near;
    f.backoff = real(0);
    f.depth_min = bc_huge();
    f.magnitude = real(0);
    if (!(tan_half_fov > real(0)) || !bc_finite(tan_half_fov) || !(min_near > real(0)) || !bc_finite(min_near))
        f.flags |= BC_VIEW_BAD_PARAMETERS;
    real length2 = bc_dot3(axis, axis);
    if (!bc_finite(length2) || !bc_finite(f.origin.x) || !bc_finite(f.origin.y) || !bc_finite(f.origin.z))
        f.flags |= BC_VIEW_NOT_FINITE;
    if (sums.unfit != 0u) f.flags |= BC_VIEW_NOT_FINITE;
    if (sums.count == 0u || !(length2 > bc_tiny())) f.flags |= BC_VIEW_EMPTY;
    bool has_axis = (f.flags & (BC_VIEW_EMPTY | BC_VIEW_NOT_FINITE)) == 0;
    f.forward = has_axis ? axis / sqrt(length2) : vec3(real(0), real(0), real(1));
    virtual_view_basis(f.forward, f.right, f.up);
    return f;
}

// First step of the fit, from the sums over the cluster's pixels: the view
// axis is their mean specular direction. tan_half_fov = tan(fov / 2), fov in
// (0, 180) degrees (the paper: 80); min_near > 0 (scene units) keeps the eye
// at least that far behind every pixel, so the near plane is never at zero.
BC_FN VirtualViewFit virtual_view_begin(BC_IN(ClusterSums) sums, real tan_half_fov, real min_near) {
    return virtual_view_begin_along(sums, cluster_direction_sum(sums), tan_half_fov, min_near);
}

// The back-off t_i at which `position` enters the frustum and is min_near in
// front of the eye (scene units; negative when it is inside already at t = 0).
BC_FN real virtual_view_point_backoff(BC_IN(VirtualViewFit) f, vec3 position) {
    vec3 r = position - f.origin;
    real side = max(abs(bc_dot3(r, f.right)), abs(bc_dot3(r, f.up))) / f.tan_half_fov;
    return max(side, f.min_near) - bc_dot3(r, f.forward);
}

// Whether a ray direction stays inside the frustum of the view (forward,
// right, up, tan_half_fov): positive depth and max(|x|, |y|) <= z tan.
// The zero vector is outside.
BC_FN bool virtual_view_direction_inside(vec3 forward, vec3 right, vec3 up, real tan_half_fov, vec3 direction) {
    real z = bc_dot3(direction, forward);
    real side = max(abs(bc_dot3(direction, right)), abs(bc_dot3(direction, up)));
    return z > real(0) && side <= z * tan_half_fov;
}

// Second step: `f` with one more pixel of the cluster.
BC_FN VirtualViewFit virtual_view_add(BC_IN(VirtualViewFit) f, vec3 position, vec3 direction) {
    VirtualViewFit g = f;
    vec3 r = position - f.origin;
    real z = bc_dot3(r, f.forward);
    real t = virtual_view_point_backoff(f, position);
    if (!bc_finite(t) || !bc_finite(direction.x) || !bc_finite(direction.y) || !bc_finite(direction.z)) {
        g.flags |= BC_VIEW_NOT_FINITE;
        return g;
    }
    g.backoff = max(g.backoff, t);
    g.depth_min = min(g.depth_min, z);
    // t_i rounds relative to the coordinates it is made of (r = p - m and its
    // projections, the latter divided by tan).
    vec3 size = abs(position) + abs(f.origin);
    real scale = max(max(size.x, size.y), size.z) * (real(1) + real(1) / f.tan_half_fov);
    g.magnitude = max(g.magnitude, scale + abs(t) + f.min_near);
    if (!virtual_view_direction_inside(f.forward, f.right, f.up, f.tan_half_fov, direction))
        g.flags |= BC_VIEW_DIRECTION_OUTSIDE;
    return g;
}

// Last step: the viewpoint. The back-off is widened by the rounding margin of
// its terms (bc_err), so every pixel tests inside despite rounding. The near
// plane is the closest pixel's depth at the unwidened back-off (>= min_near
// up to rounding), so every pixel is that margin behind it.
// With any flag but BC_VIEW_DIRECTION_OUTSIDE set the view is not usable.
BC_FN VirtualView virtual_view_finish(BC_IN(VirtualViewFit) f) {
    VirtualView v;
    v.forward = f.forward;
    v.right = f.right;
    v.up = f.up;
    v.tan_half_fov = f.tan_half_fov;
    v.flags = f.flags;
    real pad = bc_err(f.magnitude + abs(f.backoff));
    v.backoff = f.backoff + pad;
    v.eye = f.origin - v.backoff * f.forward;
    v.near = f.depth_min + f.backoff;
    return v;
}
