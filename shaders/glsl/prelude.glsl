#version 450 core
// blurcull's GLSL prelude: maps the shared C++/GLSL dialect of
// include/blurcull/detail/dialect.hpp and kernel.hpp onto GLSL 4.50
// (docs/glsl.md). The build puts the shared *_body.inl text after it.

// The scalar of every formula: IEEE binary32, like the host's kernel<float>.
#define real float

// Function definitions and parameter passing (C++: static inline, const T&, T&, T&).
// Out and inout parameters are `precise`, so what a function writes into
// them is evaluated as written (docs/glsl.md, "The GPU arithmetic model").
#define BC_FN
#define BC_IN(T) in T
#define BC_OUT(T) precise out T
#define BC_INOUT(T) precise inout T
// Nothing: the build (cmake/EmbedGlsl.cmake) makes every declaration of the
// bodies `precise`, so no compound expression is reassociated or fused, not
// only the ones the bodies mark BC_PRECISE (which C++ ignores likewise).
#define BC_PRECISE
// The emitted bodies test `if (bc_cond = <condition>)` (EmbedGlsl.cmake), so
// that a condition's arithmetic, which reaches no variable of its own, is
// precise too. Written, never read.
precise bool bc_cond;
// The bodies' dot() and cross(), renamed by the emission: GLM's operation
// order (glm/detail/func_geometric.inl), each product and sum rounded as on
// the host, where GLSL's built-ins may fuse them.
float bc_dot(vec2 a, vec2 b) {
    precise float d = a.x * b.x + a.y * b.y;
    return d;
}
float bc_dot(vec3 a, vec3 b) {
    precise float d = (a.x * b.x + a.y * b.y) + a.z * b.z;
    return d;
}
vec3 bc_cross(vec3 a, vec3 b) {
    precise vec3 c = vec3(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
    return c;
}

// Public names (docs/glsl.md, "Names"): every public function of the shared
// text is bc_<name> in GLSL, while its C++ member of kernel<Real> keeps <name>
// (kerneld::covers). The bodies call and define the plain names; these macros
// rename them for GLSL, and the emitted library #undefs them again after the
// last body, so a shader that includes it sees only the bc_ names and may use
// the plain ones for itself. Functions already named bc_* are internal.
// shaders/check_glsl_emission.cmake checks that every public function has its
// line here.
// the per-pixel sample pattern (sampling_body.inl)
#define pixel_sample_setup bc_pixel_sample_setup
#define pixel_sample_from bc_pixel_sample_from
#define pixel_sample bc_pixel_sample
// circle of confusion, motion, classification (coc_motion_body.inl)
#define thin_lens_coc bc_thin_lens_coc
#define coc_at bc_coc_at
#define coc_controlled bc_coc_controlled
#define vertex_at bc_vertex_at
#define triangle_is_finite bc_triangle_is_finite
#define classify bc_classify
// the exact coverage test (oracle_body.inl)
#define covers bc_covers
#define covers_hit bc_covers_hit
// the screen bound (screen_bound_body.inl)
#define cull_traits bc_cull_traits
#define screen_bound bc_screen_bound
#define stratum_screen_box bc_stratum_screen_box
#define depth_floor_scale bc_depth_floor_scale
#define depth_floor bc_depth_floor
#define screen_footprint bc_screen_footprint
#define screen_contains bc_screen_contains
// the per-footprint sample bounds (sample_bounds_body.inl)
#define no_sample_bounds bc_no_sample_bounds
#define sample_bounds bc_sample_bounds
#define sample_axis_bounds bc_sample_axis_bounds
#define combine_axis_bounds bc_combine_axis_bounds
#define sample_time_range bc_sample_time_range
#define sample_passes bc_sample_passes
#define sample_passes_at bc_sample_passes_at
#define sample_bounds_in_tile bc_sample_bounds_in_tile
#define sample_bounds_apply bc_sample_bounds_apply
#define sample_bounds_without_planes bc_sample_bounds_without_planes
#define add_sample_planes bc_add_sample_planes
#define with_tile_planes bc_with_tile_planes
#define plane_pieces bc_plane_pieces
#define plane_piece_time bc_plane_piece_time
#define plane_piece_culls_box bc_plane_piece_culls_box
// the raster glue both backends share (raster_body.inl)
#define raster_to_ndc bc_raster_to_ndc
#define ndc_to_raster bc_ndc_to_raster
#define pixel_sample_ndc bc_pixel_sample_ndc
#define pixel_rect_ndc bc_pixel_rect_ndc
#define box_cell_rect bc_box_cell_rect
#define interleaved_cell bc_interleaved_cell
#define interleaved_sample_ndc bc_interleaved_sample_ndc
#define sample_culled bc_sample_culled
#define sample_test bc_sample_test
#define depth_nearer bc_depth_nearer
#define depth_key bc_depth_key
#define depth_key_wins bc_depth_key_wins
#define camera_coc bc_camera_coc
// motion segments (motion_segment_body.inl)
#define segment_window bc_segment_window
#define segment_holds bc_segment_holds
#define segment_local_time bc_segment_local_time
#define segment_shutter_range bc_segment_shutter_range
// the dodecahedron's facets (dodecahedron_body.inl)
#define dodecahedron_normal bc_dodecahedron_normal
#define dodecahedron_facet bc_dodecahedron_facet
// clustering reflector pixels (clusters_body.inl)
#define cluster_position_scale bc_cluster_position_scale
#define cluster_sums_empty bc_cluster_sums_empty
#define cluster_fixed_terms bc_cluster_fixed_terms
#define cluster_sums_add bc_cluster_sums_add
#define cluster_sums_merge bc_cluster_sums_merge
#define cluster_mean_position bc_cluster_mean_position
#define cluster_direction_sum bc_cluster_direction_sum
#define cluster_target_size bc_cluster_target_size
#define clusters_for_facet bc_clusters_for_facet
#define kmeans_nearest bc_kmeans_nearest
#define kmeans_start_key bc_kmeans_start_key
// the virtual viewpoint (virtual_view_body.inl)
#define virtual_view_basis bc_virtual_view_basis
#define virtual_view_begin_along bc_virtual_view_begin_along
#define virtual_view_begin bc_virtual_view_begin
#define virtual_view_point_backoff bc_virtual_view_point_backoff
#define virtual_view_direction_inside bc_virtual_view_direction_inside
#define virtual_view_add bc_virtual_view_add
#define virtual_view_finish bc_virtual_view_finish
// image-space tracing (layer_trace_body.inl)
#define layer_view_from bc_layer_view_from
#define layer_project bc_layer_project
#define layer_segment bc_layer_segment
#define layer_footprint bc_layer_footprint
#define layer_step_count bc_layer_step_count
#define layer_trace_begin bc_layer_trace_begin
#define layer_trace_step bc_layer_trace_step
// the sample patterns of patterns.hpp (patterns_body.inl)
#define pattern_random bc_pattern_random
#define pattern_jittered bc_pattern_jittered
#define interval_sample bc_interval_sample
#define pattern_sobol bc_pattern_sobol
#define pattern_padded_sobol bc_pattern_padded_sobol
#define pattern_sample bc_pattern_sample
#define pattern_sample_tiled bc_pattern_sample_tiled
#define sampler_setup bc_sampler_setup
#define sampler_sample bc_sampler_sample
#define interleaved_tuple bc_interleaved_tuple
#define interleaved_corner_colour bc_interleaved_corner_colour
#define interleaved_prototype bc_interleaved_prototype
#define interleaved_jitter bc_interleaved_jitter
#define accum_sample bc_accum_sample

// std::numeric_limits<float>::epsilon() and max(), exactly (0x34000000, 0x7f7fffff).
float bc_epsilon() { return uintBitsToFloat(0x34000000u); }
float bc_huge() { return uintBitsToFloat(0x7f7fffffu); }
// std::numeric_limits<float>::min(), the smallest normal value (0x00800000).
float bc_tiny() { return uintBitsToFloat(0x00800000u); }
