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
#define BC_PATTERN_PADDED_SOBOL 4  // (x, y) and (u, v, t) from two independently shuffled Sobol sets
#define BC_PATTERN_COUNT 5     // ids are 0 .. BC_PATTERN_COUNT - 1

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

// The Laine-Karras permutation of a bit-reversed 32-bit value: bit i of the
// result is bit i of x xored with a function of the bits below it and of the
// seed (adding, multiplying by an odd number, xoring with a product by an
// even number each keep that), which, read with the bits reversed, is Owen's
// nested uniform scrambling (Laine and Karras, "Stratified sampling for
// stochastic transparency", EGSR 2011; Burley, "Practical Hash-based Owen
// Scrambling", JCGT 9(4), 2020). The constants are N. Vegdahl's improved
// hash ("Building a better LK hash", 2021), as in Blender Cycles.
BC_FN uint bc_lk_permute(uint x, uint seed) {
    x = x ^ (x * 0x3d20adeau);
    x = x + seed;
    x = x * ((seed >> 16u) | 1u);
    x = x ^ (x * 0x05526c56u);
    x = x ^ (x * 0x53a22864u);
    return x;
}

// Nested uniform (Owen) scrambling of a 32-bit fraction (Burley 2020's
// nested_uniform_scramble): the top m output digits are a function of the
// top m input digits and the seed only, and a bijection of them.
BC_FN uint bc_owen_scramble(uint x, uint seed) {
    return bc_reverse_bits(bc_lk_permute(bc_reverse_bits(x), seed));
}

