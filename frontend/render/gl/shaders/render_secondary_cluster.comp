// dof-secondary's clustering on the GPU (gl_clustering.cpp): the steps of
// cluster_reflector_pixels (include/blurcull/secondary_clusters.hpp), one
// dispatch each, on the kernel's shared text: each ray's dodecahedron
// facet, the facets' k, the k-means start (the least kmeans_start_key, then
// the farthest rays), Lloyd's assignments and updates, the final sums. Every
// choice is a minimum or maximum and every sum exact (64-bit fixed point,
// added with atomics on its two words), so the order the invocations run
// in changes nothing: the host's clusters, bit for bit, where the GPU
// rounds as the host does. The per-ray steps run a run of BC_CLUSTER_RUN
// consecutive rays an invocation, the per-facet steps one work group.
layout(local_size_x = BC_TRACE_GROUP) in;
layout(std430, binding = BC_GL_CLUSTER_POINTS_BINDING) readonly buffer Points { vec4 point[]; };  // position, direction
layout(std430, binding = BC_GL_CLUSTER_LABELS_BINDING) buffer Labels { uint label[]; };          // facet * 4 + local
layout(std430, binding = BC_GL_CLUSTER_STATE_BINDING) coherent buffer State { ClusterState state; };
uniform int step;
uniform uint rays;
uniform uint wanted_clusters;
uniform uint max_per_facet;
uniform uint seed;

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
    for (uint r = first; r < min(first + uint(BC_CLUSTER_RUN), rays); ++r) ray_step(r);
}
