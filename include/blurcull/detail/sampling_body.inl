// Shared C++/GLSL text (see dialect.hpp). The per-pixel sample pattern.
//
// Samples are a pure function of (pixel, index, spp, seed): no texture, no
// state, so the CPU and GPU backends draw exactly the same samples and the
// pattern never tiles. Positions are jittered strata of an n x n grid, time is
// stratified over the shutter with a per-pixel rotation, and the strata of
// position and time are decorrelated by a per-pixel affine permutation.

// Integer hash (the "PCG" hash recommended by Jarzynski and Olano, JCGT 2020).
BC_FN uint bc_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

BC_FN uint bc_hash3(uint a, uint b, uint c) {
    return bc_hash(a ^ bc_hash(b ^ bc_hash(c)));
}

// 24 random bits to [0, 1): exact in float, so host and GPU agree bit for bit.
BC_FN real bc_unit(uint h) {
    return real(h >> 8u) * real(5.9604644775390625e-8);
}

BC_FN uint bc_gcd(uint a, uint b) {
    for (int guard = 0; guard < 64 && b != 0u; ++guard) {
        uint r = a % b;
        a = b;
        b = r;
    }
    return a;
}

// A multiplier coprime with n, so i -> (m i + o) mod n is a permutation.
BC_FN uint bc_coprime_multiplier(uint n, uint h) {
    if (n <= 2u) return 1u;
    uint m = 1u + h % (n - 1u);
    for (int guard = 0; guard < 64; ++guard) {
        if (bc_gcd(m, n) == 1u) break;
        m = m + 1u;
        if (m >= n) m = 1u;
    }
    return m;
}

// Unit square to unit disk, area-preserving (Shirley and Chiu's concentric map).
BC_FN vec2 bc_square_to_disk(vec2 q) {
    vec2 a = real(2) * q - vec2(real(1));
    if (a.x == real(0) && a.y == real(0)) return vec2(real(0));
    real quarter_pi = real(0.78539816339744831);
    real r;
    real phi;
    if (abs(a.x) > abs(a.y)) {
        r = a.x;
        phi = quarter_pi * (a.y / a.x);
    } else {
        r = a.y;
        phi = real(2) * quarter_pi - quarter_pi * (a.x / a.y);
    }
    return vec2(r * cos(phi), r * sin(phi));
}

struct PixelSample {
    vec2 offset;  // position inside the pixel, [0,1)^2
    vec2 lens;    // lens position (u, v) in the unit disk
    real time;    // shutter time in [0,1)
};

// What pixel_sample computes once per pixel: its key, the stratum counts and
// the two permutations (position strata, time strata).
struct PixelSampleSetup {
    uint key;
    uint spp;
    uint n;          // position strata per side
    uint cells;      // n * n
    uint cell_mul;   // cell = (cell_mul * index + cell_add) % cells
    uint cell_add;
    uint time_mul;   // stratum = (time_mul * index + time_add) % spp
    uint time_add;
};

// The per-pixel setup of pixel_sample for pixel (px, py), spp >= 1 samples, seed.
BC_FN PixelSampleSetup pixel_sample_setup(uint px, uint py, uint spp, uint seed) {
    PixelSampleSetup p;
    p.key = bc_hash3(px, py, seed);
    p.spp = spp;
    p.n = 1u;
    while ((p.n + 1u) * (p.n + 1u) <= spp) p.n = p.n + 1u;
    p.cells = p.n * p.n;
    p.cell_mul = bc_coprime_multiplier(p.cells, bc_hash(p.key ^ 0x2545f491u));
    p.cell_add = bc_hash(p.key ^ 0x9e3779b9u);
    p.time_mul = bc_coprime_multiplier(spp, bc_hash(p.key ^ 0x85ebca6bu));
    p.time_add = bc_hash(p.key ^ 0xc2b2ae35u);
    return p;
}

// Sample `index` of a pixel, from its setup (a renderer that draws all of a
// pixel's samples computes the setup once).
BC_FN PixelSample pixel_sample_from(BC_IN(PixelSampleSetup) p, uint index) {
    uint h = bc_hash3(p.key, index, 0x68bc21ebu);
    PixelSample s;
    // Position: a per-pixel permutation of the n x n strata, jittered.
    if (index < p.cells) {
        uint cell = (p.cell_mul * index + p.cell_add) % p.cells;
        s.offset = vec2((real(cell % p.n) + bc_unit(bc_hash(h ^ 1u))) / real(p.n),
                        (real(cell / p.n) + bc_unit(bc_hash(h ^ 2u))) / real(p.n));
    } else {
        s.offset = vec2(bc_unit(bc_hash(h ^ 1u)), bc_unit(bc_hash(h ^ 2u)));
    }
    // Time: stratified over the shutter, strata permuted independently of position.
    uint stratum = (p.time_mul * index + p.time_add) % p.spp;
    s.time = (real(stratum) + bc_unit(bc_hash(h ^ 3u))) / real(p.spp);
    if (s.time >= real(1)) s.time = real(0.99999994);
    s.lens = bc_square_to_disk(vec2(bc_unit(bc_hash(h ^ 4u)), bc_unit(bc_hash(h ^ 5u))));
    // Rounding in cos/sin may step a hair outside the disk; the culling bounds
    // assume |u|, |v| <= 1.
    s.lens = clamp(s.lens, vec2(real(-1)), vec2(real(1)));
    return s;
}

// Sample `index` (0 .. spp-1) of pixel (px, py): the default pattern
// (BC_PATTERN_HASHED), the same on every backend. kernel.hpp has the details.
BC_FN PixelSample pixel_sample(uint px, uint py, uint index, uint spp, uint seed) {
    return pixel_sample_from(pixel_sample_setup(px, py, spp, seed), index);
}
