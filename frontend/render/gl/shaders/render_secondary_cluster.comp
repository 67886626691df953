// dof-secondary's clustering on the GPU (gl_clustering.cpp): the steps of
// cluster_reflector_pixels (include/blurcull/secondary_clusters.hpp), one
// dispatch each, on the kernel's shared text: each ray's dodecahedron
// facet, the facets' k, the k-means start (the least kmeans_start_key, then
// the farthest rays), Lloyd's assignments and updates, the final sums, then
// both view fits of every cluster (fit_cluster_views). Every choice is a
// minimum or maximum, every sum exact (64-bit fixed point, added with
// atomics on its two words) and every view field a max, min or or, so the
// order the invocations run in changes nothing: the host's clusters and
// views, bit for bit, where the GPU rounds as the host does. The per-ray steps run a run of BC_CLUSTER_RUN
// consecutive rays an invocation, the per-facet steps one work group.
layout(local_size_x = BC_TRACE_GROUP) in;
layout(std430, binding = BC_GL_CLUSTER_POINTS_BINDING) readonly buffer Points { vec4 point[]; };  // position, direction
layout(std430, binding = BC_GL_CLUSTER_LABELS_BINDING) buffer Labels { uint label[]; };          // facet * 4 + local
layout(std430, binding = BC_GL_CLUSTER_STATE_BINDING) coherent buffer State { ClusterState state; };
layout(std430, binding = BC_GL_CLUSTER_VIEWS_BINDING) coherent buffer Views { ClusterViewFit fits[]; };
uniform int step;
uniform uint rays;
uniform uint wanted_clusters;
uniform uint max_per_facet;
uniform uint seed;
uniform float tan_half_fov;  // the views' (view steps)
uniform float min_near;

vec3 position_of(uint r) { return point[2u * r].xyz; }
vec3 direction_of(uint r) { return point[2u * r + 1u].xyz; }

vec3 centre(int slot) {
    return vec3(state.centres[3 * slot], state.centres[3 * slot + 1], state.centres[3 * slot + 2]);
}

void set_centre(int slot, vec3 c) {
    state.centres[3 * slot] = c.x;
    state.centres[3 * slot + 1] = c.y;
    state.centres[3 * slot + 2] = c.z;
}

// The slot's sums as the kernel's ClusterSums.
ClusterSums slot_sums(int slot) {
    ClusterSums s = bc_cluster_sums_empty(state.position_scale);
    int at = 6 * slot;
    s.position_hi = ivec3(state.sum_hi[at], state.sum_hi[at + 1], state.sum_hi[at + 2]);
    s.position_lo = uvec3(state.sum_lo[at], state.sum_lo[at + 1], state.sum_lo[at + 2]);
    s.direction_hi = ivec3(state.sum_hi[at + 3], state.sum_hi[at + 4], state.sum_hi[at + 5]);
    s.direction_lo = uvec3(state.sum_lo[at + 3], state.sum_lo[at + 4], state.sum_lo[at + 5]);
    s.count = state.sum_count[slot];
    s.unfit = state.sum_unfit[slot];
    return s;
}

// Adds the 64-bit value (hi, lo) to the sum at `word`: the low word's
// atomic add returns what was there, from which the carry is exact
// whatever ran before or after.
void add_fixed(int word, int hi, uint lo) {
    uint before = atomicAdd(state.sum_lo[word], lo);
    int high = hi + ((before + lo) < before ? 1 : 0);
    if (high != 0) atomicAdd(state.sum_hi[word], high);
}

// Sums taken in an invocation's registers (the kernel's exact
// cluster_sums_add) into the slot's: positions, count, unfit, and with
// `with_directions` the directions.
void flush_sums(int slot, ClusterSums s, bool with_directions) {
    if (slot < 0 || s.count + s.unfit == 0u) return;
    int at = 6 * slot;
    if (s.count > 0u) {
        add_fixed(at, s.position_hi.x, s.position_lo.x);
        add_fixed(at + 1, s.position_hi.y, s.position_lo.y);
        add_fixed(at + 2, s.position_hi.z, s.position_lo.z);
        if (with_directions) {
            add_fixed(at + 3, s.direction_hi.x, s.direction_lo.x);
            add_fixed(at + 4, s.direction_hi.y, s.direction_lo.y);
            add_fixed(at + 5, s.direction_hi.z, s.direction_lo.z);
        }
        atomicAdd(state.sum_count[slot], s.count);
    }
    if (s.unfit > 0u) atomicAdd(state.sum_unfit[slot], s.unfit);
}

