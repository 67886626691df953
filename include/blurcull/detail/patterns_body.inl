// Shared C++/GLSL text (see dialect.hpp): sample patterns and the per-sample
// part of interleaved sampling. Needs sampling_body.inl first (bc_hash,
// bc_unit, bc_square_to_disk, PixelSample, pixel_sample).
//
// Every pattern is a pure function of (pixel, index, spp, seed) returning a
// PixelSample (offset in the pixel, lens in the unit disk, time in [0, 1)),
// like pixel_sample; docs/sampling.md describes them and why Sobol.

#define BC_PATTERN_HASHED 0    // pixel_sample, the default of every backend
#define BC_PATTERN_RANDOM 1    // independent uniform samples
#define BC_PATTERN_JITTERED 2  // stratified in (x, y), (u, v) and t, padded by random shuffles
#define BC_PATTERN_SOBOL 3     // 5D Sobol, Owen-scrambled by hashing, index shuffled per pixel

#define BC_INTERLEAVED_COLOURS 3u

// Reverses the 32 bits of x (GLSL's bitfieldReverse, spelled out for C++).
BC_FN uint bc_reverse_bits(uint x) {
    x = ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
    x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
    x = ((x >> 4u) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4u);
    x = ((x >> 8u) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8u);
    return (x >> 16u) | (x << 16u);
}

// A keyed bijection of [0, mask] for mask = 2^w - 1: addition and odd
// multiplication modulo 2^w and a right xorshift are each invertible there.
BC_FN uint bc_bijection(uint x, uint mask, uint key) {
    uint bits = 0u;
    for (int b = 0; b < 32; ++b) {
        if (((mask >> uint(b)) & 1u) != 0u) bits = bits + 1u;
    }
    uint shift = max(bits / 2u, 1u);
    for (int round = 0; round < 4; ++round) {
        uint k = bc_hash(key ^ (uint(round) * 0x9e3779b9u));
        x = (x + k) & mask;
        x = (x * (k | 1u)) & mask;
        x = x ^ (x >> shift);
    }
    return x;
}

// Element i of a keyed random permutation of [0, n), i < n: the bijection of
// the enclosing power of two, walked along its cycle until it lands below n
// (at most n - 1 steps, since the cycle returns to i itself; n <= 2^20 here).
BC_FN uint bc_permute(uint i, uint n, uint key) {
    if (n <= 1u) return 0u;
    uint mask = n - 1u;
    mask = mask | (mask >> 1u);
    mask = mask | (mask >> 2u);
    mask = mask | (mask >> 4u);
    mask = mask | (mask >> 8u);
    mask = mask | (mask >> 16u);
    uint x = i;
    for (int guard = 0; guard < 1048576; ++guard) {
        x = bc_bijection(x, mask, key);
        if (x < n) return x;
    }
    return i % n;
}

// Nested uniform (Owen) scrambling of a 32-bit fraction by hashing (Laine and
// Karras 2011; Burley, "Practical Hash-based Owen Scrambling", JCGT 2020).
// With the bits reversed, digit i of the fraction is bit i, and each step
// below changes bit i only as a function of the bits below it (the fraction's
// more significant digits) and of the seed: adding, multiplying by an odd
// number, xoring with a product by an even number. That is exactly Owen's
// rule, so nets stay nets. The seed-dependent constants are this project's.
BC_FN uint bc_owen_scramble(uint x, uint seed) {
    uint a = bc_hash(seed ^ 0x3c6ef372u);
    uint b = bc_hash(a ^ 0xa54ff53au);
    uint c = bc_hash(b ^ 0x510e527fu);
    x = bc_reverse_bits(x);
    x = x + a;
    x = x ^ (x * (b << 1u));
    x = x * (c | 1u);
    x = x ^ (x * 0x6a09e668u);
    x = x + b;
    x = x ^ (x * (a << 1u));
    x = x * (bc_hash(c) | 1u);
    return bc_reverse_bits(x);
}

