// Shared C++/GLSL text (see dialect.hpp): the image-space tracing step of
// Lee, Eisemann and Seidel (EGSR 2009, SIGGRAPH 2010) as Xie, Sun and Wang
// use it for secondary rays: a ray segment is projected into a layered image
// (a view: eye, orthonormal axes, square frustum), clipped to the frustum and
// to a min/max depth interval, stepped over texel by texel, and the hit
// refined inside the step (docs/secondary-rays.md, "Image-space tracing").
//
// Layer images hold, per texel, the view depth z = (p - eye) . forward of the
// surface seen there (scene units); a texel with no surface holds +infinity
// or any value >= far (NaN is treated as empty as well). The caller reads
// them: layer_trace_begin names a texel, the caller reads every layer's depth
// there into a fixed-size array and passes it to layer_trace_step, which
// names the next texel. The bodies cannot read images themselves: a texture
// or buffer is the calling shader's declaration, and a function the caller
// must define (a GLSL prototype) breaks the link of every shader that does
// not (Mesa resolves calls from functions main never calls).
//
// Texel (x, y) covers continuous image coordinates [x, x+1) x [y, y+1);
// x grows along right, y along up, (0, 0) is the corner at -right, -up.

// Layers read per step, at most (the paper: 4 from the camera, 8 per cluster).
#define BC_LAYERS_MAX 8

struct LayerView {
    vec3 eye;           // scene units
    vec3 forward;       // unit viewing direction
    vec3 right;         // unit, image x
    vec3 up;            // unit, image y
    real tan_half_fov;  // square frustum: |x|, |y| <= z tan_half_fov
    real near;          // view depths kept: [near, far], 0 < near < far
    real far;
    int size;           // the layer images are size x size texels
};

// A ray segment clipped to a view and projected into its image.
struct LayerSegment {
    bool empty;  // nothing of the ray is inside the frustum and the interval
    real s0;     // ray parameters of the clipped ends (units of the direction)
    real s1;
    real z0;     // view depths at s0 and s1
    real z1;
    vec2 p0;     // continuous image coordinates at s0 and s1
    vec2 p1;
};

struct LayerHit {
    bool hit;
    int layer;    // layer image the hit is in
    real s;       // ray parameter of the hit point
    real depth;   // its view depth
    vec2 image;   // its continuous image coordinates
    int steps;    // texels visited (each reads layer_count depths)
};

// The view of a virtual viewpoint, with its far plane (> v.near) and image
// size (texels per side, >= 1).
BC_FN LayerView layer_view_from(BC_IN(VirtualView) v, real far, int size) {
    LayerView l;
    l.eye = v.eye;
    l.forward = v.forward;
    l.right = v.right;
    l.up = v.up;
    l.tan_half_fov = v.tan_half_fov;
    l.near = v.near;
    l.far = far;
    l.size = max(size, 1);
    return l;
}

// Continuous image coordinates of view coordinates (x, y, z), z > 0.
BC_FN vec2 bc_layer_image(BC_IN(LayerView) v, real x, real y, real z) {
    BC_PRECISE real scale = real(0.5) * real(v.size) / (z * v.tan_half_fov);
    BC_PRECISE real ix = x * scale + real(0.5) * real(v.size);
    BC_PRECISE real iy = y * scale + real(0.5) * real(v.size);
    return vec2(ix, iy);
}

// (image x, image y, view depth) of a scene point; image coordinates are
// meaningful only for depth > 0 (else 0).
BC_FN vec3 layer_project(BC_IN(LayerView) v, vec3 p) {
    vec3 q = p - v.eye;
    real z = bc_dot3(q, v.forward);
    if (!(z > real(0))) return vec3(real(0), real(0), z);
    vec2 image = bc_layer_image(v, bc_dot3(q, v.right), bc_dot3(q, v.up), z);
    return vec3(image.x, image.y, z);
}

// The part of the parameter range [range.x, range.y] where a + b s >= 0.
// Empty ranges come out with range.x > range.y.
BC_FN vec2 bc_clip_linear(vec2 range, real a, real b) {
    vec2 r = range;
    if (b > real(0)) r.x = max(r.x, -a / b);
    else if (b < real(0)) r.y = min(r.y, -a / b);
    else if (a < real(0)) r = vec2(real(1), real(0));
    return r;
}