// The squared distance from ray r to the nearest of its facet's centres so far.
float far_distance(uint r, int facet) {
    vec3 p = position_of(r);
    int base = facet * BC_CLUSTERS_PER_FACET_MAX;
    float d = bc_distance2(p, centre(base));
    for (int c = 1; c < state.facet_chosen[facet]; ++c) d = min(d, bc_distance2(p, centre(base + c)));
    return d;
}

void clear_facet_sums(int facet) {
    for (int slot = facet * BC_CLUSTERS_PER_FACET_MAX; slot < (facet + 1) * BC_CLUSTERS_PER_FACET_MAX; ++slot) {
        for (int w = 6 * slot; w < 6 * slot + 6; ++w) {
            state.sum_hi[w] = 0;
            state.sum_lo[w] = 0u;
        }
        state.sum_count[slot] = 0u;
        state.sum_unfit[slot] = 0u;
    }
}

vec3 load3(float v[3]) { return vec3(v[0], v[1], v[2]); }

// Fit i as virtual_view_begin left it.
VirtualViewFit begun_fit(int i) {
    VirtualViewFit f;
    f.origin = load3(fits[i].origin);
    f.forward = load3(fits[i].forward);
    f.right = load3(fits[i].right);
    f.up = load3(fits[i].up);
    f.tan_half_fov = fits[i].tan_half_fov;
    f.min_near = fits[i].min_near;
    f.backoff = 0.0;
    f.depth_min = bc_huge();
    f.magnitude = 0.0;
    f.flags = fits[i].begin_flags;
    return f;
}

void begin_fit(int i, VirtualViewFit f) {
    for (int a = 0; a < 3; ++a) {
        fits[i].origin[a] = f.origin[a];
        fits[i].forward[a] = f.forward[a];
        fits[i].right[a] = f.right[a];
        fits[i].up[a] = f.up[a];
    }
    fits[i].tan_half_fov = f.tan_half_fov;
    fits[i].min_near = f.min_near;
    fits[i].begin_flags = f.flags;
    fits[i].backoff_bits = floatBitsToUint(f.backoff);
    fits[i].depth_min_key = bc_float_order(f.depth_min);
    fits[i].magnitude_bits = floatBitsToUint(f.magnitude);
    fits[i].add_flags = 0;
}

// The per-slot view steps (one invocation per slot).
void slot_view_step(int slot) {
    ClusterSums sums = slot_sums(slot);
    if (sums.count + sums.unfit == 0u) return;
    int along_mean = 2 * slot, along_normal = 2 * slot + 1;
    if (step == BC_CLUSTER_STEP_VIEW_BEGIN) {
        begin_fit(along_mean, bc_virtual_view_begin(sums, tan_half_fov, min_near));
        begin_fit(along_normal, bc_virtual_view_begin_along(sums, bc_dodecahedron_normal(slot / BC_CLUSTERS_PER_FACET_MAX),
                                                            tan_half_fov, min_near));
        return;
    }
    for (int i = along_mean; i <= along_normal; ++i) {
        VirtualViewFit f = begun_fit(i);
        f.backoff = uintBitsToFloat(fits[i].backoff_bits);
        f.depth_min = bc_float_of_order(fits[i].depth_min_key);
        f.magnitude = uintBitsToFloat(fits[i].magnitude_bits);
        f.flags |= fits[i].add_flags;
        VirtualView v = bc_virtual_view_finish(f);
        for (int a = 0; a < 3; ++a) fits[i].eye[a] = v.eye[a];
        fits[i].near = v.near;
        fits[i].backoff = v.backoff;
        fits[i].flags = v.flags;
    }
}

// A run's fold of virtual_view_add into fit i: the fit's maxima, minimum
// and flags (each ray's add from the begun fit: its t, z, magnitude and
// flags, as the host's fold takes them).
void flush_view(int i, VirtualViewFit g) {
    if (i < 0) return;
    if (g.backoff > 0.0 && floatBitsToUint(g.backoff) > fits[i].backoff_bits)
        atomicMax(fits[i].backoff_bits, floatBitsToUint(g.backoff));
    uint key = bc_float_order(g.depth_min);
    if (key < fits[i].depth_min_key) atomicMin(fits[i].depth_min_key, key);
    if (floatBitsToUint(g.magnitude) > fits[i].magnitude_bits)
        atomicMax(fits[i].magnitude_bits, floatBitsToUint(g.magnitude));
    int added = g.flags & ~fits[i].begin_flags;
    if ((added & ~fits[i].add_flags) != 0) atomicOr(fits[i].add_flags, added);
}

