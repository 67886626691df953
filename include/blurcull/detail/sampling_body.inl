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

// ---- the sampler's own arithmetic (docs/glsl.md, "The GPU arithmetic model") ----
// GLSL leaves a/b within 2.5 ulp, sqrt within about 4 ulp and cos/sin of
// undefined precision, so a sampler that used them would draw other samples on
// every GPU than on the host. These functions use only + - * (correctly rounded
// on the host, which must not contract a*b+c, and under GLSL's `precise`, which
// the build puts on every value of the bodies), comparisons, floor, frexp and
// ldexp (exact): each gives the same bits on the host and on any conformant GPU.
// Their accuracy (tests/test_kernel_units.cpp): bc_div and bc_sqrt within one
// ulp of the exact result (correctly rounded on nearly every input), the
// quarter-circle cos/sin within 2 ulp of std::cos/std::sin.

// Veltkamp's split of a: hi + lo = a exactly, each of half the significand
// (the factor is 2^ceil(p/2) + 1: 4097 for float, 2^27 + 1 for double).
BC_FN vec2 bc_split(real a) {
    real factor = bc_epsilon() < real(1e-10) ? real(134217729) : real(4097);
    real c = factor * a;
    real hi = c - (c - a);
    return vec2(hi, a - hi);
}

// Dekker's two-product: (p, e) with p = a * b rounded and p + e = a * b
// exactly (no overflow or underflow: |a b| well inside the normal range).
BC_FN vec2 bc_two_product(real a, real b) {
    real p = a * b;
    vec2 x = bc_split(a);
    vec2 y = bc_split(b);
    real e = ((x.x * y.x - p) + x.x * y.y + x.y * y.x) + x.y * y.y;
    return vec2(p, e);
}

// a / b for b != 0 and a quotient in the normal range, without GLSL's
// division: b = m 2^e (frexp, |m| in [0.5, 1)); 1/m by Newton's iteration
// from the linear guess 48/17 - 32/17 |m| (relative error at most 1/17,
// squared by each step: 3 steps in float, 4 in double); q = (a 2^-e) / m
// from it, then corrected once by the exact residual a 2^-e - q m.
BC_FN real bc_div(real a, real b) {
    int e;
    real m = frexp(b, e);
    real n = ldexp(a, -e);
    // A power of two (the stratum counts often are): exact.
    if (m == real(0.5)) return real(2) * n;
    if (m == real(-0.5)) return real(-2) * n;
    real am = abs(m);
    real y = real(2.8235294818878173828125) - real(1.88235294818878173828125) * am;
    y = y + y * (real(1) - am * y);
    y = y + y * (real(1) - am * y);
    y = y + y * (real(1) - am * y);
    if (bc_epsilon() < real(1e-10)) y = y + y * (real(1) - am * y);
    if (m < real(0)) y = -y;
    real q = n * y;
    vec2 p = bc_two_product(q, m);
    real r = (n - p.x) - p.y;  // n - q m: n - p.x is exact (Sterbenz), p.y exact
    if (r == real(0)) return q;  // exact (and keeps the sign of a zero quotient)
    return q + r * y;
}

// sqrt(x) for x >= 0 in the normal range (0 for x <= 0), without GLSL's
// sqrt: x = m 2^e with e even and m in [0.5, 2); 1/sqrt(m) by Newton's
// iteration from a linear guess (4 steps in float, 5 in double); s = m / sqrt(m),
// then corrected once by the exact residual m - s^2.
BC_FN real bc_sqrt(real x) {
    if (!(x > real(0))) return real(0);
    int e;
    real m = frexp(x, e);
    if ((e & 1) != 0) {  // (GLSL leaves % of a negative int undefined)
        m = real(2) * m;
        e = e - 1;
    }
    real y = real(1.5) - real(0.4375) * m;
    real half_m = real(0.5) * m;
    for (int k = 0; k < 4; ++k) y = y * (real(1.5) - half_m * y * y);
    if (bc_epsilon() < real(1e-10)) y = y * (real(1.5) - half_m * y * y);
    real s = m * y;
    vec2 p = bc_two_product(s, s);
    real r = (m - p.x) - p.y;  // m - s^2: m - p.x is exact (Sterbenz), p.y exact
    s = s + r * (real(0.5) * y);
    return ldexp(s, e / 2);
}

