// Shared C++/GLSL text (see dialect.hpp): the 12 facets of the regular
// dodecahedron, used to group specular directions (Xie, Sun, Wang, JCST 28(3)
// 2013, section 3.2; docs/secondary-rays.md derives the classifier).
//
// The face normals are the 12 vertices of the icosahedron, normalised:
//   family 0: (0, +-phi, +-1),  family 1: (+-1, 0, +-phi),  family 2: (+-phi, +-1, 0),
// phi = (1 + sqrt 5) / 2, each divided by sqrt(1 + phi^2). Face index
//   face = 4 family + 2 (first nonzero component < 0) + (second nonzero component < 0),
// the nonzero components taken in x, y, z order (family 0: y then z; family 1:
// x then z; family 2: x then y). Face 0 is (0, phi, 1) / sqrt(1 + phi^2).

#define BC_DODECAHEDRON_FACES 12

// The two component magnitudes of every face normal, correctly rounded from
// sqrt((5 - sqrt 5) / 10) and sqrt((5 + sqrt 5) / 10).
BC_FN real bc_dodecahedron_small() { return real(0.52573111211913360602566908484788); }
BC_FN real bc_dodecahedron_large() { return real(0.85065080835203993218154049706301); }
// The golden ratio, the weight of the classifier's sums.
BC_FN real bc_golden_ratio() { return real(1.6180339887498948482045868343656); }

// Unit normal of facet `face` (0..11, numbering above). Out-of-range faces
// return the zero vector.
BC_FN vec3 dodecahedron_normal(int face) {
    if (face < 0 || face >= BC_DODECAHEDRON_FACES) return vec3(real(0));
    int family = face / 4;
    real first = (face & 2) != 0 ? -real(1) : real(1);
    real second = (face & 1) != 0 ? -real(1) : real(1);
    real minor_part = bc_dodecahedron_small();
    real major_part = bc_dodecahedron_large();
    if (family == 0) return vec3(real(0), first * major_part, second * minor_part);
    if (family == 1) return vec3(first * minor_part, real(0), second * major_part);
    return vec3(first * major_part, second * minor_part, real(0));
}

// The facet whose normal n maximises dot(n, d), for any direction d (need not
// be unit length; units do not matter).
//
// With a = |d|, the best face of each family matches the signs of d, and its
// dot product times sqrt(1 + phi^2) is
//   c0 = phi a_y + a_z,  c1 = a_x + phi a_z,  c2 = phi a_x + a_y,
// so the largest c picks the family and the signs of d pick the face.
// Tie rule (deterministic, on the computed sums): the lowest family among the
// largest c (c0 before c1 before c2); within the family a component that is
// zero, of either sign, counts as positive. A direction on a facet border up
// to rounding goes to either neighbour; both maximise dot(n, d) to within the
// rounding of the sums (docs/secondary-rays.md, "Ties").
// Fallback: the zero vector goes to face 0 (all sums tie at 0); a NaN
// component fails every comparison, so the result is still a valid face.
BC_FN int dodecahedron_facet(vec3 d) {
    real phi = bc_golden_ratio();
    vec3 a = abs(d);
    BC_PRECISE real c0 = phi * a.y + a.z;
    BC_PRECISE real c1 = a.x + phi * a.z;
    BC_PRECISE real c2 = phi * a.x + a.y;
    int family = 0;
    real best = c0;
    if (c1 > best) {
        family = 1;
        best = c1;
    }
    if (c2 > best) family = 2;
    bool neg_x = d.x < real(0);
    bool neg_y = d.y < real(0);
    bool neg_z = d.z < real(0);
    if (family == 0) return (neg_y ? 2 : 0) + (neg_z ? 1 : 0);
    if (family == 1) return 4 + (neg_x ? 2 : 0) + (neg_z ? 1 : 0);
    return 8 + (neg_x ? 2 : 0) + (neg_y ? 1 : 0);
}