void view_run(uint first) {
    int slot = -1;
    VirtualViewFit runs[2];
    for (uint r = first; r < min(first + uint(BC_CLUSTER_RUN), rays); ++r) {
        int f = int(label[r] >> 2u);
        if (state.facet_k[f] == 0) continue;
        int ray_slot = f * BC_CLUSTERS_PER_FACET_MAX + int(label[r] & 3u);
        if (ray_slot != slot) {
            if (slot >= 0) {
                flush_view(2 * slot, runs[0]);
                flush_view(2 * slot + 1, runs[1]);
            }
            slot = ray_slot;
            runs[0] = begun_fit(2 * slot);
            runs[1] = begun_fit(2 * slot + 1);
        }
        runs[0] = bc_virtual_view_add(runs[0], position_of(r), direction_of(r));
        runs[1] = bc_virtual_view_add(runs[1], position_of(r), direction_of(r));
    }
    if (slot >= 0) {
        flush_view(2 * slot, runs[0]);
        flush_view(2 * slot + 1, runs[1]);
    }
}

// The per-facet steps.
void facet_step(int f) {
    int base = f * BC_CLUSTERS_PER_FACET_MAX;
    if (step == BC_CLUSTER_STEP_SETUP) {
        if (f == 0) state.position_scale = bc_cluster_position_scale(uintBitsToFloat(state.largest_bits));
        uint target = bc_cluster_target_size(rays, wanted_clusters);
        state.facet_k[f] = int(bc_clusters_for_facet(state.facet_count[f], target, max_per_facet));
        state.facet_chosen[f] = 0;
        state.facet_flags[f] = 0u;
        state.facet_iterations[f] = 0;
        state.pick_key[f] = 0xffffffffu;
        state.pick_ray[f] = 0xffffffffu;
        clear_facet_sums(f);
    } else if (step == BC_CLUSTER_STEP_PICK) {
        int chosen = state.facet_chosen[f];
        if (chosen < state.facet_k[f]) {
            if (chosen > 0 && state.pick_key[f] == 0u) {
                state.facet_k[f] = chosen;  // every ray on a centre: fewer clusters
            } else {
                set_centre(base + chosen, position_of(state.pick_ray[f]));
                state.facet_chosen[f] = chosen + 1;
            }
        }
        state.pick_key[f] = 0u;  // the farthest picks take the greatest distance
        state.pick_ray[f] = 0xffffffffu;
    } else if (step == BC_CLUSTER_STEP_UPDATE) {
        if (state.facet_k[f] == 0 || (state.facet_flags[f] & BC_CLUSTER_SETTLED) != 0u) return;
        state.facet_iterations[f] += 1;
        if ((state.facet_flags[f] & BC_CLUSTER_CHANGED) == 0u) {
            state.facet_flags[f] = BC_CLUSTER_SETTLED;
        } else {
            // An emptied cluster keeps its centre (it stays empty and is dropped).
            for (int c = 0; c < state.facet_k[f]; ++c)
                if (state.sum_count[base + c] > 0u) set_centre(base + c, bc_cluster_mean_position(slot_sums(base + c)));
            state.facet_flags[f] = 0u;
        }
        clear_facet_sums(f);
    }
}

