// Shared C++/GLSL text (see dialect.hpp): motion segments. A motion that is
// not linear over the shutter (a rotation) is split into K linear pieces; a
// segment is a MovingTriangle whose "open" and "close" are its vertices at
// the window's ends, so every other kernel function works on it unchanged in
// the segment's LOCAL time t' in [0, 1]. These functions map between the
// sample's shutter time and that local time (docs/kernel.md, "Motion
// segments"). Needs coc_motion_body.inl (bc_err).

// The shutter window [k / K, (k + 1) / K] of segment k of K >= 1 equal
// segments; the last one ends at exactly 1.
BC_FN vec2 segment_window(int segment, int segments) {
    return vec2(real(segment) / real(segments), real(segment + 1) / real(segments));
}

// Whether shutter time t belongs to the window: half open, [lo, hi), so a
// time on a boundary belongs to one segment only, except that a window that
// ends at the shutter's close (hi >= 1) holds its end too.
BC_FN bool segment_holds(vec2 window, real t) {
    return t >= window.x && (t < window.y || (window.y >= real(1) && t <= window.y));
}

// The segment's local time of shutter time t: (t - lo) / (hi - lo). In
// [0, 1] for every t the window holds (rounding is monotone); 0 for an empty
// window. The one place a sample's time enters a segment: the bounds and
// covers() are then evaluated at this value.
BC_FN real segment_local_time(vec2 window, real t) {
    real span = window.y - window.x;
    if (!(span > real(0))) return real(0);
    return (t - window.x) / span;
}

// The shutter times of the window whose local time (segment_local_time) lies
// in local_range = [lo, hi] (e.g. sample_time_range of a segment's bounds),
// widened by the rounding of both maps and clipped to the window: every t
// that the window holds with segment_local_time(window, t) in [lo, hi] lies
// inside. (1, 0) (lo > hi) when local_range is empty.
BC_FN vec2 segment_shutter_range(vec2 window, vec2 local_range) {
    if (local_range.x > local_range.y) return vec2(real(1), real(0));
    real span = window.y - window.x;
    real lo = window.x + local_range.x * span;
    real hi = window.x + local_range.y * span;
    // Both maps round a few times at magnitudes up to |lo| + |hi| + the window's.
    real pad = bc_err(real(1) + abs(window.x) + abs(window.y) + abs(lo) + abs(hi));
    return vec2(max(lo - pad, window.x), min(hi + pad, window.y));
}
