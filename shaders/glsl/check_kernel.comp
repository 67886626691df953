// Appended to blurcull_kernel.glsl by the build and compiled and linked by
// glslangValidator: it calls every public function of the shared text, so no
// function can escape checking by being unused (a definition missing from the
// headers fails the link). Never run; the outputs only keep the calls alive.
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer CheckData {
    float values[];
};

void main() {
    MovingTriangle tri;
    for (int j = 0; j < 6; ++j) {
        tri.p[j] = vec3(values[3 * j], values[3 * j + 1], values[3 * j + 2]);
        tri.c[j] = vec2(values[18 + 2 * j], values[19 + 2 * j]);
    }
    float near = values[30];
    int method = int(values[31]);
    vec2 s = vec2(values[32], values[33]);
    vec2 uv = vec2(values[34], values[35]);
    float t = values[36];

    vec2 lens_ab = thin_lens_coc(values[37], values[38], values[39]);
    float coc = coc_at(lens_ab, values[40]) + coc_controlled(lens_ab, values[40], values[41], values[42]);
    vec3 vertex = vertex_at(tri, 1, t, uv);
    bool finite = triangle_is_finite(tri);
    int needs = classify(tri);
    float depth;
    bool covered = covers(tri, s, uv, t, near, depth);
    ScreenBound screen = screen_bound(tri, near, method);
    bool on_screen = screen_contains(screen, s);
    int footprint_state = screen_footprint(screen, s - vec2(0.01), s + vec2(0.01));
    SampleBounds none = no_sample_bounds();
    SampleBounds bounds = sample_bounds(tri, s - vec2(0.01), s + vec2(0.01), method);
    SampleBounds edge_bounds = sample_bounds(tri, s - vec2(0.01), s + vec2(0.01), BC_CULL_EDGES);
    bool passes = sample_passes(bounds, uv, t) || sample_passes(none, uv, t) || sample_passes(edge_bounds, uv, t);
    vec2 time_range = sample_time_range(bounds);
    uint px = uint(values[43]);
    uint py = uint(values[44]);
    PixelSample sample_at = pixel_sample(px, py, 3u, 16u, 7u);
    PixelSampleSetup setup = pixel_sample_setup(px, py, 16u, 7u);
    PixelSample from_setup = pixel_sample_from(setup, 3u);
    PixelSample patterned = pattern_sample(method, px, py, 3u, 16u, 7u);
    PixelSample tiled = pattern_sample_tiled(method, px, py, 3u, 16u, 7u, 2u);
    PixelSample others[4] = PixelSample[4](pattern_random(px, py, 1u, 7u), pattern_jittered(px, py, 1u, 16u, 7u),
                                           pattern_sobol(px, py, 1u, 7u), interval_sample(px, py, 1u, 4u, 7u));
    vec3 tuple = interleaved_tuple(px);
    uint tile = interleaved_corner_colour(px, py, 7u) + interleaved_prototype(px, py, 7u);
    vec2 jitter = interleaved_jitter(px, py, 7u);
    PixelSample accum = accum_sample(px, 7u);

    values[0] = coc + vertex.x + float(finite) + float(needs) + float(covered) + depth + float(on_screen) + float(footprint_state) +
                float(passes) + time_range.x + sample_at.offset.x + sample_at.lens.y + sample_at.time + patterned.time +
                tiled.time + from_setup.time + others[0].time + others[1].time + others[2].time + others[3].time + tuple.x +
                float(tile) + jitter.x + accum.time + accum.offset.x + accum.lens.y + bc_rotate_unit(jitter.x, jitter.y);
}
