#include "scene/builtin/mesh_builder.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace blurcull::frontend::builtin {

namespace {

float signed_power(float value, float exponent) { return std::copysign(std::pow(std::abs(value), exponent), value); }

float angle_of(int index, int count) { return 2.0f * kPi * static_cast<float>(index) / static_cast<float>(count); }

}  // namespace

glm::mat3 rotation(const glm::vec3& axis, float angle) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), angle, glm::normalize(axis)));
}

Frame frame_along(const glm::vec3& origin, const glm::vec3& direction) {
    const glm::vec3 z = glm::normalize(direction);
    const glm::vec3 helper = std::abs(z.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 x = glm::normalize(glm::cross(helper, z));
    const glm::vec3 y = glm::cross(z, x);
    return {origin, glm::mat3(x, y, z)};
}

Frame upright(const glm::vec3& origin) {
    return {origin, glm::mat3(glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f))};
}

std::uint32_t MeshBuilder::material(const glm::vec3& color, const std::string& name) {
    return add_material(scene_, Material{color, name});
}

void MeshBuilder::rings(const std::vector<glm::vec3>& points, int ring_size, const glm::vec3* first_pole,
                        const glm::vec3* last_pole, bool close_loop, std::uint32_t material_index) {
    const int ring_count = static_cast<int>(points.size()) / ring_size;
    std::vector<glm::vec3> vertices = points;
    std::vector<glm::uvec3> triangles;
    auto at = [&](int ring, int slot) {
        return static_cast<std::uint32_t>((ring % ring_count) * ring_size + slot % ring_size);
    };
    const int joined = close_loop ? ring_count : ring_count - 1;
    for (int ring = 0; ring < joined; ++ring) {
        for (int slot = 0; slot < ring_size; ++slot) {
            triangles.emplace_back(at(ring, slot), at(ring + 1, slot), at(ring, slot + 1));
            triangles.emplace_back(at(ring, slot + 1), at(ring + 1, slot), at(ring + 1, slot + 1));
        }
    }
    if (first_pole != nullptr) {
        const auto pole = static_cast<std::uint32_t>(vertices.size());
        vertices.push_back(*first_pole);
        for (int slot = 0; slot < ring_size; ++slot) triangles.emplace_back(pole, at(0, slot), at(0, slot + 1));
    }
    if (last_pole != nullptr) {
        const auto pole = static_cast<std::uint32_t>(vertices.size());
        vertices.push_back(*last_pole);
        for (int slot = 0; slot < ring_size; ++slot) {
            triangles.emplace_back(pole, at(ring_count - 1, slot + 1), at(ring_count - 1, slot));
        }
    }
    append_mesh(scene_, vertices, vertices, triangles, material_index);
}

void MeshBuilder::ellipsoid(const Frame& frame, const glm::vec3& radii, int slices, int stacks,
                            std::uint32_t material_index) {
    superellipsoid(frame, radii, 1.0f, 1.0f, slices, stacks, material_index);
}

void MeshBuilder::superellipsoid(const Frame& frame, const glm::vec3& radii, float vertical, float horizontal,
                                 int slices, int stacks, std::uint32_t material_index) {
    std::vector<glm::vec3> points;
    for (int stack = 1; stack < stacks; ++stack) {
        const float eta = 0.5f * kPi - kPi * static_cast<float>(stack) / static_cast<float>(stacks);
        const float around = signed_power(std::cos(eta), vertical);
        const float height = signed_power(std::sin(eta), vertical);
        for (int slice = 0; slice < slices; ++slice) {
            const float omega = angle_of(slice, slices);
            points.push_back(frame.point(radii * glm::vec3(around * signed_power(std::cos(omega), horizontal),
                                                           around * signed_power(std::sin(omega), horizontal),
                                                           height)));
        }
    }
    const glm::vec3 top = frame.point({0.0f, 0.0f, radii.z});
    const glm::vec3 bottom = frame.point({0.0f, 0.0f, -radii.z});
    rings(points, slices, &top, &bottom, false, material_index);
}

void MeshBuilder::capsule(const glm::vec3& a, const glm::vec3& b, float radius, int slices, int half_stacks,
                          std::uint32_t material_index) {
    const Frame frame = frame_along(a, b - a);
    const float length = glm::length(b - a);
    std::vector<glm::vec3> points;
    for (int stack = 1; stack <= 2 * half_stacks; ++stack) {
        // Rings 1..half_stacks belong to the b cap, the rest to the a cap;
        // the equator appears once per cap, which makes the cylinder.
        const bool b_cap = stack <= half_stacks;
        const int polar_step = b_cap ? stack : stack - 1;
        const float theta = 0.5f * kPi * static_cast<float>(polar_step) / static_cast<float>(half_stacks);
        const float center = b_cap ? length : 0.0f;
        for (int slice = 0; slice < slices; ++slice) {
            const float phi = angle_of(slice, slices);
            points.push_back(frame.point({radius * std::sin(theta) * std::cos(phi),
                                          radius * std::sin(theta) * std::sin(phi),
                                          center + radius * std::cos(theta)}));
        }
    }
    const glm::vec3 top = frame.point({0.0f, 0.0f, length + radius});
    const glm::vec3 bottom = frame.point({0.0f, 0.0f, -radius});
    rings(points, slices, &top, &bottom, false, material_index);
}

