// Compute pipeline, between the binning's count and fill: the exclusive
// prefix sum of the tiles' counts (each tile's list start, in TileEnds), in
// one work group (each invocation a run of tiles, then a scan of the runs in
// shared memory), counted in 64 bits. Sets bin_state: the entries needed,
// overflow when they exceed the capacity (or 2^32 - 1), the longest list.
layout(local_size_x = 256) in;

TILE_BUFFERS

uniform uint tile_count;

shared uvec2 partial[256];  // (low, high) words of the sums

uvec2 add64(uvec2 a, uvec2 b) {
    uint carry;
    uint low = uaddCarry(a.x, b.x, carry);
    return uvec2(low, a.y + b.y + carry);
}

void main() {
    uint id = gl_LocalInvocationID.x;
    uint per = (tile_count + 255u) / 256u;
    uint first = min(id * per, tile_count), end = min(first + per, tile_count);
    uvec2 sum = uvec2(0u);
    uint longest = 0u;
    for (uint t = first; t < end; ++t) {
        sum = add64(sum, uvec2(tile_counts[t], 0u));
        longest = max(longest, tile_counts[t]);
    }
    if (longest > 0u) atomicMax(bin_state.max_count, longest);
    partial[id] = sum;
    memoryBarrierShared();
    barrier();
    // Inclusive scan of the runs' sums (Hillis and Steele).
    for (uint d = 1u; d < 256u; d <<= 1u) {
        uvec2 before = id >= d ? partial[id - d] : uvec2(0u);
        memoryBarrierShared();
        barrier();
        partial[id] = add64(partial[id], before);
        memoryBarrierShared();
        barrier();
    }
    uint start = id == 0u ? 0u : partial[id - 1u].x;
    for (uint t = first; t < end; ++t) {
        tile_ends[t] = start;
        start += tile_counts[t];
    }
    if (id == 255u) {
        uvec2 total = partial[255];
        bin_state.entries = total.x;
        bin_state.entries_high = total.y;
        bin_state.overflow = total.y != 0u || total.x > bin_state.capacity ? 1u : 0u;
    }
}