// The ray origin + s direction, s in [0, s_max], clipped to the view's
// frustum and to view depths [max(near, depth_range.x), min(far,
// depth_range.y)] (the interval of a min/max depth pyramid over the
// footprint; pass (0, huge) for none), then projected. The direction need
// not be unit length; s is in its units. s_max may be +infinity (the frustum
// and the far plane bound the ray, unless the direction is zero). Fallback:
// a NaN or infinite origin, direction or interval, a NaN s_max, or nothing
// left after clipping gives an empty segment.
BC_FN LayerSegment layer_segment(BC_IN(LayerView) v, vec3 origin, vec3 direction, real s_max, vec2 depth_range) {
    vec3 q = origin - v.eye;
    real ox = bc_dot3(q, v.right);
    real oy = bc_dot3(q, v.up);
    real oz = bc_dot3(q, v.forward);
    real dx = bc_dot3(direction, v.right);
    real dy = bc_dot3(direction, v.up);
    real dz = bc_dot3(direction, v.forward);
    real z_lo = max(v.near, depth_range.x);
    real z_hi = min(v.far, depth_range.y);
    real tan_h = v.tan_half_fov;
    vec2 r = vec2(real(0), s_max);
    r = bc_clip_linear(r, oz - z_lo, dz);
    r = bc_clip_linear(r, z_hi - oz, -dz);
    r = bc_clip_linear(r, tan_h * oz - ox, tan_h * dz - dx);
    r = bc_clip_linear(r, tan_h * oz + ox, tan_h * dz + dx);
    r = bc_clip_linear(r, tan_h * oz - oy, tan_h * dz - dy);
    r = bc_clip_linear(r, tan_h * oz + oy, tan_h * dz + dy);
    LayerSegment seg;
    seg.s0 = r.x;
    seg.s1 = r.y;
    // NaN or infinite input anywhere makes the sum non-finite (the clips
    // above may have dropped it: max and min ignore a NaN operand).
    real input_sum = abs(ox) + abs(oy) + abs(oz) + abs(dx) + abs(dy) + abs(dz) + abs(z_lo) + abs(z_hi);
    seg.empty = !(r.x <= r.y) || !bc_finite(r.x) || !bc_finite(r.y) || !bc_finite(input_sum) || !(z_lo > real(0)) ||
                v.size < 1;
    // Rounding may put an end a hair outside [z_lo, z_hi]; the depth must stay
    // positive for the projection.
    seg.z0 = max(oz + r.x * dz, z_lo);
    seg.z1 = max(oz + r.y * dz, z_lo);
    seg.p0 = bc_layer_image(v, ox + r.x * dx, oy + r.x * dy, seg.z0);
    seg.p1 = bc_layer_image(v, ox + r.y * dx, oy + r.y * dy, seg.z1);
    if (seg.empty) {
        seg.z0 = z_lo;
        seg.z1 = z_lo;
        seg.p0 = vec2(real(0));
        seg.p1 = vec2(real(0));
    }
    return seg;
}

// The box of texels the segment crosses: (x_min, y_min, x_max, y_max),
// clamped to the image; where the caller reads its min/max depth pyramid.
// An empty segment gives x_min > x_max.
BC_FN vec4 layer_footprint(BC_IN(LayerView) v, BC_IN(LayerSegment) seg) {
    if (seg.empty) return vec4(real(1), real(1), real(0), real(0));
    real last = real(v.size - 1);
    vec2 lo = clamp(floor(min(seg.p0, seg.p1)), vec2(real(0)), vec2(last));
    vec2 hi = clamp(floor(max(seg.p0, seg.p1)), vec2(real(0)), vec2(last));
    return vec4(lo.x, lo.y, hi.x, hi.y);
}

// Number of steps over a segment: one per texel along its longer image axis,
// at least 1, at most 2 size + 2 (the segment is inside the image).
BC_FN int layer_step_count(BC_IN(LayerView) v, BC_IN(LayerSegment) seg) {
    if (seg.empty) return 0;
    vec2 span = abs(seg.p1 - seg.p0);
    real n = ceil(max(span.x, span.y));
    return int(clamp(n, real(1), real(2 * v.size + 2)));
}

// View depth of the segment at image fraction f in [0, 1] (perspective:
// 1 / z is linear in the image).
BC_FN real bc_segment_depth(BC_IN(LayerSegment) seg, real f) {
    BC_PRECISE real inv = (real(1) - f) / seg.z0 + f / seg.z1;
    return real(1) / inv;
}

// The ray parameter at image fraction f (perspective-correct).
BC_FN real bc_segment_parameter(BC_IN(LayerSegment) seg, real f) {
    BC_PRECISE real w1 = f / seg.z1;
    BC_PRECISE real w = (real(1) - f) / seg.z0 + w1;
    return seg.s0 + (seg.s1 - seg.s0) * (w1 / w);
}