// Point `index` of the Sobol sequence in dimension dim (0..4), as a 32-bit
// fraction with its bits reversed (bit 0 = the first binary digit), so that
// bc_lk_permute scrambles it directly. Dimension 0 is van der Corput;
// dimensions 1..4 use the primitive polynomials (degree s, coefficients a) and
// initial numbers m_1..m_s of dimensions 2..5 of S. Joe and F. Y. Kuo,
// "Constructing Sobol sequences with better two-dimensional projections",
// SIAM J. Sci. Comput. 30(5), 2008 (table new-joe-kuo-6.21201):
// (1,0;1) (2,1;1,3) (3,1;1,3,1) (3,2;1,1,1). Direction numbers follow the
// recurrence of Bratley and Fox (1988), V_k = m_k 2^(32-k) for k <= s, then
// V_k = V_(k-s) ^ (V_(k-s) >> s) ^ sum over j < s of a_j V_(k-j); reversed,
// R_k = V_k's bits reversed = m_k's k bits reversed, and >> becomes <<.
BC_FN uint bc_sobol_reversed(uint index, int dim) {
    if (dim <= 0) return index;
    uint s = 3u;
    uint a = 2u;
    uint r1 = 1u;  // m_1 = 1 in every dimension
    uint r2 = 2u;  // m_2 = 1: "01" reversed
    uint r3 = 4u;  // m_3 = 1: "001" reversed
    if (dim == 1) {
        s = 1u;
        a = 0u;
    } else if (dim == 2) {
        s = 2u;
        a = 1u;
        r2 = 3u;  // m_2 = 3
    } else if (dim == 3) {
        a = 1u;
        r2 = 3u;
    }
    uint result = 0u;
    uint v1 = 0u;  // R_(k-1)
    uint v2 = 0u;  // R_(k-2)
    uint v3 = 0u;  // R_(k-3)
    for (uint k = 1u; k <= 32u; ++k) {
        if ((index >> (k - 1u)) == 0u) break;
        uint v;
        if (k <= s) {
            v = k == 1u ? r1 : (k == 2u ? r2 : r3);
        } else {
            uint back = s == 1u ? v1 : (s == 2u ? v2 : v3);
            v = back ^ (back << s);
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

// Point `index` of the Sobol sequence in dimension dim (0..4), as a 32-bit
// fraction (bit 31 = the first binary digit).
BC_FN uint bc_sobol(uint index, int dim) {
    return bc_reverse_bits(bc_sobol_reversed(index, dim));
}

// The lens sample of a point of the unit square, kept inside [-1, 1]^2 (the
// culling bounds assume it; bc_square_to_disk keeps it, the clamp guards it).
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
        vec2 xy = vec2(real(cell_xy % n), real(cell_xy / n)) + jitter_xy;
        vec2 uv = vec2(real(cell_uv % n), real(cell_uv / n)) + jitter_uv;
        s.offset = vec2(bc_div(xy.x, real(n)), bc_div(xy.y, real(n)));
        square = vec2(bc_div(uv.x, real(n)), bc_div(uv.y, real(n)));
    } else {
        s.offset = jitter_xy;
        square = jitter_uv;
    }
    // (cell + jitter) / n may round up to exactly 1 in float.
    s.offset = min(s.offset, vec2(real(1) - bc_epsilon()));
    uint stratum = index;
    if (!time_by_index) stratum = bc_permute(index % count, count, bc_hash(pixel_key ^ 0xd3a2646cu));
    s.time = min(bc_div(real(stratum % count) + bc_unit(bc_hash(h ^ 3u)), real(count)), real(1) - bc_epsilon());
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

// The per-pixel part of the Sobol patterns: the index shuffle's key and mask
// and one Owen-scrambling seed per dimension.
struct SobolSetup {
    uint index_key;   // the shuffle of (x, y)'s index
    uint index_key2;  // BC_PATTERN_PADDED_SOBOL: the shuffle of (u, v, t)'s index
    uint index_mask;  // 2^m - 1 with 2^m >= spp: the pixel's points are one block of 2^m
    uint dim_key0;
    uint dim_key1;
    uint dim_key2;
    uint dim_key3;
    uint dim_key4;
};

BC_FN SobolSetup bc_sobol_setup(uint px, uint py, uint spp, uint seed) {
    SobolSetup p;
    uint pixel_key = bc_hash3(px, py, seed ^ 0xe6546b64u);
    p.index_key = bc_hash(pixel_key ^ 0x5851f42du);
    p.index_key2 = bc_hash(pixel_key ^ 0x14057b7eu);
    p.index_mask = 0u;
    while (p.index_mask < max(spp, 1u) - 1u) p.index_mask = (p.index_mask << 1u) | 1u;
    p.dim_key0 = bc_hash(pixel_key ^ 0x68e31da4u);
    p.dim_key1 = bc_hash(pixel_key ^ 0xb5297a4du);
    p.dim_key2 = bc_hash(pixel_key ^ 0x1b56c4e9u);
    p.dim_key3 = bc_hash(pixel_key ^ 0x3c6ef372u);
    p.dim_key4 = bc_hash(pixel_key ^ 0xa54ff53au);
    return p;
}

// The index shuffle (Burley 2020): Owen-scrambling the index maps indices
// 0 .. 2^m - 1 onto one aligned block of 2^m Sobol points, itself a net, in a
// random order; masked to the pixel's 2^M >= spp points so the Sobol sums stay
// short.
BC_FN uint bc_sobol_shuffle(uint index, uint key, uint mask) {
    return bc_owen_scramble(index, key) & mask;
}

// Coordinate dim of Sobol point `shuffled`, Owen-scrambled with `key`, in [0, 1).
BC_FN real bc_sobol_unit(uint shuffled, int dim, uint key) {
    return bc_unit(bc_reverse_bits(bc_lk_permute(bc_sobol_reversed(shuffled, dim), key)));
}

// Owen-scrambled 5D Sobol (x, y, t, u, v = dimensions 0..4): the pixel's
// samples, for any power-of-two prefix, are a net of the Sobol sequence,
// (x, y) a (0, m, 2)-net, each coordinate stratified in 2^m strata.
BC_FN PixelSample bc_sobol_from(BC_IN(SobolSetup) p, uint index) {
    uint shuffled = bc_sobol_shuffle(index, p.index_key, p.index_mask);
    PixelSample s;
    s.offset = vec2(bc_sobol_unit(shuffled, 0, p.dim_key0), bc_sobol_unit(shuffled, 1, p.dim_key1));
    s.time = bc_sobol_unit(shuffled, 2, p.dim_key2);
    s.lens = bc_lens_of(vec2(bc_sobol_unit(shuffled, 3, p.dim_key3), bc_sobol_unit(shuffled, 4, p.dim_key4)));
    return s;
}

// Padded Sobol (Kollig and Keller's padding with Burley's shuffles): (x, y)
// = Sobol dimensions 0, 1 under one index shuffle, (u, v, t) = dimensions
// 0, 1, 2 under an independent one. Both the pixel position and the lens
// square are (0, m, 2)-nets, the lens and time jointly a (1, m, 3)-net
// (dimensions 0..2 of Joe and Kuo), at the cost of any joint stratification
// between position and lens.
BC_FN PixelSample bc_padded_sobol_from(BC_IN(SobolSetup) p, uint index) {
    uint position = bc_sobol_shuffle(index, p.index_key, p.index_mask);
    uint lens_time = bc_sobol_shuffle(index, p.index_key2, p.index_mask);
    PixelSample s;
    s.offset = vec2(bc_sobol_unit(position, 0, p.dim_key0), bc_sobol_unit(position, 1, p.dim_key1));
    s.lens = bc_lens_of(vec2(bc_sobol_unit(lens_time, 0, p.dim_key3), bc_sobol_unit(lens_time, 1, p.dim_key4)));
    s.time = bc_sobol_unit(lens_time, 2, p.dim_key2);
    return s;
}

// BC_PATTERN_SOBOL: sample `index` of `spp` of pixel (px, py).
BC_FN PixelSample pattern_sobol(uint px, uint py, uint index, uint spp, uint seed) {
    return bc_sobol_from(bc_sobol_setup(px, py, spp, seed), index);
}

// BC_PATTERN_PADDED_SOBOL: sample `index` of `spp` of pixel (px, py).
BC_FN PixelSample pattern_padded_sobol(uint px, uint py, uint index, uint spp, uint seed) {
    return bc_padded_sobol_from(bc_sobol_setup(px, py, spp, seed), index);
}

// The common interface: sample `index` of `spp` of pixel (px, py) in one of
// the BC_PATTERN_* patterns (an unknown id gives pixel_sample).
BC_FN PixelSample pattern_sample(int pattern, uint px, uint py, uint index, uint spp, uint seed) {
    if (pattern == BC_PATTERN_RANDOM) return pattern_random(px, py, index, seed);
    if (pattern == BC_PATTERN_JITTERED) return pattern_jittered(px, py, index, spp, seed);
    if (pattern == BC_PATTERN_SOBOL) return pattern_sobol(px, py, index, spp, seed);
    if (pattern == BC_PATTERN_PADDED_SOBOL) return pattern_padded_sobol(px, py, index, spp, seed);
    return pixel_sample(px, py, index, spp, seed);
}

// ---- the sampler of the stochastic renderers (--sampler) --------------------

// What a renderer computes once per pixel to draw all of its samples in the
// pattern it renders with: the pattern's per-pixel setup.
struct SamplerSetup {
    int pattern;
    PixelSampleSetup hashed;  // BC_PATTERN_HASHED
    SobolSetup sobol;         // BC_PATTERN_SOBOL, BC_PATTERN_PADDED_SOBOL
    uint px;
    uint py;
    uint spp;
    uint seed;
};

// The per-pixel setup of pattern `pattern` (BC_PATTERN_*) for pixel (px, py),
// spp >= 1 samples and seed; every backend draws its samples through it.
BC_FN SamplerSetup sampler_setup(int pattern, uint px, uint py, uint spp, uint seed) {
    SamplerSetup p;
    p.pattern = pattern;
    p.hashed = pixel_sample_setup(px, py, spp, seed);
    p.sobol = bc_sobol_setup(px, py, spp, seed);
    p.px = px;
    p.py = py;
    p.spp = spp;
    p.seed = seed;
    return p;
}

// Sample `index` of the pixel of setup p: pattern_sample(p.pattern, ...) with
// the per-pixel work done once (BC_PATTERN_HASHED is pixel_sample_from).
BC_FN PixelSample sampler_sample(BC_IN(SamplerSetup) p, uint index) {
    if (p.pattern == BC_PATTERN_SOBOL) return bc_sobol_from(p.sobol, index);
    if (p.pattern == BC_PATTERN_PADDED_SOBOL) return bc_padded_sobol_from(p.sobol, index);
    if (p.pattern == BC_PATTERN_HASHED) return pixel_sample_from(p.hashed, index);
    return pattern_sample(p.pattern, p.px, p.py, index, p.spp, p.seed);
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
    real inverse_base = bc_div(real(1), real(base));
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
// turn in [0, 1): uniform on the disk for uniform (r2, turn). With the
// sampler's own sqrt and cos/sin (sampling_body.inl), so every GPU draws the
// host's samples: the angle is (pi/2) k + (pi/4) t with k = the nearest
// quarter turn, t = 2 (4 turn - k) in [-1, 1] (both exact), and the quarter
// k turns (cos, sin) by exact swaps and negations.
BC_FN vec2 bc_polar_disk(real r2, real turn) {
    real r = bc_sqrt(r2);
    real v = real(4) * turn;
    real k = floor(v + real(0.5));
    vec2 cs = bc_cos_sin_quarter_pi(real(2) * (v - k));
    int quarter = int(k) & 3;
    vec2 d = cs;
    if (quarter == 1) d = vec2(-cs.y, cs.x);
    if (quarter == 2) d = vec2(-cs.x, -cs.y);
    if (quarter == 3) d = vec2(cs.y, -cs.x);
    return clamp(vec2(r * d.x, r * d.y), vec2(real(-1)), vec2(real(1)));
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
