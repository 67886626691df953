// Compute pipeline, the raster pass: one work group per screen tile of
// BC_GL_TILE_SIZE^2 pixels, one invocation per pixel, which owns its
// samples (no atomics on depth). A dispatch handles CHUNK samples per pixel
// (chunk_base ...) against the entries slice_first ... slice_first +
// slice_entries - 1 of each tile's list; the host dispatches every (chunk,
// slice), and the winners so far carry over between slices in SampleIds and
// SampleKeys, and between triangle batches too (the host sets up, bins and
// rasterizes a scene in batches of at most GlOptions::triangle_batch
// triangles: triangles[], the infos, stratum boxes and lists hold the batch,
// indices local to it; a sample's id is the scene index, triangle_base plus
// the local one). (One slice holds the longest list on a hardware GPU; on
// llvmpipe, which ends any shader invocation's loops after 65535 iterations
// in all, a slice is one batch of 64 entries.) The slice is read in batches of one
// triangle per invocation: each invocation sets up one triangle's pixels in
// the tile (its pixel rectangle clipped to the tile) and its sample bounds
// over them (bc_sample_bounds, those pixels as the footprint, for the
// methods that bound lens and time; an empty bound drops the triangle for
// the tile) into shared memory; then every invocation tests its
// pixel's samples against the batch: bc_sample_test (lens/time bounds,
// screen bound and hull, then bc_covers), the alpha mask, and the depth rule
// bc_depth_key_wins (the larger near / w key, on equal keys the lower index:
// the per-sample result of drawing in index order with a GREATER depth test,
// whatever the list's order). The samples are the pattern's (pattern_sample,
// as render_samples.comp draws them). render_resolve.comp sums SampleIds.
layout(local_size_x = BC_GL_TILE_SIZE, local_size_y = BC_GL_TILE_SIZE) in;

layout(std430, binding = BC_GL_INFOS_BINDING) readonly buffer Infos { TriangleInfo infos[]; };
// The fragment stages' two words, and their carries (BC_COUNTER_ADD): 64-bit counts per frame.
layout(std430, binding = BC_GL_COUNTERS_BINDING) buffer Counters { uint tested; uint hit; uint tested_carry; uint hit_carry; };
layout(std430, binding = BC_GL_SAMPLE_IDS_BINDING) buffer SampleIds { uint sample_ids[]; };
layout(std430, binding = BC_GL_SAMPLE_KEYS_BINDING) buffer SampleKeys { float sample_keys[]; };
// render_compute_strata.comp: per triangle the screen box of each shutter slice.
layout(std430, binding = BC_GL_STRATUM_BOXES_BINDING) readonly buffer StratumBoxes { vec4 stratum_boxes[]; };
TILE_BUFFERS

uniform int sampler;        // BC_PATTERN_* (RenderSettings::sampler)
uniform int method;         // BC_CULL_*
uniform int tile_bounds;    // 1: the method bounds lens and time (bc_sample_bounds per tile)
uniform uint tiles_x;       // tiles per row
uniform uint chunk_base;    // this dispatch's samples: chunk_base ... chunk_base + CHUNK - 1
uniform uint slice_first;   // and list entries: slice_first ... slice_first + slice_entries - 1
uniform uint slice_entries;
uniform uint triangle_base; // the batch's first scene triangle
uniform int carry;          // 1: the samples hold earlier slices' or batches' winners (SampleIds, SampleKeys)
uniform int occlusion;      // 1: skip an entry (or its shutter slices) behind every sample the tile holds there

#define BATCH (BC_GL_TILE_SIZE * BC_GL_TILE_SIZE)
#define CHUNK 8
#define NO_TRIANGLE 0xffffffffu

// Per shutter slice (BC_GL_TIME_STRATA of them, as the stratum boxes), the
// smallest depth key the tile's samples of this chunk in that slice hold,
// as float bits (positive floats order as their bits; 0: a sample shows the
// background; +infinity: no sample in the slice), double-buffered by batch:
// the loaders of batch j read what the invocations left after batch j - 1
// (entry parity * BC_GL_TIME_STRATA + slice).
shared uint tile_min_key[2 * BC_GL_TIME_STRATA];
// Each batch entry's shutter slices whose samples it cannot win (bit s:
// slice s), by the occlusion test.
shared uint batch_hidden_slices[BATCH];
shared uint batch_triangle[BATCH];
// Each batch entry's pixels in the tile (empty: x0 > x1) and sample bounds.
shared CellBounds batch_bounds[BATCH];