// The image fraction in [f_a, f_b] where the segment's depth is `depth`
// (clamped); f_a when the depth does not change along the segment.
BC_FN real bc_segment_fraction_at(BC_IN(LayerSegment) seg, real depth, real f_a, real f_b) {
    BC_PRECISE real dinv = real(1) / seg.z1 - real(1) / seg.z0;
    if (dinv == real(0)) return f_a;
    BC_PRECISE real f = (real(1) / depth - real(1) / seg.z0) / dinv;
    return clamp(f, f_a, f_b);
}

// The state of a trace over one segment: the caller reads the depths of
// layers 0 .. layers - 1 at texel (x, y) and hands them to layer_trace_step,
// until done (at most `steps` calls; docs/secondary-rays.md has the loop in
// GLSL, include/blurcull/layer_trace.hpp runs it on the host).
struct LayerTrace {
    int step;        // index of the next step, 0 .. steps
    int steps;       // layer_step_count of the segment
    int layers;      // layers read per step, [1, BC_LAYERS_MAX]
    real thickness;  // slab thickness of a stored depth (scene units)
    real z_a;        // the ray's view depth where the next step starts
    int x;           // texel of the next step
    int y;
    bool done;
    LayerHit hit;    // the result once done
};

// Texel read by step k of n: the one under the middle of the step.
BC_FN void bc_layer_step_texel(BC_IN(LayerView) v, BC_IN(LayerSegment) seg, int k, int n, BC_OUT(int) x,
                               BC_OUT(int) y) {
    real f_m = (real(k) + real(0.5)) / real(max(n, 1));
    vec2 at = seg.p0 + f_m * (seg.p1 - seg.p0);
    real last = real(max(v.size, 1) - 1);
    x = int(clamp(floor(at.x), real(0), last));
    y = int(clamp(floor(at.y), real(0), last));
}

// A trace of `seg` that reads layer_count layers per step (clamped to [1,
// BC_LAYERS_MAX]); each stored depth D is a slab [D, D + thickness]
// (thickness >= 0, scene units). An empty segment is done at once: a miss
// with 0 steps.
BC_FN LayerTrace layer_trace_begin(BC_IN(LayerView) v, BC_IN(LayerSegment) seg, int layer_count, real thickness) {
    LayerTrace t;
    t.step = 0;
    t.steps = layer_step_count(v, seg);
    t.layers = min(max(layer_count, 1), BC_LAYERS_MAX);
    t.thickness = max(thickness, real(0));
    t.z_a = seg.z0;
    t.done = t.steps == 0;
    t.hit.hit = false;
    t.hit.layer = -1;
    t.hit.s = seg.s1;
    t.hit.depth = seg.z1;
    t.hit.image = seg.p1;
    t.hit.steps = 0;
    bc_layer_step_texel(v, seg, 0, t.steps, t.x, t.y);
    return t;
}

// One step, given depths[l] = depth of layer l at texel (t.x, t.y) for l <
// t.layers. The step hits a layer when the ray's depths over it overlap the
// slab of the stored depth; among the layers hit, the one whose hit comes
// first along the ray (ties: lowest layer), refined to where the ray's depth
// equals D inside the step (clamped to the step). A hit or the last step
// ends the trace; a NaN depth is no surface.
BC_FN LayerTrace layer_trace_step(BC_IN(LayerView) v, BC_IN(LayerSegment) seg, BC_IN(LayerTrace) t,
                                  real depths[BC_LAYERS_MAX]) {
    LayerTrace r = t;
    if (t.done) return r;
    int k = t.step;
    real f_a = real(k) / real(t.steps);
    real f_b = real(k + 1) / real(t.steps);
    real z_b = bc_segment_depth(seg, f_b);
    real z_lo = min(t.z_a, z_b);
    real z_hi = max(t.z_a, z_b);
    real best_f = real(2);
    for (int l = 0; l < t.layers; ++l) {
        real d = depths[l];
        if (!(z_hi >= d) || !(z_lo <= d + t.thickness)) continue;
        real f = bc_segment_fraction_at(seg, clamp(d, z_lo, z_hi), f_a, f_b);
        if (f < best_f) {
            best_f = f;
            r.hit.layer = l;
        }
    }
    r.step = k + 1;
    r.hit.steps = k + 1;
    r.z_a = z_b;
    if (r.hit.layer >= 0) {
        r.done = true;
        r.hit.hit = true;
        r.hit.s = bc_segment_parameter(seg, best_f);
        r.hit.depth = bc_segment_depth(seg, best_f);
        r.hit.image = seg.p0 + best_f * (seg.p1 - seg.p0);
        return r;
    }
    r.done = r.step >= t.steps;
    if (!r.done) bc_layer_step_texel(v, seg, r.step, t.steps, r.x, r.y);
    return r;
}
