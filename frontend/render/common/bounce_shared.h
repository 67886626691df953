// The host-side decisions of dof-secondary's image-space bounce, written once
// for C++ and GLSL (like layer_raster_shared.h): which pyramid level answers
// a footprint's interval, the depth interval a group of rays is clipped to,
// the union of the group's footprints, and which stored surface a hit
// belongs to. The CPU build (render/secondary/dof_secondary.cpp and
// layer_images.cpp) and the GPU-resident bounce
// (render/gl/shaders/render_secondary_*.comp) call these, so both clip,
// trace and pick the same surface (docs/secondary-rays.md, "What the gl
// backend runs"). The kernel's layer_segment and layer_footprint do the
// geometry; these only combine their results.
#ifndef BLURCULL_BOUNCE_SHARED_H
#define BLURCULL_BOUNCE_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cstdint>

namespace blurcull::frontend::bounce {
using glm::vec2;
using glm::vec4;
using glm::clamp;
using glm::floor;
using glm::max;
using glm::min;
using glm::sqrt;
#define BC_BOUNCE_FN inline
#define BC_BOUNCE_PRECISE
#else
#define BC_BOUNCE_FN
#define BC_BOUNCE_PRECISE precise
#endif

// Interval clipping rounds (Lee et al.: clip, re-read the pyramid, clip again).
#define BC_BOUNCE_CLIP_ROUNDS 3

// The segments' "no limit" depth and ray length: FLT_MAX.
#define BC_BOUNCE_HUGE_DEPTH 3.402823466e+38

// The union of no footprint in an image of `size` texels per side (x_min >
// x_max), to which bc_footprint_union adds.
BC_BOUNCE_FN vec4 bc_footprint_none(int size) { return vec4(float(size), float(size), -1.0f, -1.0f); }

// `box` grown by footprint `f` (kernel layer_footprint: x_min > x_max when
// the segment is empty, which adds nothing).
BC_BOUNCE_FN vec4 bc_footprint_union(vec4 box, vec4 f) {
    if (f.x > f.z) return box;
    return vec4(min(box.x, f.x), min(box.y, f.y), max(box.z, f.z), max(box.w, f.w));
}

// The level of a min/max pyramid of `levels` levels (texels at level 0,
// halved per level) whose cells under texel box [x0, x1] x [y0, y1] are at
// most 2 x 2: the coarsest needed, the last level at most.
BC_BOUNCE_FN int bc_pyramid_level(int x0, int y0, int x1, int y1, int levels) {
    int level = 0;
    while (level + 1 < levels && ((x1 >> level) - (x0 >> level) > 1 || (y1 >> level) - (y0 >> level) > 1)) ++level;
    return level;
}

// The view depths a group's segments are clipped to, from the pyramid's
// (min, max) over their footprints: up to the farthest surface plus its
// slab `thickness`; nothing (huge, 0) where the footprints hold no surface
// (min > max).
BC_BOUNCE_FN vec2 bc_bounce_clip(vec2 range, float thickness, float huge) {
    BC_BOUNCE_PRECISE float far_end = range.y + thickness;
    return range.x > range.y ? vec2(huge, 0.0f) : vec2(range.x, far_end);
}

// The texel of a hit, clamped into the image (a hit's image point lies in it
// up to rounding).
BC_BOUNCE_FN int bc_hit_texel(float image, int size) { return clamp(int(floor(image)), 0, size - 1); }

// Whether a stored depth `gap` away from the hit's depth (|stored - hit|)
// names the hit's surface rather than the best so far, `best` away: the
// nearest in depth of the 3 x 3 texels around the hit, the hit's own texel
// on ties (a hit is refined inside its step, so it may sit across a texel
// border from the depth it hit).
BC_BOUNCE_FN bool bc_hit_surface_closer(float gap, float best, bool own_texel) {
    return gap < best || (own_texel && gap <= best);
}

// The layers' normal cull of a cluster whose rays' least cosine to its
// view's forward axis is `cos_widest` (their cone's half angle): a triangle
// whose unit normal has n . forward above the returned sine faces away from
// every ray (the paper's normal cone); 2 (no cull) when the cone is wider
// than a hemisphere or `cull` is off.
BC_BOUNCE_FN float bc_normal_cone_threshold(float cos_widest, bool cull) {
    BC_BOUNCE_PRECISE float sine2 = 1.0f - cos_widest * cos_widest;
    return cull && cos_widest > 0.0f ? sqrt(max(0.0f, sine2)) : 2.0f;
}

#ifdef __cplusplus
}  // namespace blurcull::frontend::bounce

namespace blurcull::frontend {

// What a bounced ray found in its cluster's layers: the bounce's result,
// from the host (render/secondary) or the GPU (render/gl's
// GlLayerTracer::bounce).
struct LayerBounceHit {
    bool hit = false;
    std::uint32_t triangle = 0;  // the scene triangle of the surface hit
    int steps = 0;               // texels the trace visited
    bool traced = true;          // false: the ray was not queued (a batch's hits by ray index)
};

// What sorts a bounced ray into its cluster's groups and culls on the GPU
// (render/gl's GlClustering::group): the reflector triangle it starts on,
// and its pixel << 4 | lens part (pixels below 2^28).
struct RayGroupKey {
    std::uint32_t triangle = 0;
    std::uint32_t pixel_part = 0;
};

}  // namespace blurcull::frontend
#endif

#endif  // BLURCULL_BOUNCE_SHARED_H