// Point `index` of the Sobol sequence in dimension dim (0..4), as a 32-bit
// fraction. Dimension 0 is van der Corput; dimensions 1..4 use the primitive
// polynomials (degree s, coefficients a) and initial numbers m_1..m_s of
// dimensions 2..5 of S. Joe and F. Y. Kuo, "Constructing Sobol sequences with
// better two-dimensional projections", SIAM J. Sci. Comput. 30(5), 2008
// (table new-joe-kuo-6.21201): (1,0;1) (2,1;1,3) (3,1;1,3,1) (3,2;1,1,1).
// Direction numbers follow the recurrence of Bratley and Fox (1988):
// V_k = m_k 2^(32-k) for k <= s, then
// V_k = V_(k-s) ^ (V_(k-s) >> s) ^ sum over j < s of a_j V_(k-j).
BC_FN uint bc_sobol(uint index, int dim) {
    if (dim <= 0) return bc_reverse_bits(index);
    uint s = 3u;
    uint a = 2u;
    uint m1 = 1u;
    uint m2 = 1u;
    uint m3 = 1u;
    if (dim == 1) {
        s = 1u;
        a = 0u;
    } else if (dim == 2) {
        s = 2u;
        a = 1u;
        m2 = 3u;
    } else if (dim == 3) {
        a = 1u;
        m2 = 3u;
    }
    uint result = 0u;
    uint v1 = 0u;  // V_(k-1)
    uint v2 = 0u;  // V_(k-2)
    uint v3 = 0u;  // V_(k-3)
    for (uint k = 1u; k <= 32u; ++k) {
        if ((index >> (k - 1u)) == 0u) break;
        uint v;
        if (k <= s) {
            uint m = k == 1u ? m1 : (k == 2u ? m2 : m3);
            v = m << (32u - k);
        } else {
            uint back = s == 1u ? v1 : (s == 2u ? v2 : v3);
            v = back ^ (back >> s);
            if (s >= 2u && ((a >> (s - 2u)) & 1u) != 0u) v = v ^ v1;
            if (s >= 3u && ((a >> (s - 3u)) & 1u) != 0u) v = v ^ v2;
        }
        if (((index >> (k - 1u)) & 1u) != 0u) result = result ^ v;
        v3 = v2;
        v2 = v1;
        v1 = v;
    }
    return result;
}

// The lens sample of a point of the unit square, kept inside [-1, 1]^2 (the
// culling bounds assume it; cos/sin rounding may step a hair outside).
BC_FN vec2 bc_lens_of(vec2 square) {
    return clamp(bc_square_to_disk(square), vec2(real(-1)), vec2(real(1)));
}

// Independent uniform samples: the baseline every other pattern must beat.
BC_FN PixelSample pattern_random(uint px, uint py, uint index, uint seed) {
    uint h = bc_hash3(bc_hash3(px, py, seed ^ 0x1b873593u), index, 0x7feb352du);
    PixelSample s;
    s.offset = vec2(bc_unit(bc_hash(h ^ 1u)), bc_unit(bc_hash(h ^ 2u)));
    s.time = bc_unit(bc_hash(h ^ 3u));
    s.lens = bc_lens_of(vec2(bc_unit(bc_hash(h ^ 4u)), bc_unit(bc_hash(h ^ 5u))));
    return s;
}

// Jittered (stratified) samples padded across dimensions: (x, y) and the lens
// square are each an n x n jittered grid (n = floor(sqrt(spp)); samples past
// n^2 are uniform), t is jittered over spp strata, and the three sets are
// paired by independent random permutations of the index, so no stratum of
// one is tied to a stratum of another. With time_by_index, sample `index`
// takes time stratum `index` (the interval method's one sample per stratum).
BC_FN PixelSample bc_jittered(uint px, uint py, uint index, uint spp, uint seed, bool time_by_index) {
    uint count = max(spp, 1u);  // spp = 0 would divide by zero
    uint pixel_key = bc_hash3(px, py, seed ^ 0xcc9e2d51u);
    uint h = bc_hash3(pixel_key, index, 0x85ebca77u);
    uint n = 1u;
    while ((n + 1u) * (n + 1u) <= count && n < 65535u) n = n + 1u;
    uint cells = n * n;
    PixelSample s;
    vec2 jitter_xy = vec2(bc_unit(bc_hash(h ^ 1u)), bc_unit(bc_hash(h ^ 2u)));
    vec2 jitter_uv = vec2(bc_unit(bc_hash(h ^ 4u)), bc_unit(bc_hash(h ^ 5u)));
    vec2 square;
    if (index < cells) {
        uint cell_xy = bc_permute(index, cells, bc_hash(pixel_key ^ 0x27d4eb2fu));
        uint cell_uv = bc_permute(index, cells, bc_hash(pixel_key ^ 0x165667b1u));
        s.offset = (vec2(real(cell_xy % n), real(cell_xy / n)) + jitter_xy) / real(n);
        square = (vec2(real(cell_uv % n), real(cell_uv / n)) + jitter_uv) / real(n);
    } else {
        s.offset = jitter_xy;
        square = jitter_uv;
    }
    // (cell + jitter) / n may round up to exactly 1 in float.
    s.offset = min(s.offset, vec2(real(1) - bc_epsilon()));
    uint stratum = index;
    if (!time_by_index) stratum = bc_permute(index % count, count, bc_hash(pixel_key ^ 0xd3a2646cu));
    s.time = min((real(stratum % count) + bc_unit(bc_hash(h ^ 3u))) / real(count), real(1) - bc_epsilon());
    s.lens = bc_lens_of(square);
    return s;
}