// Per shutter slice, the smallest key this invocation's samples hold, into
// tile_min_key[base + slice] (a slice none of them is in is left alone).
void hold_keys(uint base, float best_key[CHUNK], int slices[CHUNK], uint samples_here) {
    const float nothing = uintBitsToFloat(0x7f800000u);
    for (int slice = 0; slice < BC_GL_TIME_STRATA; ++slice) {
        float held = nothing;
        for (uint k = 0u; k < samples_here; ++k) {
            if (slices[k] == slice) held = min(held, best_key[k]);
        }
        if (held < nothing) atomicMin(tile_min_key[base + uint(slice)], floatBitsToUint(held));
    }
}

void main() {
    uvec2 tile = gl_WorkGroupID.xy;
    uint t = tile.y * tiles_x + tile.x;
    uint count = tile_counts[t];
    // Uniform over the work group, before any barrier: a later slice or
    // batch past the list's end has nothing to add (the frame's first slice
    // always runs: it starts every sample at the background).
    if (carry != 0 && slice_first >= count) return;
    uint first = tile_ends[t] - count;  // the fill advanced each end by the count
    uint slice_end = min(count, slice_first + slice_entries);
    uvec2 pixel = tile * uint(BC_GL_TILE_SIZE) + gl_LocalInvocationID.xy;
    uint width = uint(image_size.x), height = uint(image_size.y);
    bool inside = pixel.x < width && pixel.y < height;
    ivec4 tile_rect = ivec4(ivec2(tile) * BC_GL_TILE_SIZE,
                            min(ivec2(tile) * BC_GL_TILE_SIZE + (BC_GL_TILE_SIZE - 1), ivec2(width, height) - 1));
    uint samples_here = min(uint(CHUNK), spp - chunk_base);
    uint slot = (min(pixel.y, height - 1u) * width + min(pixel.x, width - 1u)) * spp + chunk_base;
    vec4 ndc_lens[CHUNK];
    float times[CHUNK];
    int slices[CHUNK];  // each sample's shutter slice
    float best_key[CHUNK];
    uint best_id[CHUNK];
    SamplerSetup setup = bc_sampler_setup(sampler, min(pixel.x, width - 1u), min(pixel.y, height - 1u), spp, seed);
    for (uint k = 0u; k < uint(CHUNK); ++k) {
        ndc_lens[k] = vec4(0.0);
        times[k] = 0.0;
        best_key[k] = 0.0;
        best_id[k] = NO_TRIANGLE;
        slices[k] = 0;
        if (inside && k < samples_here) {
            pattern_sample(setup, pixel, chunk_base + k, ndc_lens[k], times[k]);
            slices[k] = min(int(times[k] * float(BC_GL_TIME_STRATA)), BC_GL_TIME_STRATA - 1);
            if (carry != 0) {
                best_key[k] = sample_keys[slot + k];
                best_id[k] = sample_ids[slot + k];
            }
        }
    }
    uint local = gl_LocalInvocationIndex;
    uint tested_here = 0u, hit_here = 0u, occluded_here = 0u;
    const uint no_key = 0x7f800000u;  // +infinity: nothing held yet
    if (local < uint(2 * BC_GL_TIME_STRATA)) tile_min_key[local] = no_key;
    memoryBarrierShared();
    barrier();
    if (inside && occlusion != 0) hold_keys(uint(BC_GL_TIME_STRATA), best_key, slices, samples_here);
    for (uint b = slice_first; b < slice_end; b += uint(BATCH)) {
        uint parity = ((b - slice_first) / uint(BATCH)) & 1u;
        memoryBarrierShared();
        barrier();  // the previous batch is no longer read, its keys are in tile_min_key[1 - parity]
        if (local < uint(BC_GL_TIME_STRATA)) tile_min_key[parity * uint(BC_GL_TIME_STRATA) + local] = no_key;
        if (b + local < slice_end) {
            uint i = tile_list[first + b + local];
            batch_triangle[local] = i;
            CellBounds c;
            SampleBounds sb = bc_no_sample_bounds();
            // The triangle's pixels in the tile (its rect holds every pixel
            // with a sample in its screen bound), the footprint of its bounds.
            ivec4 r = infos[i].rect;
            c.rect = ivec4(max(r.xy, tile_rect.xy), min(r.zw, tile_rect.zw));
            if (tile_bounds != 0 && infos[i].needs != 0 && c.rect.x <= c.rect.z && c.rect.y <= c.rect.w) {
                vec4 footprint = bc_pixel_rect_ndc(c.rect, image_size);
                sb = bc_sample_bounds(triangles[i], footprint.xy, footprint.zw, method);
                if (sb.empty) c.rect = ivec4(0, 0, -1, -1);
            }
            // Hierarchical occlusion, per tile and shutter slice: the
            // kernel's depth floor over the slice (no covered sample of the
            // triangle in it is nearer) against the farthest sample the tile
            // holds in that slice; strictly behind it, the triangle wins no
            // sample of the slice (bc_depth_key is monotone in the depth).
            // Hidden in every slice, it is dropped for the tile.
            uint hidden = 0u;
            if (occlusion != 0 && c.rect.x <= c.rect.z && c.rect.y <= c.rect.w) {
                // Every sample has |NDC| <= 1; 2 leaves room for their rounding (as the cpu's frame_setup).
                float scale = bc_depth_floor_scale(triangles[i], vec2(0.0, 1.0), vec2(-1.0, 1.0), vec2(-1.0, 1.0), 2.0);
                for (int slice = 0; slice < BC_GL_TIME_STRATA; ++slice) {
                    float held = uintBitsToFloat(tile_min_key[(1u - parity) * uint(BC_GL_TIME_STRATA) + uint(slice)]);
                    vec2 time = vec2(float(slice), float(slice + 1)) / float(BC_GL_TIME_STRATA);
                    float floor_depth = bc_depth_floor(triangles[i], time, scale);
                    if (floor_depth > 0.0 && bc_depth_key(near_plane, floor_depth) < held) hidden |= 1u << slice;
                }
                if (hidden == (1u << BC_GL_TIME_STRATA) - 1u) {
                    c.rect = ivec4(0, 0, -1, -1);
                    ++occluded_here;
                }
            }
            batch_hidden_slices[local] = hidden;
            c.lens = vec4(sb.u_range, sb.v_range);
            c.time_lines_u_a = sb.u_time_a;
            c.time_lines_u_b = sb.u_time_b;
            c.time_lines_v_a = sb.v_time_a;
            c.time_lines_v_b = sb.v_time_b;
            batch_bounds[local] = c;
        }
        memoryBarrierShared();
        barrier();
        if (!inside) continue;
        uint batch_count = min(uint(BATCH), slice_end - b);
        for (uint e = 0u; e < batch_count; ++e) {
            CellBounds c = batch_bounds[e];
            if (int(pixel.x) < c.rect.x || int(pixel.x) > c.rect.z || int(pixel.y) < c.rect.y ||
                int(pixel.y) > c.rect.w) {
                continue;
            }
            int i = int(batch_triangle[e]);
            uint scene_index = triangle_base + uint(i);
            uint hidden = batch_hidden_slices[e];
            SampleBounds sb = carried_sample_bounds(c.lens, c.time_lines_u_a, c.time_lines_u_b, c.time_lines_v_a,
                                                    c.time_lines_v_b);
            ScreenBound screen;
            screen.empty = false;
            screen.lo = infos[i].box.xy;
            screen.hi = infos[i].box.zw;
            screen.hull_count = infos[i].hull_count;
            for (int h = 0; h < screen.hull_count; ++h) screen.hull_edge[h] = infos[i].hull[h].xyz;
            for (uint k = 0u; k < samples_here; ++k) {
                // The sample's shutter slice: outside its screen box the
                // triangle covers it at no lens position (culled, not tested).
                int slice = slices[k];
                if (((hidden >> uint(slice)) & 1u) != 0u) continue;  // every sample of the slice holds a nearer one
                vec4 box = stratum_boxes[i * BC_GL_TIME_STRATA + slice];
                if (!(ndc_lens[k].x >= box.x && ndc_lens[k].y >= box.y && ndc_lens[k].x <= box.z &&
                      ndc_lens[k].y <= box.w)) {
                    continue;
                }
                float depth;
                int verdict = bc_sample_test(triangles[i], screen, true, sb, ndc_lens[k].xy, ndc_lens[k].zw, times[k],
                                             near_plane, depth);
                if (verdict != BC_SAMPLE_CULLED) ++tested_here;
                // alphaMode MASK after coverage, before the depth rule
                if (verdict == BC_SAMPLE_COVERED &&
                    mask_keeps_batch(int(scene_index), i, ndc_lens[k].xy, ndc_lens[k].zw, times[k])) {
                    ++hit_here;
                    float key = bc_depth_key(near_plane, depth);
                    // key > 0: as the depth test against the cleared 0
                    if (key > 0.0 &&
                        (best_id[k] == NO_TRIANGLE || bc_depth_key_wins(key, scene_index, best_key[k], best_id[k]))) {
                        best_key[k] = key;
                        best_id[k] = scene_index;
                    }
                }
            }
        }
        if (occlusion != 0) hold_keys(parity * uint(BC_GL_TIME_STRATA), best_key, slices, samples_here);
    }
    if (inside) {
        for (uint k = 0u; k < samples_here; ++k) {
            sample_ids[slot + k] = best_id[k];
            sample_keys[slot + k] = best_key[k];
        }
    }
    if (tested_here > 0u) BC_COUNTER_ADD(tested, tested_carry, tested_here)
    if (hit_here > 0u) BC_COUNTER_ADD(hit, hit_carry, hit_here)
    if (occluded_here > 0u) atomicAdd(bin_state.occluded, occluded_here);
}