void MeshBuilder::frustum(const Frame& frame, float height, float bottom_radius, float top_radius, int slices,
                          int segments, std::uint32_t material_index) {
    std::vector<glm::vec3> points;
    const bool pointed = top_radius <= 0.0f;
    for (int level = pointed ? 1 : 0; level <= segments; ++level) {
        const float f = 1.0f - static_cast<float>(level) / static_cast<float>(segments);
        const float radius = bottom_radius + (top_radius - bottom_radius) * f;
        for (int slice = 0; slice < slices; ++slice) {
            const float phi = angle_of(slice, slices);
            points.push_back(frame.point({radius * std::cos(phi), radius * std::sin(phi), height * f}));
        }
    }
    const glm::vec3 top = frame.point({0.0f, 0.0f, height});
    const glm::vec3 bottom = frame.origin;
    rings(points, slices, &top, &bottom, false, material_index);
}

void MeshBuilder::torus(const Frame& frame, float major_radius, float minor_radius, int major, int minor,
                        std::uint32_t material_index) {
    std::vector<glm::vec3> points;
    for (int i = 0; i < major; ++i) {
        const float alpha = angle_of(i, major);
        const glm::vec3 radial(std::cos(alpha), std::sin(alpha), 0.0f);
        for (int j = 0; j < minor; ++j) {
            const float beta = angle_of(j, minor);
            const glm::vec3 local = radial * (major_radius + minor_radius * std::cos(beta)) +
                                    glm::vec3(0.0f, 0.0f, minor_radius * std::sin(beta));
            points.push_back(frame.point(local));
        }
    }
    rings(points, minor, nullptr, nullptr, true, material_index);
}

void MeshBuilder::tube(const std::vector<glm::vec3>& path, const std::vector<float>& radii, int slices,
                       std::uint32_t material_index) {
    std::vector<glm::vec3> points;
    const std::size_t n = path.size();
    glm::vec3 normal{0.0f};
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 tangent = glm::normalize(path[std::min(i + 1, n - 1)] - path[i > 0 ? i - 1 : 0]);
        if (i == 0) {
            normal = frame_along(path[0], tangent).axes[0];
        } else {
            // Parallel transport: keep the previous normal, minus its
            // component along the new tangent, so the tube does not twist.
            normal = glm::normalize(normal - glm::dot(normal, tangent) * tangent);
        }
        const glm::vec3 binormal = glm::cross(normal, tangent);
        for (int slice = 0; slice < slices; ++slice) {
            const float phi = angle_of(slice, slices);
            points.push_back(path[i] + radii[i] * (std::cos(phi) * normal + std::sin(phi) * binormal));
        }
    }
    rings(points, slices, &path.front(), &path.back(), false, material_index);
}

void MeshBuilder::grid(const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v, int nu, int nv,
                       std::uint32_t material_index) {
    parametric_grid(nu, nv, material_index, [&](float fu, float fv) { return corner + fu * u + fv * v; });
}

void MeshBuilder::chessboard(const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v, int squares,
                             int cells, std::uint32_t first, std::uint32_t second) {
    const float step = 1.0f / static_cast<float>(squares);
    for (int j = 0; j < squares; ++j) {
        for (int i = 0; i < squares; ++i) {
            const glm::vec3 square_corner =
                corner + static_cast<float>(i) * step * u + static_cast<float>(j) * step * v;
            grid(square_corner, step * u, step * v, cells, cells, (i + j) % 2 == 0 ? first : second);
        }
    }
}

void MeshBuilder::surface(int nu, int nv, const std::function<glm::vec3(float, float)>& point_at,
                          std::uint32_t material_index) {
    parametric_grid(nu, nv, material_index, point_at);
}

void MeshBuilder::heightfield(float x0, float x1, float z0, float z1, int nx, int nz,
                              const std::function<float(float, float)>& height, std::uint32_t material_index) {
    parametric_grid(nx, nz, material_index, [&](float fu, float fv) {
        const float x = x0 + (x1 - x0) * fu;
        const float z = z1 + (z0 - z1) * fv;  // v runs towards -z so the normal is +y
        return glm::vec3(x, height(x, z), z);
    });
}

void MeshBuilder::box(const glm::vec3& center, const glm::vec3& half, float yaw, int subdivisions,
                      std::uint32_t material_index) {
    const glm::mat3 turn = rotation({0.0f, 1.0f, 0.0f}, yaw);
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            const int a1 = (axis + 1) % 3;
            const int a2 = (axis + 2) % 3;
            glm::vec3 normal(0.0f), u(0.0f), v(0.0f);
            normal[axis] = sign * half[axis];
            // cross(e_a1, e_a2) = e_axis: swap u and v on the negative face.
            if (sign > 0.0f) {
                u[a1] = 2.0f * half[a1];
                v[a2] = 2.0f * half[a2];
            } else {
                u[a2] = 2.0f * half[a2];
                v[a1] = 2.0f * half[a1];
            }
            const glm::vec3 corner = normal - 0.5f * u - 0.5f * v;
            grid(center + turn * corner, turn * u, turn * v, subdivisions, subdivisions, material_index);
        }
    }
}

void MeshBuilder::translate(std::uint32_t first_vertex, std::uint32_t end_vertex, const glm::vec3& open_offset,
                            const glm::vec3& close_offset) {
    for (std::uint32_t i = first_vertex; i < end_vertex; ++i) {
        const glm::vec3 modelled = scene_.position_open[i];
        scene_.position_open[i] = modelled + open_offset;
        scene_.position_close[i] = modelled + close_offset;
    }
}

}  // namespace blurcull::frontend::builtin