// BC_PATTERN_JITTERED: bc_jittered with the time strata permuted too.
BC_FN PixelSample pattern_jittered(uint px, uint py, uint index, uint spp, uint seed) {
    return bc_jittered(px, py, index, spp, seed, false);
}

// The interval method's sample: jittered, with time in stratum `stratum` of
// `strata` equal parts of the shutter.
BC_FN PixelSample interval_sample(uint px, uint py, uint stratum, uint strata, uint seed) {
    return bc_jittered(px, py, stratum, strata, seed, true);
}

// Owen-scrambled 5D Sobol (x, y, t, u, v = dimensions 0..4). The index is
// Owen-scrambled per pixel too (Burley 2020): that maps the first 2^m indices
// onto one aligned block of 2^m points, itself a net, in a random order, so
// every power-of-two prefix of a pixel's samples stays well stratified.
BC_FN PixelSample pattern_sobol(uint px, uint py, uint index, uint seed) {
    uint pixel_key = bc_hash3(px, py, seed ^ 0xe6546b64u);
    uint shuffled = bc_owen_scramble(index, pixel_key);
    PixelSample s;
    s.offset = vec2(bc_unit(bc_owen_scramble(bc_sobol(shuffled, 0), bc_hash(pixel_key ^ 0u))),
                    bc_unit(bc_owen_scramble(bc_sobol(shuffled, 1), bc_hash(pixel_key ^ 1u))));
    s.time = bc_unit(bc_owen_scramble(bc_sobol(shuffled, 2), bc_hash(pixel_key ^ 2u)));
    s.lens = bc_lens_of(vec2(bc_unit(bc_owen_scramble(bc_sobol(shuffled, 3), bc_hash(pixel_key ^ 3u))),
                             bc_unit(bc_owen_scramble(bc_sobol(shuffled, 4), bc_hash(pixel_key ^ 4u)))));
    return s;
}

// The common interface: sample `index` of `spp` of pixel (px, py) in one of
// the BC_PATTERN_* patterns (an unknown id gives pixel_sample).
BC_FN PixelSample pattern_sample(int pattern, uint px, uint py, uint index, uint spp, uint seed) {
    if (pattern == BC_PATTERN_RANDOM) return pattern_random(px, py, index, seed);
    if (pattern == BC_PATTERN_JITTERED) return pattern_jittered(px, py, index, spp, seed);
    if (pattern == BC_PATTERN_SOBOL) return pattern_sobol(px, py, index, seed);
    return pixel_sample(px, py, index, spp, seed);
}

// The same pattern repeated every `tile` pixels in x and y, so a GPU may
// read it from a tile x tile x spp texture (patterns.hpp: make_pattern_tile)
// instead of computing it; both give the same samples.
BC_FN PixelSample pattern_sample_tiled(int pattern, uint px, uint py, uint index, uint spp, uint seed, uint tile) {
    uint size = max(tile, 1u);
    return pattern_sample(pattern, px % size, py % size, index, spp, seed);
}

// ---- interleaved sampling (Aqsis 2.0 core; Fatahalian et al. 2009) ----------

// Radical inverse of k in `base` (the Halton sequence), below 1.
BC_FN real bc_radical_inverse(uint k, uint base) {
    real inverse_base = real(1) / real(base);
    real digit_scale = inverse_base;
    real value = real(0);
    for (int guard = 0; guard < 32 && k > 0u; ++guard) {
        value = value + digit_scale * real(k % base);
        k = k / base;
        digit_scale = digit_scale * inverse_base;
    }
    return min(value, real(1) - bc_epsilon());
}

