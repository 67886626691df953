// The shapes the built-in scenes are made of (ellipsoids, superellipsoids,
// capsules, frustums, tori, tubes, grids, height fields, boxes), tessellated
// into a Scene, and the frames that place them.
#pragma once

#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace blurcull::frontend::builtin {

constexpr float kPi = 3.14159265358979f;

// Rotation by `angle` radians about `axis` (any length).
glm::mat3 rotation(const glm::vec3& axis, float angle);

// Origin plus right-handed orthonormal axes (the columns).
struct Frame {
    glm::vec3 origin{0.0f};
    glm::mat3 axes{1.0f};
    glm::vec3 point(const glm::vec3& local) const { return origin + axes * local; }
};

// A frame whose local +z points along `direction`.
Frame frame_along(const glm::vec3& origin, const glm::vec3& direction);

// Local y -> world -z and local z -> world up, for shapes whose "vertical"
// axis is local z (superellipsoids, frustums).
Frame upright(const glm::vec3& origin);

// Appends tessellated shapes and materials to a Scene. Every vertex starts
// static (close == open); motion is applied afterwards to vertex ranges.
class MeshBuilder {
public:
    explicit MeshBuilder(Scene& scene) : scene_(scene) {}

    // Adds a material; returns its index.
    std::uint32_t material(const glm::vec3& color, const std::string& name);

    // Vertices so far: the start (or end) of the range a shape adds.
    std::uint32_t vertex_count() const { return static_cast<std::uint32_t>(scene_.position_open.size()); }

    // `points` holds ring_count rings of ring_size points, ring after ring,
    // ordered from the end nearest `first_pole` to the end nearest
    // `last_pole`, each ring counter-clockwise seen from the first pole.
    // Consecutive rings are joined by quads, the poles close the ends with
    // fans, and close_loop joins the last ring back to the first (a torus).
    void rings(const std::vector<glm::vec3>& points, int ring_size, const glm::vec3* first_pole,
               const glm::vec3* last_pole, bool close_loop, std::uint32_t material_index);

    // 2 * slices * (stacks - 1) triangles; local z is the polar axis.
    void ellipsoid(const Frame& frame, const glm::vec3& radii, int slices, int stacks, std::uint32_t material_index);

    // Barr's superellipsoid: exponents below 1 make it boxy (car bodies,
    // palms). `vertical` shapes the profile along local z, `horizontal` the
    // cross-section. 2 * slices * (stacks - 1) triangles.
    void superellipsoid(const Frame& frame, const glm::vec3& radii, float vertical, float horizontal, int slices,
                        int stacks, std::uint32_t material_index);

    // Cylinder from a to b with hemispherical ends: 4 * slices * half_stacks triangles.
    void capsule(const glm::vec3& a, const glm::vec3& b, float radius, int slices, int half_stacks,
                 std::uint32_t material_index);

    // Truncated cone standing on frame.origin along local z, flat caps; a
    // zero top radius makes a pointed cone. 2 * slices * (segments + 1)
    // triangles (2 * slices * segments for a cone).
    void frustum(const Frame& frame, float height, float bottom_radius, float top_radius, int slices, int segments,
                 std::uint32_t material_index);

    // Ring torus around local z: 2 * major * minor triangles.
    void torus(const Frame& frame, float major_radius, float minor_radius, int major, int minor,
               std::uint32_t material_index);

    // Tube through `path` with per-point radii and flat end caps:
    // 2 * slices * path.size() triangles.
    void tube(const std::vector<glm::vec3>& path, const std::vector<float>& radii, int slices,
              std::uint32_t material_index);

    // Flat grid from corner along u and v (normal cross(u, v)): 2 * nu * nv triangles.
    void grid(const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v, int nu, int nv,
              std::uint32_t material_index);

    // squares x squares chessboard from corner along u and v (the whole
    // board's edges), alternating materials `first` (at the corner) and
    // `second`; each square is one grid of cells x cells quads.
    void chessboard(const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v, int squares, int cells,
                    std::uint32_t first, std::uint32_t second);

    // Any parametric surface: (nu + 1) x (nv + 1) points point_at(s, t),
    // s, t in [0, 1], two triangles per cell (normal along dP/ds x dP/dt).
    void surface(int nu, int nv, const std::function<glm::vec3(float, float)>& point_at,
                 std::uint32_t material_index);

    // Terrain y = height(x, z) over [x0, x1] x [z0, z1], facing up.
    void heightfield(float x0, float x1, float z0, float z1, int nx, int nz,
                     const std::function<float(float, float)>& height, std::uint32_t material_index);

    // Box with each face split into subdivisions^2 quads: 12 * subdivisions^2 triangles.
    void box(const glm::vec3& center, const glm::vec3& half, float yaw, int subdivisions,
             std::uint32_t material_index);

    // Moves vertices [first_vertex, end_vertex) by open_offset at shutter
    // open and by close_offset at shutter close.
    void translate(std::uint32_t first_vertex, std::uint32_t end_vertex, const glm::vec3& open_offset,
                   const glm::vec3& close_offset);

private:
    // (nu + 1) x (nv + 1) vertices point_at(i / nu, j / nv), two triangles per cell.
    template <typename PointAt>
    void parametric_grid(int nu, int nv, std::uint32_t material_index, PointAt point_at) {
        std::vector<glm::vec3> points;
        for (int j = 0; j <= nv; ++j) {
            for (int i = 0; i <= nu; ++i) {
                points.push_back(
                    point_at(static_cast<float>(i) / static_cast<float>(nu), static_cast<float>(j) / static_cast<float>(nv)));
            }
        }
        std::vector<glm::uvec3> triangles;
        const auto row = static_cast<std::uint32_t>(nu + 1);
        for (int j = 0; j < nv; ++j) {
            for (int i = 0; i < nu; ++i) {
                const std::uint32_t a = static_cast<std::uint32_t>(j) * row + static_cast<std::uint32_t>(i);
                triangles.emplace_back(a, a + 1, a + row + 1);
                triangles.emplace_back(a, a + row + 1, a + row);
            }
        }
        append_mesh(scene_, points, points, triangles, material_index);
    }

    Scene& scene_;
};

}  // namespace blurcull::frontend::builtin
