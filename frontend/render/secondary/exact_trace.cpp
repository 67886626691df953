#include "render/secondary/exact_trace.hpp"

#include <cmath>
#include <limits>

namespace blurcull::frontend {

namespace {

// The nearest of `count` triangles along origin + s direction, s > s_min,
// triangle t's vertices from vertices(t): Moller-Trumbore in double.
template <typename Vertices>
ExactHit nearest_hit(std::size_t count, const Vertices& vertices, glm::vec3 origin, glm::vec3 direction, float s_min) {
    ExactHit best;
    const glm::dvec3 o(origin), d(direction);
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < count; ++t) {
        const std::array<glm::vec3, 3> p = vertices(t);
        const glm::dvec3 v0(p[0]), e1 = glm::dvec3(p[1]) - v0, e2 = glm::dvec3(p[2]) - v0;
        const glm::dvec3 pv = glm::cross(d, e2);
        const double det = glm::dot(e1, pv);
        if (det == 0.0 || !std::isfinite(det)) continue;
        const double inv = 1.0 / det;
        const glm::dvec3 tv = o - v0;
        const double b1 = glm::dot(tv, pv) * inv;
        if (b1 < 0.0 || b1 > 1.0) continue;
        const glm::dvec3 qv = glm::cross(tv, e1);
        const double b2 = glm::dot(d, qv) * inv;
        if (b2 < 0.0 || b1 + b2 > 1.0) continue;
        const double s = glm::dot(e2, qv) * inv;
        if (s > double(s_min) && s < nearest) {
            nearest = s;
            best.hit = true;
            best.triangle = static_cast<std::uint32_t>(t);
            best.distance = static_cast<float>(s);
        }
    }
    return best;
}

}  // namespace

std::array<glm::vec3, 3> triangle_at(const Scene& scene, std::size_t triangle, float time) {
    const glm::uvec3& tri = scene.triangles[triangle];
    std::array<glm::vec3, 3> p;
    for (int k = 0; k < 3; ++k)
        p[static_cast<std::size_t>(k)] = glm::mix(scene.position_open[tri[k]], scene.position_close[tri[k]], time);
    return p;
}

glm::vec3 unit_normal(const std::array<glm::vec3, 3>& p) {
    const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    const float length = glm::length(n);
    return length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f);
}

bool scene_moves(const Scene& scene) { return scene.position_open != scene.position_close; }

WorldTriangles world_triangles(const Scene& scene, float time) {
    WorldTriangles out;
    out.vertices.resize(scene.triangles.size());
    out.normals.resize(scene.triangles.size());
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        out.vertices[t] = triangle_at(scene, t, time);
        for (const glm::vec3& p : out.vertices[t]) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        out.normals[t] = unit_normal(out.vertices[t]);
    }
    if (!scene.triangles.empty()) {
        out.box_min = lo;
        out.box_max = hi;
    }
    return out;
}

ExactHit trace_exact(const WorldTriangles& triangles, glm::vec3 origin, glm::vec3 direction, float s_min) {
    return nearest_hit(
        triangles.vertices.size(), [&](std::size_t t) { return triangles.vertices[t]; }, origin, direction, s_min);
}

ExactHit trace_exact_at(const Scene& scene, float time, glm::vec3 origin, glm::vec3 direction, float s_min) {
    return nearest_hit(
        scene.triangles.size(), [&](std::size_t t) { return triangle_at(scene, t, time); }, origin, direction, s_min);
}

}  // namespace blurcull::frontend