// The lens position with squared radius r2 and angle 2 pi turn, for r2 and
// turn in [0, 1): uniform on the disk for uniform (r2, turn).
BC_FN vec2 bc_polar_disk(real r2, real turn) {
    real r = sqrt(r2);
    real theta = real(6.283185307179586) * turn;
    return clamp(vec2(r * cos(theta), r * sin(theta)), vec2(real(-1)), vec2(real(1)));
}

// Tuple k of the frame's interleaved (u, v, t) set, returned as (u, v, t):
// t = radical inverse base 2, lens disk radius sqrt(radical inverse base 3),
// angle 2 pi radical inverse base 5 (uniform on the disk), as in Aqsis 2.0.
BC_FN vec3 interleaved_tuple(uint k) {
    real t = bc_radical_inverse(k, 2u);
    vec2 uv = bc_polar_disk(bc_radical_inverse(k, 3u), bc_radical_inverse(k, 5u));
    return vec3(uv.x, uv.y, t);
}

// Colour (0, 1 or 2) of lattice corner (cx, cy): tile (tx, ty) has corners
// (tx, ty) top-left, (tx + 1, ty) top-right, (tx, ty + 1) bottom-left and
// (tx + 1, ty + 1) bottom-right, so neighbouring tiles share corner colours.
BC_FN uint interleaved_corner_colour(uint cx, uint cy, uint seed) {
    return bc_hash3(cx, cy, seed ^ 0x5bd1e995u) % BC_INTERLEAVED_COLOURS;
}

// Prototype (0..80) of tile (tx, ty): TL + 3 TR + 9 BL + 27 BR corner colours.
BC_FN uint interleaved_prototype(uint tx, uint ty, uint seed) {
    return interleaved_corner_colour(tx, ty, seed) + 3u * interleaved_corner_colour(tx + 1u, ty, seed) +
           9u * interleaved_corner_colour(tx, ty + 1u, seed) +
           27u * interleaved_corner_colour(tx + 1u, ty + 1u, seed);
}

// Position of the sample in lattice cell (gx, gy), in [0, 1)^2 of the cell.
BC_FN vec2 interleaved_jitter(uint gx, uint gy, uint seed) {
    uint h = bc_hash3(gx, gy, seed ^ 0x2127599bu);
    return vec2(bc_unit(bc_hash(h ^ 1u)), bc_unit(bc_hash(h ^ 2u)));
}

// fract(a + shift) for a, shift in [0, 1), kept below 1 (the sum may round up to 2).
BC_FN real bc_rotate_unit(real a, real shift) {
    real v = a + shift;
    if (v >= real(1)) v = v - real(1);
    return min(v, real(1) - bc_epsilon());
}

// Pass k of the accumulation buffer (render_accum): one pinhole pass at lens
// position and time (u, v, t)_k with every pixel sampled at the same sub-pixel
// offset. The Halton points of interleaved_tuple (bases 2, 3, 5 for t, r^2,
// angle) and bases 7, 11 for the offset, all from index k + 1 (index 0 would
// put every sample on a pixel corner and at t = 0), each Cranley-Patterson
// rotated by a shift hashed from the seed: any seed gives a low-discrepancy
// set, and different seeds give different passes.
BC_FN PixelSample accum_sample(uint k, uint seed) {
    uint key = bc_hash(seed ^ 0x68e31da4u);
    uint index = k + 1u;
    PixelSample s;
    s.time = bc_rotate_unit(bc_radical_inverse(index, 2u), bc_unit(bc_hash(key ^ 1u)));
    s.lens = bc_polar_disk(bc_rotate_unit(bc_radical_inverse(index, 3u), bc_unit(bc_hash(key ^ 2u))),
                           bc_rotate_unit(bc_radical_inverse(index, 5u), bc_unit(bc_hash(key ^ 3u))));
    s.offset = vec2(bc_rotate_unit(bc_radical_inverse(index, 7u), bc_unit(bc_hash(key ^ 4u))),
                    bc_rotate_unit(bc_radical_inverse(index, 11u), bc_unit(bc_hash(key ^ 5u))));
    return s;
}
