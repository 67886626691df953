// Seeded inputs of the secondary-ray kernel tests (test_kernel_secondary and
// its GLSL parity twin): directions for the facet classifier, including the
// ones on facet borders and vertices; clusters of reflector pixels; a layered
// image of two planes and rays at it. Built in double; kernel<float> tests
// round them once.
#pragma once

#include "kernel_generators.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace blurcull::testing {

using dvec3 = glm::dvec3;

inline dvec3 random_unit(Rng& rng) {
    for (;;) {
        dvec3 d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        double l2 = glm::dot(d, d);
        if (l2 > 1e-6 && l2 <= 1.0) return d / std::sqrt(l2);
    }
}

// The 12 face normals in long double, from their definition.
inline void exact_normals(long double n[12][3]) {
    const long double phi = (1.0L + std::sqrt(5.0L)) / 2.0L;
    const long double s = std::sqrt(1.0L + phi * phi);
    for (int face = 0; face < 12; ++face) {
        int family = face / 4;
        long double first = (face & 2) ? -1.0L : 1.0L;
        long double second = (face & 1) ? -1.0L : 1.0L;
        long double v[3];
        if (family == 0) { v[0] = 0; v[1] = first * phi; v[2] = second; }
        else if (family == 1) { v[0] = first; v[1] = 0; v[2] = second * phi; }
        else { v[0] = first * phi; v[1] = second; v[2] = 0; }
        for (int a = 0; a < 3; ++a) n[face][a] = v[a] / s;
    }
}

// Directions for the classifier: random ones over many scales, and the hard
// cases: sums of two adjacent normals (facet borders) and of three mutually
// adjacent ones (vertices), each exact and nudged by a few ULP; directions
// with zero (and negative zero) components; the axes, (+-1, +-1, +-1), zero.
inline std::vector<dvec3> facet_test_directions(std::uint64_t seed, int count) {
    Rng rng(seed);
    long double n[12][3];
    exact_normals(n);
    auto normal = [&](int f) { return dvec3(double(n[f][0]), double(n[f][1]), double(n[f][2])); };
    std::vector<int> pairs;    // adjacent faces: dot = 1 / sqrt 5
    std::vector<int> triples;  // mutually adjacent
    auto adjacent = [&](int a, int b) {
        long double d = n[a][0] * n[b][0] + n[a][1] * n[b][1] + n[a][2] * n[b][2];
        return std::fabs(d - 1.0L / std::sqrt(5.0L)) < 1e-9L;
    };
    for (int a = 0; a < 12; ++a)
        for (int b = a + 1; b < 12; ++b) {
            if (!adjacent(a, b)) continue;
            pairs.push_back(a * 12 + b);
            for (int c = b + 1; c < 12; ++c)
                if (adjacent(a, c) && adjacent(b, c)) triples.push_back((a * 12 + b) * 12 + c);
        }
    std::vector<dvec3> out;
    for (double x : {-1.0, 0.0, 1.0})
        for (double y : {-1.0, 0.0, 1.0})
            for (double z : {-1.0, 0.0, 1.0}) out.emplace_back(x, y, z);
    for (double zero : {0.0, -0.0}) {
        out.emplace_back(0.3, 1.0, zero);
        out.emplace_back(-0.3, -1.0, zero);
        out.emplace_back(zero, 0.4, 1.0);
        out.emplace_back(1.0, zero, -0.2);
        out.emplace_back(zero, zero, -1.0);
        out.emplace_back(-1.0, zero, zero);
    }
    auto nudge = [&](dvec3 d) {
        int kind = static_cast<int>(rng.below(3));
        if (kind == 0) return d;
        for (int a = 0; a < 3; ++a) {
            int ulps = static_cast<int>(rng.below(9)) - 4;
            for (int u = 0; u < std::abs(ulps); ++u) d[a] = std::nextafter(d[a], ulps > 0 ? 1e9 : -1e9);
            if (kind == 2) d[a] = double(float(d[a]));
        }
        return d;
    };
    while (static_cast<int>(out.size()) < count) {
        double scale = std::pow(10.0, rng.uniform(-6.0, 6.0));
        int kind = static_cast<int>(rng.below(10));
        dvec3 d;
        if (kind == 0) {
            int p = pairs[rng.below(static_cast<int>(pairs.size()))];
            d = nudge((normal(p / 12) + normal(p % 12)) * scale);
        } else if (kind == 1) {
            int t = triples[rng.below(static_cast<int>(triples.size()))];
            d = nudge((normal(t / 144) + normal(t / 12 % 12) + normal(t % 12)) * scale);
        } else if (kind == 2) {
            d = random_unit(rng) * scale;
            d[rng.below(3)] = rng.below(2) ? 0.0 : -0.0;
        } else {
            d = random_unit(rng) * scale;
        }
        out.push_back(d);
    }
    return out;
}

// A cluster of reflector pixels: positions around a centre, unit specular
// directions within `cone_degrees` of an axis.
struct SyntheticCluster {
    std::vector<dvec3> positions;
    std::vector<dvec3> directions;
};

inline dvec3 direction_in_cone(Rng& rng, dvec3 axis, double cone_degrees) {
    double cos_max = std::cos(cone_degrees * 3.14159265358979323846 / 180.0);
    for (;;) {
        dvec3 d = random_unit(rng);
        if (glm::dot(d, axis) >= cos_max) return d;
        // Rejection is slow for narrow cones: pull towards the axis instead.
        double w = rng.uniform();
        d = glm::normalize(axis * (1.0 + 8.0 * w) + d);
        if (glm::dot(d, axis) >= cos_max) return d;
    }
}