// (cos, sin) of (pi / 4) t for t in [-1, 1] (a little beyond is fine), by
// their Taylor series in t: in float (GLSL) to t^10 and t^9, the terms left
// out below 2e-9, the coefficients ((pi/4)^k / k!, rounded to float) written
// out exactly so that every compiler reads the same value. |cos| and |sin|
// never exceed 1.
BC_FN vec2 bc_cos_sin_quarter_pi(real t) {
    real t2 = t * t;
    if (bc_epsilon() < real(1e-10)) {
        // double (C++ only): terms to t^16 and t^17 (the rest below 3e-18)
        // with double's coefficients.
        real cd = real(1) + t2 * (real(-0.30842513753404244) + t2 * (real(0.015854344243815502) +
                  t2 * (real(-0.00032599188692739001) + t2 * (real(3.5908604485915101e-06) +
                  t2 * (real(-2.4611369504941999e-08) + t2 * (real(1.1501159127974052e-10) +
                  t2 * (real(-3.8980731712596753e-13) + t2 * real(1.0018864616362721e-15))))))));
        real sd = t * (real(0.78539816339744828) + t2 * (real(-0.080745512188280785) +
                  t2 * (real(0.0024903945701927202) + t2 * (real(-3.6576204182177253e-05) +
                  t2 * (real(3.1336168903781217e-07) + t2 * (real(-1.757247673443401e-09) +
                  t2 * (real(6.9484532738866292e-12) + t2 * (real(-2.0410263396641442e-14) +
                  t2 * real(4.6287046288346829e-17)))))))));
        return vec2(cd, sd);
    }
    real c = real(1) + t2 * (real(-0.308425128459930419921875) +
                             t2 * (real(0.01585434377193450927734375) +
                                   t2 * (real(-0.000325991888530552387237548828125) +
                                         t2 * (real(0.000003590860387703287415206432342529296875) +
                                               t2 * real(-0.0000000246113689428284487803466618061065673828125)))));
    real s = t * (real(0.785398185253143310546875) +
                  t2 * (real(-0.080745510756969451904296875) +
                        t2 * (real(0.00249039451591670513153076171875) +
                              t2 * (real(-0.0000365762025467120110988616943359375) +
                                    t2 * real(0.00000031336168149209697730839252471923828125)))));
    return vec2(c, s);
}

// Unit square to unit disk, area-preserving (Shirley and Chiu's concentric
// map): radius r = a.x and angle (pi/4) (a.y / a.x) in the sectors around
// the x axis, r = a.y and angle pi/2 - (pi/4) (a.x / a.y) around the y axis,
// with the sampler's own division and cos/sin. |r| <= 1 and |cos|, |sin| <= 1,
// so both coordinates lie in [-1, 1].
BC_FN vec2 bc_square_to_disk(vec2 q) {
    vec2 a = real(2) * q - vec2(real(1));
    if (a.x == real(0) && a.y == real(0)) return vec2(real(0));
    if (abs(a.x) > abs(a.y)) {
        vec2 cs = bc_cos_sin_quarter_pi(bc_div(a.y, a.x));
        return vec2(a.x * cs.x, a.x * cs.y);
    }
    // cos(pi/2 - x) = sin x, sin(pi/2 - x) = cos x
    vec2 cs = bc_cos_sin_quarter_pi(bc_div(a.x, a.y));
    return vec2(a.y * cs.y, a.y * cs.x);
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
        s.offset = vec2(bc_div(real(cell % p.n) + bc_unit(bc_hash(h ^ 1u)), real(p.n)),
                        bc_div(real(cell / p.n) + bc_unit(bc_hash(h ^ 2u)), real(p.n)));
    } else {
        s.offset = vec2(bc_unit(bc_hash(h ^ 1u)), bc_unit(bc_hash(h ^ 2u)));
    }
    // Time: stratified over the shutter, strata permuted independently of position.
    uint stratum = (p.time_mul * index + p.time_add) % p.spp;
    s.time = bc_div(real(stratum) + bc_unit(bc_hash(h ^ 3u)), real(p.spp));
    if (s.time >= real(1)) s.time = real(0.99999994);
    s.lens = bc_square_to_disk(vec2(bc_unit(bc_hash(h ^ 4u)), bc_unit(bc_hash(h ^ 5u))));
    // The culling bounds assume |u|, |v| <= 1, which bc_square_to_disk keeps
    // (products of factors of magnitude <= 1); the clamp guards it.
    s.lens = clamp(s.lens, vec2(real(-1)), vec2(real(1)));
    return s;
}

// Sample `index` (0 .. spp-1) of pixel (px, py): the default pattern
// (BC_PATTERN_HASHED), the same on every backend. kernel.hpp has the details.
BC_FN PixelSample pixel_sample(uint px, uint py, uint index, uint spp, uint seed) {
    return pixel_sample_from(pixel_sample_setup(px, py, spp, seed), index);
}
