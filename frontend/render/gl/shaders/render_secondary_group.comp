// dof-secondary's ray groups and culls on the GPU (gl_clustering.cpp,
// GlClustering::group), after the clustering passes, from their labels:
// what the host's cluster_rays and cluster_culls make per cluster
// (render/secondary/dof_secondary.cpp), for every slot at once.
//
// BC_GROUP_STEP_RAYS, an invocation per ray: the ray's triangle is its
// slot's own (a bit, atomicOr) and its cosine to the slot's forward axis
// goes into the slot's least (atomicMin of bc_float_order); the first ray
// of each pixel's run (the rays come in pixel order, at most
// BC_GROUP_RAYS_PER_SAMPLE * spp a pixel) lists the run.
//
// BC_GROUP_STEP_RUNS, an invocation per listed run (all of them busy: a
// run's work in the ray step kept most of a SIMD group idle): the run
// sorted by lens part and slot, in scratch beside the pairs, and each
// group (one pixel's rays in one slot and lens part) listed in its slot:
// a place for the group's rays and one for its (begin, end) pair, both
// taken by atomicAdd. The order of the groups in a list is the order the
// invocations ran in; each group's rays are the host's group's, and the
// passes that read them (clip, trace, the culls) do not depend on the
// order: hits are written by ray index, footprints and cull depths are
// minima and maxima.
//
// BC_GROUP_STEP_THRESHOLDS, an invocation per slot: the normal cone's
// threshold from the least cosine.
layout(local_size_x = BC_TRACE_GROUP) in;
layout(std430, binding = BC_GL_CLUSTER_POINTS_BINDING) readonly buffer PointWords { uvec4 point_word[]; };
layout(std430, binding = BC_GL_CLUSTER_LABELS_BINDING) readonly buffer Labels { uint label[]; };  // facet * 4 + local
layout(std430, binding = BC_GL_GROUP_SLOTS_BINDING) coherent buffer Slots { ClusterSlotGroups slots[]; };
layout(std430, binding = BC_GL_GROUP_LISTS_BINDING) writeonly buffer Lists { uint list[]; };
// 2 words a ray (the pairs), 2 a ray of scratch, then the runs' count and first rays.
layout(std430, binding = BC_GL_GROUP_PAIRS_BINDING) coherent buffer Pairs { uint pair[]; };
layout(std430, binding = BC_GL_GROUP_OWN_BINDING) coherent buffer Own { uint own_bits[]; };
uniform int step;
uniform uint rays;
uniform uint own_words;  // per slot: (triangles + 31) / 32
uniform uint triangles;
uniform int cull_normals;

// Ray r's slot; BC_CLUSTER_SLOTS for a label naming none (the clustering
// leaves none such: the host checks where it reads the labels back).
uint slot_of(uint r) {
    uint l = label[r];
    uint facet = l >> 2u, local = l & 3u;
    bool valid = facet < uint(BC_CLUSTER_FACETS) && local < uint(BC_CLUSTERS_PER_FACET_MAX);
    return valid ? facet * uint(BC_CLUSTERS_PER_FACET_MAX) + local : uint(BC_CLUSTER_SLOTS);
}
uint pixel_of(uint r) { return point_word[2u * r + 1u].w >> BC_GROUP_PART_BITS; }
uint part_of(uint r) { return point_word[2u * r + 1u].w & ((1u << BC_GROUP_PART_BITS) - 1u); }
// Lens part, then slot: the sort key of a run.
uint group_key(uint r) { return part_of(r) * uint(BC_CLUSTER_SLOTS + 1) + slot_of(r); }

// Scratch: 2 words a ray from word 2 * rays, the run's rays sorted with
// their keys (group_key), each run in its own rays' words.
uint scratch_at(uint r) { return 2u * rays + 2u * r; }