inline SyntheticCluster make_cluster(Rng& rng, double cone_degrees) {
    SyntheticCluster c;
    int count = 1 + static_cast<int>(rng.below(rng.below(4) == 0 ? 4 : 300));
    dvec3 centre(rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0));
    double spread = std::pow(10.0, rng.uniform(-2.0, 0.5));
    dvec3 stretch(rng.uniform(0.1, 1.0), rng.uniform(0.1, 1.0), rng.uniform(0.1, 1.0));
    dvec3 axis = random_unit(rng);
    for (int i = 0; i < count; ++i) {
        dvec3 r(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        c.positions.push_back(centre + spread * stretch * r);
        c.directions.push_back(direction_in_cone(rng, axis, cone_degrees));
    }
    return c;
}

// A layered image for the tracing tests: a view at the origin looking down
// +z; layer 0 is the plane dot(normal, p) = offset, layer 1 a nearer
// plane seen only through a square window of texels (an occluder).
struct LayerScene {
    dvec3 eye{0.0, 0.0, 0.0};
    dvec3 forward{0.0, 0.0, 1.0};
    dvec3 right{1.0, 0.0, 0.0};
    dvec3 up{0.0, 1.0, 0.0};
    double tan_half_fov = 0.83909963117728;  // 80 degrees
    double near = 0.1;
    double far = 100.0;
    int size = 64;
    dvec3 plane_normal{0.0, 0.0, -1.0};
    double plane_offset = -8.0;  // z = 8
    dvec3 occluder_normal{0.0, 0.0, -1.0};
    double occluder_offset = -4.0;
    int window_lo = 20;  // occluder texels: [lo, hi)^2
    int window_hi = 36;
    std::vector<double> depth[2];  // size * size each, row y, column x
};

// Depth along the view ray through continuous image position (ix, iy) to the
// plane dot(n, p) = c, or +infinity.
inline double plane_view_depth(const LayerScene& s, double ix, double iy, dvec3 n, double c) {
    double sx = (ix / s.size * 2.0 - 1.0) * s.tan_half_fov;
    double sy = (iy / s.size * 2.0 - 1.0) * s.tan_half_fov;
    dvec3 ray = s.forward + sx * s.right + sy * s.up;  // depth 1 per unit
    double den = glm::dot(n, ray);
    if (den == 0.0) return std::numeric_limits<double>::infinity();
    double z = (c - glm::dot(n, s.eye)) / den;
    return z > 0.0 ? z : std::numeric_limits<double>::infinity();
}

inline LayerScene make_layer_scene(Rng& rng) {
    LayerScene s;
    s.plane_normal = glm::normalize(dvec3(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), -1.0));
    s.plane_offset = glm::dot(s.plane_normal, dvec3(0.0, 0.0, rng.uniform(5.0, 12.0)));
    s.occluder_offset = glm::dot(s.occluder_normal, dvec3(0.0, 0.0, rng.uniform(2.0, 4.0)));
    for (int l = 0; l < 2; ++l) s.depth[l].assign(static_cast<std::size_t>(s.size * s.size), 0.0);
    for (int y = 0; y < s.size; ++y)
        for (int x = 0; x < s.size; ++x) {
            std::size_t i = static_cast<std::size_t>(y * s.size + x);
            s.depth[0][i] = plane_view_depth(s, x + 0.5, y + 0.5, s.plane_normal, s.plane_offset);
            bool window = x >= s.window_lo && x < s.window_hi && y >= s.window_lo && y < s.window_hi;
            s.depth[1][i] = window ? plane_view_depth(s, x + 0.5, y + 0.5, s.occluder_normal, s.occluder_offset)
                                   : std::numeric_limits<double>::infinity();
        }
    return s;
}

// A ray of the tracing tests: from a point in front of the occluder's depth,
// towards a random point of the main plane inside the view.
struct TraceRay {
    dvec3 origin;
    dvec3 direction;  // unit
};

inline TraceRay make_trace_ray(Rng& rng, const LayerScene& s) {
    TraceRay r;
    double z = rng.uniform(0.5, 1.8);
    r.origin = dvec3(rng.uniform(-0.6, 0.6) * z, rng.uniform(-0.6, 0.6) * z, z);
    double ix = rng.uniform(2.0, s.size - 2.0);
    double iy = rng.uniform(2.0, s.size - 2.0);
    double d = plane_view_depth(s, ix, iy, s.plane_normal, s.plane_offset);
    dvec3 target = s.eye + d * (s.forward + (ix / s.size * 2.0 - 1.0) * s.tan_half_fov * s.right +
                                (iy / s.size * 2.0 - 1.0) * s.tan_half_fov * s.up);
    r.direction = glm::normalize(target - r.origin);
    return r;
}

// The pixels of a mirror sphere (radius 1 at z = 5) seen from the origin
// through a 96 x 96 image: positions and the mirror directions of the view
// rays.
inline void mirror_sphere_pixels(std::vector<dvec3>& positions, std::vector<dvec3>& directions) {
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            dvec3 ray = glm::normalize(dvec3((x + 0.5) / 96.0 * 0.5 - 0.25, (y + 0.5) / 96.0 * 0.5 - 0.25, 1.0));
            dvec3 centre(0, 0, 5);
            double b = glm::dot(ray, centre);
            double disc = b * b - (glm::dot(centre, centre) - 1.0);
            if (disc <= 0) continue;
            dvec3 p = ray * (b - std::sqrt(disc));
            dvec3 nrm = glm::normalize(p - centre);
            positions.push_back(p);
            directions.push_back(ray - 2.0 * glm::dot(ray, nrm) * nrm);
        }
}

}  // namespace blurcull::testing
