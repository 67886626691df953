// Static path, one invocation per pixel: the pass's four samples of the
// pattern, each tested by covers() (for a static in-focus triangle, three edge
// functions), coverage written through gl_SampleMask; depth is the rasterizer's.
layout(std430, binding = 1) readonly buffer Infos { TriangleInfo infos[]; };
layout(std430, binding = 2) buffer Counters { uint tested; uint hit; };

flat in int g_index;
layout(location = 0) out uint out_id;

// The pixel (row 0 at the top) of this fragment: GL's window rows grow upwards.
uvec2 fragment_pixel() {
    return uvec2(uint(gl_FragCoord.x), uint(image_size.y) - 1u - uint(gl_FragCoord.y));
}

void main() {
    uvec2 pixel = fragment_pixel();
    MovingTriangle tri = triangles[g_index];
    ScreenBound b;
    b.empty = false;
    b.lo = infos[g_index].box.xy;
    b.hi = infos[g_index].box.zw;
    b.hull_count = 0;
    PixelSampleSetup setup = pixel_sample_setup(pixel.x, pixel.y, spp, seed);
    int mask = 0;
    uint tests = 0u, hits = 0u;
    for (int k = 0; k < 4; ++k) {
        uint j = pass_base + uint(k);
        if (j >= spp) break;
        PixelSample s = pixel_sample_from(setup, j);
        vec2 ndc = sample_ndc(pixel.x, pixel.y, s.offset);
        if (!screen_contains(b, ndc)) continue;
        tests += 1u;
        float depth;
        if (covers(tri, ndc, s.lens, s.time, near_plane, depth)) {
            mask |= 1 << k;
            hits += 1u;
        }
    }
    if (tests > 0u) atomicAdd(tested, tests);
    if (mask == 0) discard;
    atomicAdd(hit, hits);
    gl_SampleMask[0] = mask;
    out_id = uint(g_index);
}