// Lloyd's assignment (`assign`) or the final sums over the invocation's run
// of BC_CLUSTER_RUN consecutive rays: neighbouring rays mostly share a
// cluster, so each run's sums go to the slots in a few atomics, not one per
// ray and word.
void sum_run(uint first, bool assign) {
    int slot = -1;
    ClusterSums run = bc_cluster_sums_empty(state.position_scale);
    for (uint r = first; r < min(first + uint(BC_CLUSTER_RUN), rays); ++r) {
        int f = int(label[r] >> 2u);
        if (state.facet_k[f] == 0) continue;
        uint c = label[r] & 3u;
        if (assign) {
            if ((state.facet_flags[f] & BC_CLUSTER_SETTLED) != 0u) continue;
            int base = f * BC_CLUSTERS_PER_FACET_MAX;
            vec3 centres[BC_CLUSTERS_PER_FACET_MAX] =
                vec3[BC_CLUSTERS_PER_FACET_MAX](centre(base), centre(base + 1), centre(base + 2));
            uint nearest = uint(bc_kmeans_nearest(position_of(r), centres, state.facet_k[f]));
            if (nearest != c) atomicOr(state.facet_flags[f], BC_CLUSTER_CHANGED);
            label[r] = uint(f) * 4u + nearest;
            c = nearest;
        }
        int ray_slot = f * BC_CLUSTERS_PER_FACET_MAX + int(c);
        if (ray_slot != slot) {
            flush_sums(slot, run, !assign);
            run = bc_cluster_sums_empty(state.position_scale);
            slot = ray_slot;
        }
        run = bc_cluster_sums_add(run, position_of(r), direction_of(r));
    }
    flush_sums(slot, run, !assign);
}

// The per-ray steps but the sums, for ray r. An atomic minimum or maximum
// is skipped when the value cannot win (most rays, once one has stored a
// near-final value): fewer atomics on the 12 facets' words.
void ray_step(uint r) {
    if (step == BC_CLUSTER_STEP_CLASSIFY) {
        int f = bc_dodecahedron_facet(direction_of(r));
        label[r] = uint(f) * 4u + BC_CLUSTER_NO_LOCAL;
        atomicAdd(state.facet_count[f], 1u);
        vec3 p = abs(position_of(r));
        float largest = 0.0;
        for (int a = 0; a < 3; ++a)
            if (bc_finite(p[a])) largest = max(largest, p[a]);
        if (floatBitsToUint(largest) > state.largest_bits) atomicMax(state.largest_bits, floatBitsToUint(largest));
        return;
    }
    int f = int(label[r] >> 2u);
    if (state.facet_k[f] == 0) return;
    bool picking = state.facet_chosen[f] < state.facet_k[f];
    if (step == BC_CLUSTER_STEP_START_KEY) {
        uint key = bc_kmeans_start_key(seed, f, r);
        if (key < state.pick_key[f]) atomicMin(state.pick_key[f], key);
    } else if (step == BC_CLUSTER_STEP_START_RAY) {
        if (bc_kmeans_start_key(seed, f, r) == state.pick_key[f]) atomicMin(state.pick_ray[f], r);
    } else if (step == BC_CLUSTER_STEP_FAR_DISTANCE) {
        // Non-negative floats order as their bits; NaN never passes d > 0.
        if (!picking) return;
        float d = far_distance(r, f);
        if (d > 0.0 && floatBitsToUint(d) > state.pick_key[f]) atomicMax(state.pick_key[f], floatBitsToUint(d));
    } else if (step == BC_CLUSTER_STEP_FAR_RAY) {
        if (picking && state.pick_key[f] != 0u && floatBitsToUint(far_distance(r, f)) == state.pick_key[f])
            atomicMin(state.pick_ray[f], r);
    }
}

void main() {
    if (step == BC_CLUSTER_STEP_VIEW_BEGIN || step == BC_CLUSTER_STEP_VIEW_FINISH) {
        if (gl_LocalInvocationID.x < uint(BC_CLUSTER_SLOTS)) slot_view_step(int(gl_LocalInvocationID.x));
        return;
    }
    if (step == BC_CLUSTER_STEP_SETUP || step == BC_CLUSTER_STEP_PICK || step == BC_CLUSTER_STEP_UPDATE) {
        if (gl_LocalInvocationID.x < uint(BC_CLUSTER_FACETS)) facet_step(int(gl_LocalInvocationID.x));
        return;
    }
    uint first = dispatch_item() * uint(BC_CLUSTER_RUN);
    if (first >= rays) return;
    if (step == BC_CLUSTER_STEP_ASSIGN || step == BC_CLUSTER_STEP_FINAL_SUMS) {
        sum_run(first, step == BC_CLUSTER_STEP_ASSIGN);
        return;
    }
    if (step == BC_CLUSTER_STEP_VIEW_ADD) {
        view_run(first);
        return;
    }
    for (uint r = first; r < min(first + uint(BC_CLUSTER_RUN), rays); ++r) ray_step(r);
}