// The group of sorted rays [begin, end) of a run (one slot and lens part
// of one pixel) listed in its slot.
void list_group(uint begin, uint end) {
    uint slot = pair[scratch_at(begin) + 1u] % uint(BC_CLUSTER_SLOTS + 1);
    if (slot >= uint(BC_CLUSTER_SLOTS)) return;
    uint count = end - begin;
    uint at = atomicAdd(slots[slot].filled, count);
    uint g = atomicAdd(slots[slot].groups, 1u);
    uint first = slots[slot].first;
    for (uint k = 0u; k < count; ++k) list[first + at + k] = pair[scratch_at(begin + k)];
    pair[2u * (first + g)] = at;
    pair[2u * (first + g) + 1u] = at + count;
}

// The run of pixel rays [r, end): counted by lens part into scratch (its
// part's rays in ray order, with their keys), each part's rays then sorted
// by slot (insertion: a part's rays are mostly of one or two slots), and
// each run of one key listed.
void group_run(uint r) {
    uint pixel = pixel_of(r);
    uint end = r + 1u;
    while (end < rays && pixel_of(end) == pixel) ++end;
    uint starts[1u << BC_GROUP_PART_BITS];
    for (uint p = 0u; p < (1u << BC_GROUP_PART_BITS); ++p) starts[p] = 0u;
    for (uint i = r; i < end; ++i) ++starts[part_of(i)];
    uint sum = r;
    for (uint p = 0u; p < (1u << BC_GROUP_PART_BITS); ++p) {
        uint n = starts[p];
        starts[p] = sum;
        sum += n;
    }
    for (uint i = r; i < end; ++i) {
        uint key = group_key(i);
        uint at = scratch_at(starts[key / uint(BC_CLUSTER_SLOTS + 1)]++);
        pair[at] = i;
        pair[at + 1u] = key;
    }
    for (uint i = r + 1u; i < end; ++i) {
        uint ray = pair[scratch_at(i)];
        uint key = pair[scratch_at(i) + 1u];
        uint j = i;
        for (; j > r && pair[scratch_at(j - 1u) + 1u] > key; --j) {
            pair[scratch_at(j)] = pair[scratch_at(j - 1u)];
            pair[scratch_at(j) + 1u] = pair[scratch_at(j - 1u) + 1u];
        }
        pair[scratch_at(j)] = ray;
        pair[scratch_at(j) + 1u] = key;
    }
    uint begin = r;
    for (uint i = r + 1u; i <= end; ++i) {
        if (i == end || pair[scratch_at(i) + 1u] != pair[scratch_at(begin) + 1u]) {
            list_group(begin, i);
            begin = i;
        }
    }
}

void main() {
    uint i = dispatch_item();
    uint runs = 4u * rays;  // the runs' count, then their first rays
    if (step == BC_GROUP_STEP_RUNS) {
        if (i < pair[runs]) group_run(pair[runs + 1u + i]);
        return;
    }
    if (step == BC_GROUP_STEP_THRESHOLDS) {
        if (i >= uint(BC_CLUSTER_SLOTS)) return;
        slots[i].normal_threshold = bc_normal_cone_threshold(bc_float_of_order(slots[i].cos_key), cull_normals != 0);
        return;
    }
    if (i >= rays) return;
    if (i == 0u || pixel_of(i - 1u) != pixel_of(i)) pair[runs + 1u + atomicAdd(pair[runs], 1u)] = i;
    uint slot = slot_of(i);
    if (slot >= uint(BC_CLUSTER_SLOTS)) return;
    uint triangle = point_word[2u * i].w;
    // The atomics only where they would change something (a slot's rays
    // share a few triangles and soon its least cosine): a read that misses
    // a concurrent write only costs the atomic it would have skipped.
    uint word = slot * own_words + (triangle >> 5u), bit = 1u << (triangle & 31u);
    if (triangle < triangles && (own_bits[word] & bit) == 0u) atomicOr(own_bits[word], bit);
    vec3 direction = uintBitsToFloat(point_word[2u * i + 1u].xyz);
    vec3 forward = vec3(slots[slot].forward[0], slots[slot].forward[1], slots[slot].forward[2]);
    uint cos_key = bc_float_order(bc_dot3(direction, forward));
    if (cos_key < slots[slot].cos_key) atomicMin(slots[slot].cos_key, cos_key);
}
