// Appended to blurcull_kernel.glsl by the build and compiled and linked by
// glslangValidator: it calls every public function of the shared text, by
// its GLSL name bc_<name> (prelude.glsl), so no
// function can escape checking by being unused (a definition missing from the
// headers fails the link). Never run; the outputs only keep the calls alive.
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer CheckData {
    float values[];
};

// The secondary-ray functions (docs/secondary-rays.md).
float check_secondary_rays(vec3 d, vec3 p) {
    int face = bc_dodecahedron_facet(d);
    vec3 normal = bc_dodecahedron_normal(face);
    ClusterSums empty = bc_cluster_sums_empty(bc_cluster_position_scale(values[56]));
    ClusterSums sums = bc_cluster_sums_merge(bc_cluster_sums_add(empty, p, normal), empty);
    ivec3 fixed_p;
    ivec3 fixed_d;
    bool fits = bc_cluster_fixed_terms(p, d, sums.position_scale, fixed_p, fixed_d);
    vec3 mean = bc_cluster_mean_position(sums) + bc_cluster_direction_sum(sums) + vec3(fits ? fixed_p : fixed_d);
    uint k = bc_clusters_for_facet(sums.count, bc_cluster_target_size(100u, 24u), 3u) + bc_kmeans_start_key(5u, face, 7u);
    vec3 centres[BC_CLUSTERS_PER_FACET_MAX] = vec3[BC_CLUSTERS_PER_FACET_MAX](p, mean, d);
    int nearest = bc_kmeans_nearest(p, centres, int(k));
    vec3 right;
    vec3 up;
    bc_virtual_view_basis(normal, right, up);
    VirtualViewFit fit = bc_virtual_view_begin(sums, values[50], values[51]);
    VirtualViewFit along = bc_virtual_view_begin_along(sums, normal, values[50], values[51]);
    float backoff = bc_virtual_view_point_backoff(fit, p) + bc_virtual_view_point_backoff(along, d);
    bool inside = bc_virtual_view_direction_inside(normal, right, up, values[50], d);
    VirtualView view = bc_virtual_view_finish(bc_virtual_view_add(fit, p, normal));
    LayerView layer = bc_layer_view_from(view, values[52], 16);
    vec3 projected = bc_layer_project(layer, p + d);
    LayerSegment seg = bc_layer_segment(layer, p, d, values[53], vec2(values[54], values[55]));
    vec4 box = bc_layer_footprint(layer, seg);
    int steps = bc_layer_step_count(layer, seg);
    LayerTrace trace = bc_layer_trace_begin(layer, seg, 2, values[56]);
    for (int k = 0; k < trace.steps; ++k) {
        if (trace.done) break;
        float depths[BC_LAYERS_MAX];
        for (int l = 0; l < BC_LAYERS_MAX; ++l) depths[l] = values[64 + l * 4 + (trace.y & 1) * 2 + (trace.x & 1)];
        trace = bc_layer_trace_step(layer, seg, trace, depths);
    }
    LayerHit hit = trace.hit;
    return float(face) + mean.x + float(nearest) + up.x + backoff + float(inside) + view.near + projected.z + box.x +
           float(steps) + hit.s + float(hit.hit);
}

void main() {
    MovingTriangle tri;
    for (int j = 0; j < 6; ++j) {
        tri.p[j] = vec3(values[3 * j], values[3 * j + 1], values[3 * j + 2]);
        tri.c[j] = vec2(values[18 + 2 * j], values[19 + 2 * j]);
    }
    float near = values[30];
    int cull = int(values[31]);
    vec2 s = vec2(values[32], values[33]);
    vec2 uv = vec2(values[34], values[35]);
    float t = values[36];

    vec2 lens_ab = bc_thin_lens_coc(values[37], values[38], values[39]);
    float coc = bc_coc_at(lens_ab, values[40]) + bc_coc_controlled(lens_ab, values[40], values[41], values[42]);
    vec3 vertex = bc_vertex_at(tri, 1, t, uv);
    bool finite = bc_triangle_is_finite(tri);
    int needs = bc_classify(tri);
    float depth;
    bool covered = bc_covers(tri, s, uv, t, near, depth);
    vec3 barycentric;
    covered = bc_covers_hit(tri, s, uv, t, near, depth, barycentric) || covered;
    ScreenBound screen = bc_screen_bound(tri, near, cull);
    bool on_screen = bc_screen_contains(screen, s);
    int footprint_state = bc_screen_footprint(screen, s - vec2(0.01), s + vec2(0.01));
    vec4 stratum = bc_stratum_screen_box(tri, near, screen, vec2(0.25, 0.5), vec2(-1.0, 0.0), vec2(0.0, 1.0));
    float floor_scale = bc_depth_floor_scale(tri, vec2(0.0, 1.0), vec2(-1.0, 1.0), vec2(-1.0, 1.0), 1.0);
    float floored = bc_depth_floor(tri, vec2(0.25, 0.5), floor_scale);
    SampleBounds none = bc_no_sample_bounds();
    SampleBounds bounds = bc_sample_bounds(tri, s - vec2(0.01), s + vec2(0.01), cull);
    SampleBounds edge_bounds = bc_sample_bounds(tri, s - vec2(0.01), s + vec2(0.01), BC_CULL_EDGES);
    SampleBounds in_tile = bc_sample_bounds_in_tile(tri, s - vec2(0.005), s + vec2(0.005), cull, edge_bounds);
    SampleAxisBounds axis_x = bc_sample_axis_bounds(tri, 0, s.x - 0.01, s.x + 0.01, cull);
    SampleAxisBounds axis_y = bc_sample_axis_bounds(tri, 1, s.y - 0.01, s.y + 0.01, cull);
    SampleBounds combined = bc_combine_axis_bounds(axis_x, axis_y);
    int traits = bc_cull_traits(cull);
    SampleBounds without_planes = bc_sample_bounds_without_planes(tri, s - vec2(0.01), s + vec2(0.01), cull);
    SampleBounds with_planes = bc_add_sample_planes(tri, s - vec2(0.01), s + vec2(0.01), cull, without_planes);
    SampleBounds tile_planes = bc_with_tile_planes(s - vec2(0.005), s + vec2(0.005), cull, without_planes, edge_bounds);
    bool piece_culls = bc_sample_bounds_apply(tri) && bc_plane_pieces(edge_bounds) > 0 &&
                       bc_plane_piece_culls_box(edge_bounds, 0, s - vec2(0.01), s + vec2(0.01));
    float piece_start = bc_plane_piece_time(edge_bounds, 0).x;
    bool passes = bc_sample_passes(bounds, uv, t) || bc_sample_passes(none, uv, t) || bc_sample_passes(edge_bounds, uv, t) ||
                  bc_sample_passes_at(edge_bounds, s, uv, t) || bc_sample_passes_at(in_tile, s, uv, t) ||
                  bc_sample_passes(combined, uv, t) || bc_sample_passes(with_planes, uv, t) ||
                  bc_sample_passes_at(tile_planes, s, uv, t) || piece_culls || (traits & BC_CULL_BUILDS_HULL) != 0 ||
                  piece_start > 0.5;
    vec2 time_range = bc_sample_time_range(bounds);
    uint px = uint(values[43]);
    uint py = uint(values[44]);
    int pattern = int(values[45]);
    PixelSample sample_at = bc_pixel_sample(px, py, 3u, 16u, 7u);
    PixelSampleSetup setup = bc_pixel_sample_setup(px, py, 16u, 7u);
    PixelSample from_setup = bc_pixel_sample_from(setup, 3u);
    PixelSample patterned = bc_pattern_sample(pattern, px, py, 3u, 16u, 7u);
    PixelSample tiled = bc_pattern_sample_tiled(pattern, px, py, 3u, 16u, 7u, 2u);
    SamplerSetup pattern_setup = bc_sampler_setup(pattern, px, py, 16u, 7u);
    PixelSample sampled = bc_sampler_sample(pattern_setup, 3u);
    PixelSample others[4] = PixelSample[4](bc_pattern_random(px, py, 1u, 7u), bc_pattern_jittered(px, py, 1u, 16u, 7u),
                                           bc_pattern_sobol(px, py, 1u, 4u, 7u), bc_interval_sample(px, py, 1u, 4u, 7u));
    vec3 tuple = bc_interleaved_tuple(px);
    uint tile = bc_interleaved_corner_colour(px, py, 7u) + bc_interleaved_prototype(px, py, 7u);
    vec2 jitter = bc_interleaved_jitter(px, py, 7u);
    PixelSample accum = bc_accum_sample(px, 7u);
    vec2 image_size = vec2(values[45], values[46]);
    vec2 raster = bc_ndc_to_raster(bc_raster_to_ndc(s, image_size), image_size);
    vec2 sample_pos = bc_pixel_sample_ndc(ivec2(px, py), uv, image_size);
    ivec4 rect = bc_box_cell_rect(s - vec2(0.01), s + vec2(0.01), image_size);
    vec4 rect_ndc = bc_pixel_rect_ndc(rect, image_size);
    ivec2 cell = bc_interleaved_cell(ivec2(px, py), int(values[47]), 6);
    vec2 interleaved = bc_interleaved_sample_ndc(cell, 2, jitter, image_size);
    float hit_depth;
    int test = bc_sample_test(tri, screen, on_screen, bounds, s, uv, t, near, hit_depth) +
               (bc_sample_culled(screen, on_screen, bounds, s, uv, t) ? 1 : 0);
    float key = bc_depth_key(near, hit_depth);
    bool wins = bc_depth_nearer(hit_depth, depth) || bc_depth_key_wins(key, px, depth, py);
    vec2 camera_ab = bc_camera_coc(values[37], values[38], values[39]);
    vec2 window = bc_segment_window(int(values[47]), 4);
    vec2 shutter_range = bc_segment_shutter_range(window, time_range);
    float local_time = bc_segment_holds(window, t) ? bc_segment_local_time(window, t) : 0.0;

    float secondary = check_secondary_rays(vec3(values[45], values[46], values[47]), vec3(values[48], values[49], values[57]));

    values[0] = coc + vertex.x + float(finite) + float(needs) + float(covered) + depth + barycentric.y + float(on_screen) + float(footprint_state) + stratum.x + floored +
                float(passes) + time_range.x + sample_at.offset.x + sample_at.lens.y + sample_at.time + patterned.time +
                tiled.time + sampled.time + from_setup.time + bc_pattern_padded_sobol(px, py, 1u, 4u, 7u).time + others[0].time + others[1].time + others[2].time + others[3].time + tuple.x +
                float(tile) + jitter.x + accum.time + accum.offset.x + accum.lens.y + bc_rotate_unit(jitter.x, jitter.y) +
                raster.x + sample_pos.y + float(rect.x) + rect_ndc.w + interleaved.x + float(test) + key + float(wins) +
                camera_ab.y + secondary + shutter_range.x + local_time;
}
