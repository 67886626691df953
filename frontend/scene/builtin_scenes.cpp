#include "scene/builtin_scenes.hpp"

#include "scene/scene_checks.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

namespace blurcull::frontend {

namespace {

constexpr float kPi = 3.14159265358979f;

// splitmix64: tiny, well mixed and the same on every platform and library
// version (std:: distributions are not), so the scenes are reproducible.
class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}

    std::uint64_t next() {
        state_ += 0x9E3779B97F4A7C15ull;
        std::uint64_t z = state_;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // 24 random bits: every value is exactly representable in [0, 1).
    float unit() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
    float uniform(float low, float high) { return low + (high - low) * unit(); }

private:
    std::uint64_t state_;
};

glm::mat3 rotation(const glm::vec3& axis, float angle) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), angle, glm::normalize(axis)));
}

// Origin plus right-handed orthonormal axes (the columns).
struct Frame {
    glm::vec3 origin{0.0f};
    glm::mat3 axes{1.0f};
    glm::vec3 point(const glm::vec3& local) const { return origin + axes * local; }
};

// A frame whose local +z points along `direction`.
Frame frame_along(const glm::vec3& origin, const glm::vec3& direction) {
    const glm::vec3 z = glm::normalize(direction);
    const glm::vec3 helper = std::abs(z.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f)
                                                  : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 x = glm::normalize(glm::cross(helper, z));
    const glm::vec3 y = glm::cross(z, x);
    return {origin, glm::mat3(x, y, z)};
}

// Local y -> world -z and local z -> world up, for shapes whose "vertical"
// axis is local z (superellipsoids, frustums).
Frame upright(const glm::vec3& origin) {
    return {origin, glm::mat3(glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f),
                              glm::vec3(0.0f, 1.0f, 0.0f))};
}

float signed_power(float value, float exponent) {
    return std::copysign(std::pow(std::abs(value), exponent), value);
}

float angle_of(int index, int count) {
    return 2.0f * kPi * static_cast<float>(index) / static_cast<float>(count);
}

// Appends vertices, triangles and materials to a Scene. Every vertex starts
// static (close == open); motion is applied afterwards to vertex ranges.
class MeshBuilder {
public:
    explicit MeshBuilder(Scene& scene) : scene_(scene) {}

    std::uint32_t material(const glm::vec3& color, const std::string& name) {
        scene_.materials.push_back(Material{color, name});
        return static_cast<std::uint32_t>(scene_.materials.size() - 1);
    }

    std::uint32_t vertex_count() const {
        return static_cast<std::uint32_t>(scene_.position_open.size());
    }

    std::uint32_t vertex(const glm::vec3& position) {
        scene_.position_open.push_back(position);
        scene_.position_close.push_back(position);
        return vertex_count() - 1;
    }

    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t material_index) {
        scene_.triangles.emplace_back(a, b, c);
        scene_.triangle_material.push_back(material_index);
    }

    // `points` holds ring_count rings of ring_size points, ring after ring,
    // ordered from the end nearest `first_pole` to the end nearest
    // `last_pole`, each ring counter-clockwise seen from the first pole.
    // Consecutive rings are joined by quads, the poles close the ends with
    // fans, and close_loop joins the last ring back to the first (a torus).
    void rings(const std::vector<glm::vec3>& points, int ring_size, const glm::vec3* first_pole,
               const glm::vec3* last_pole, bool close_loop, std::uint32_t material_index) {
        const int ring_count = static_cast<int>(points.size()) / ring_size;
        const std::uint32_t base = vertex_count();
        for (const glm::vec3& p : points) vertex(p);
        auto at = [&](int ring, int slot) {
            return base + static_cast<std::uint32_t>((ring % ring_count) * ring_size +
                                                     slot % ring_size);
        };
        const int joined = close_loop ? ring_count : ring_count - 1;
        for (int ring = 0; ring < joined; ++ring) {
            for (int slot = 0; slot < ring_size; ++slot) {
                triangle(at(ring, slot), at(ring + 1, slot), at(ring, slot + 1), material_index);
                triangle(at(ring, slot + 1), at(ring + 1, slot), at(ring + 1, slot + 1),
                         material_index);
            }
        }
        if (first_pole != nullptr) {
            const std::uint32_t pole = vertex(*first_pole);
            for (int slot = 0; slot < ring_size; ++slot) {
                triangle(pole, at(0, slot), at(0, slot + 1), material_index);
            }
        }
        if (last_pole != nullptr) {
            const std::uint32_t pole = vertex(*last_pole);
            for (int slot = 0; slot < ring_size; ++slot) {
                triangle(pole, at(ring_count - 1, slot + 1), at(ring_count - 1, slot),
                         material_index);
            }
        }
    }

    // 2 * slices * (stacks - 1) triangles; local z is the polar axis.
    void ellipsoid(const Frame& frame, const glm::vec3& radii, int slices, int stacks,
                   std::uint32_t material_index) {
        superellipsoid(frame, radii, 1.0f, 1.0f, slices, stacks, material_index);
    }

    // Barr's superellipsoid: exponents below 1 make it boxy (car bodies,
    // palms). `vertical` shapes the profile along local z, `horizontal` the
    // cross-section. 2 * slices * (stacks - 1) triangles.
    void superellipsoid(const Frame& frame, const glm::vec3& radii, float vertical,
                        float horizontal, int slices, int stacks, std::uint32_t material_index) {
        std::vector<glm::vec3> points;
        for (int stack = 1; stack < stacks; ++stack) {
            const float eta = 0.5f * kPi - kPi * static_cast<float>(stack) / static_cast<float>(stacks);
            const float around = signed_power(std::cos(eta), vertical);
            const float height = signed_power(std::sin(eta), vertical);
            for (int slice = 0; slice < slices; ++slice) {
                const float omega = angle_of(slice, slices);
                points.push_back(frame.point(
                    radii * glm::vec3(around * signed_power(std::cos(omega), horizontal),
                                      around * signed_power(std::sin(omega), horizontal), height)));
            }
        }
        const glm::vec3 top = frame.point({0.0f, 0.0f, radii.z});
        const glm::vec3 bottom = frame.point({0.0f, 0.0f, -radii.z});
        rings(points, slices, &top, &bottom, false, material_index);
    }

    // Cylinder from a to b with hemispherical ends: 4 * slices * half_stacks triangles.
    void capsule(const glm::vec3& a, const glm::vec3& b, float radius, int slices, int half_stacks,
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

    // Truncated cone standing on frame.origin along local z, flat caps; a
    // zero top radius makes a pointed cone. 2 * slices * (segments + 1)
    // triangles (2 * slices * segments for a cone).
    void frustum(const Frame& frame, float height, float bottom_radius, float top_radius,
                 int slices, int segments, std::uint32_t material_index) {
        std::vector<glm::vec3> points;
        const bool pointed = top_radius <= 0.0f;
        for (int level = pointed ? 1 : 0; level <= segments; ++level) {
            const float f = 1.0f - static_cast<float>(level) / static_cast<float>(segments);
            const float radius = bottom_radius + (top_radius - bottom_radius) * f;
            for (int slice = 0; slice < slices; ++slice) {
                const float phi = angle_of(slice, slices);
                points.push_back(
                    frame.point({radius * std::cos(phi), radius * std::sin(phi), height * f}));
            }
        }
        const glm::vec3 top = frame.point({0.0f, 0.0f, height});
        const glm::vec3 bottom = frame.origin;
        rings(points, slices, &top, &bottom, false, material_index);
    }

    // Ring torus around local z: 2 * major * minor triangles.
    void torus(const Frame& frame, float major_radius, float minor_radius, int major, int minor,
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

    // Tube through `path` with per-point radii and flat end caps:
    // 2 * slices * path.size() triangles.
    void tube(const std::vector<glm::vec3>& path, const std::vector<float>& radii, int slices,
              std::uint32_t material_index) {
        std::vector<glm::vec3> points;
        const std::size_t n = path.size();
        glm::vec3 normal{0.0f};
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 tangent =
                glm::normalize(path[std::min(i + 1, n - 1)] - path[i > 0 ? i - 1 : 0]);
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
                points.push_back(path[i] +
                                 radii[i] * (std::cos(phi) * normal + std::sin(phi) * binormal));
            }
        }
        rings(points, slices, &path.front(), &path.back(), false, material_index);
    }

    // Flat grid from corner along u and v (normal cross(u, v)): 2 * nu * nv triangles.
    void grid(const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v, int nu, int nv,
              std::uint32_t material_index) {
        heightfield_grid(nu, nv, material_index, [&](float fu, float fv) {
            return corner + fu * u + fv * v;
        });
    }

    // Terrain y = height(x, z) over [x0, x1] x [z0, z1], facing up.
    void heightfield(float x0, float x1, float z0, float z1, int nx, int nz,
                     const std::function<float(float, float)>& height, std::uint32_t material_index) {
        heightfield_grid(nx, nz, material_index, [&](float fu, float fv) {
            const float x = x0 + (x1 - x0) * fu;
            const float z = z1 + (z0 - z1) * fv;  // v runs towards -z so the normal is +y
            return glm::vec3(x, height(x, z), z);
        });
    }

    // Box with each face split into subdivisions^2 quads: 12 * subdivisions^2 triangles.
    void box(const glm::vec3& center, const glm::vec3& half, float yaw, int subdivisions,
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
                grid(center + turn * corner, turn * u, turn * v, subdivisions, subdivisions,
                     material_index);
            }
        }
    }

    // Moves vertices [first_vertex, end_vertex) by open_offset at shutter
    // open and by close_offset at shutter close.
    void translate(std::uint32_t first_vertex, std::uint32_t end_vertex,
                   const glm::vec3& open_offset, const glm::vec3& close_offset) {
        for (std::uint32_t i = first_vertex; i < end_vertex; ++i) {
            const glm::vec3 modelled = scene_.position_open[i];
            scene_.position_open[i] = modelled + open_offset;
            scene_.position_close[i] = modelled + close_offset;
        }
    }

private:
    template <typename PointAt>
    void heightfield_grid(int nu, int nv, std::uint32_t material_index, PointAt point_at) {
        const std::uint32_t base = vertex_count();
        for (int j = 0; j <= nv; ++j) {
            for (int i = 0; i <= nu; ++i) {
                vertex(point_at(static_cast<float>(i) / static_cast<float>(nu),
                                static_cast<float>(j) / static_cast<float>(nv)));
            }
        }
        const auto row = static_cast<std::uint32_t>(nu + 1);
        for (int j = 0; j < nv; ++j) {
            for (int i = 0; i < nu; ++i) {
                const std::uint32_t a = base + static_cast<std::uint32_t>(j) * row +
                                        static_cast<std::uint32_t>(i);
                triangle(a, a + 1, a + row + 1, material_index);
                triangle(a, a + row + 1, a + row, material_index);
            }
        }
    }

    Scene& scene_;
};

// Smallest yfov that shows every vertex in [first, end) at mid-shutter from
// `view`, widened by `margin`; accounts for the aspect ratio. Mid-shutter
// positions keep the framing the same for every blur_scale.
float framing_yfov(const Scene& scene, const glm::mat4& view, std::uint32_t first,
                   std::uint32_t end, float aspect, float margin) {
    float extent = 0.05f;
    for (std::uint32_t i = first; i < end; ++i) {
        const glm::vec3 middle = 0.5f * (scene.position_open[i] + scene.position_close[i]);
        const glm::vec4 q = view * glm::vec4(middle, 1.0f);
        const float depth = -q.z;
        if (depth <= 1e-3f) continue;
        extent = std::max({extent, std::abs(q.y) / depth, std::abs(q.x) / (depth * aspect)});
    }
    return std::clamp(2.0f * std::atan(extent * margin), 0.15f, 2.2f);
}

// The camera at close: eye moved by `eye_offset`, orientation turned by
// `angle` about the world-space `axis` through the eye.
glm::mat4 moved_view(const glm::mat4& view_open, const glm::vec3& eye_offset,
                     const glm::vec3& axis, float angle) {
    if (eye_offset == glm::vec3(0.0f) && angle == 0.0f) return view_open;  // exactly static
    const glm::mat4 camera_to_world = glm::inverse(view_open);
    const glm::vec3 eye(camera_to_world[3]);
    const glm::mat4 turned = glm::translate(glm::mat4(1.0f), eye + eye_offset) *
                             glm::rotate(glm::mat4(1.0f), angle, glm::normalize(axis)) *
                             glm::translate(glm::mat4(1.0f), -eye) * camera_to_world;
    return glm::inverse(turned);
}

const glm::vec3 kUp(0.0f, 1.0f, 0.0f);

// ---------------------------------------------------------------------------
// hand: ~15k triangles, static, defocus only. Fingers recede from the camera
// and the focus sits on the middle finger, so the wrist is in front of the
// focus plane and the fingertips behind it.
Scene make_hand(float blur, float aspect) {
    Scene scene;
    scene.name = "hand";
    MeshBuilder mesh(scene);
    const std::uint32_t skin = mesh.material({0.87f, 0.64f, 0.52f}, "skin");
    const std::uint32_t nail = mesh.material({0.96f, 0.84f, 0.80f}, "nail");
    const std::uint32_t sleeve = mesh.material({0.20f, 0.32f, 0.58f}, "sleeve");
    const std::uint32_t wall = mesh.material({0.55f, 0.58f, 0.52f}, "wall");

    // Hand space: fingers along +y, palm facing +z, thumb towards -x; tilted
    // so the fingers point up and away from the camera.
    const glm::mat3 tilt = rotation({1.0f, 0.0f, 0.0f}, -0.87f);
    const Frame hand{glm::vec3(0.0f), tilt};
    const std::uint32_t hand_first = mesh.vertex_count();

    mesh.superellipsoid(hand, {0.48f, 0.55f, 0.15f}, 0.6f, 0.5f, 64, 32, skin);

    struct Finger {
        glm::vec3 base;
        glm::vec3 direction;
        float lengths[3];
        float radius;
        float curl;
    };
    const Finger fingers[5] = {
        {{-0.33f, 0.50f, 0.0f}, {-0.08f, 1.0f, 0.0f}, {0.42f, 0.26f, 0.20f}, 0.085f, 0.20f},
        {{-0.11f, 0.54f, 0.0f}, {0.00f, 1.0f, 0.0f}, {0.46f, 0.29f, 0.22f}, 0.090f, 0.16f},
        {{0.11f, 0.51f, 0.0f}, {0.06f, 1.0f, 0.0f}, {0.43f, 0.27f, 0.21f}, 0.085f, 0.22f},
        {{0.32f, 0.44f, 0.0f}, {0.14f, 1.0f, 0.0f}, {0.34f, 0.21f, 0.18f}, 0.072f, 0.28f},
        {{-0.46f, -0.12f, 0.06f}, {-0.75f, 0.62f, 0.30f}, {0.36f, 0.28f, 0.22f}, 0.100f, 0.18f},
    };
    glm::vec3 middle_finger_focus{0.0f};
    for (int f = 0; f < 5; ++f) {
        const Finger& finger = fingers[f];
        glm::vec3 start = finger.base;
        glm::vec3 direction = glm::normalize(finger.direction);
        float radius = finger.radius;
        if (f == 4) {
            // The thumb's metacarpal runs inside the palm to its base.
            mesh.capsule(hand.point({-0.25f, -0.35f, 0.0f}), hand.point(start), 0.13f, 22, 5, skin);
        }
        for (int joint = 0; joint < 3; ++joint) {
            const glm::vec3 curl_axis = glm::normalize(glm::cross(direction, glm::vec3(0, 0, 1)));
            direction = rotation(curl_axis, finger.curl * static_cast<float>(joint + 1) * 0.6f) * direction;
            const glm::vec3 end = start + direction * finger.lengths[joint];
            mesh.capsule(hand.point(start), hand.point(end), radius, 22, 5, skin);
            if (f == 1 && joint == 0) middle_finger_focus = hand.point(0.5f * (start + end));
            if (joint == 2) {
                const glm::vec3 back = glm::normalize(glm::cross(direction, curl_axis));
                const glm::vec3 center = end - direction * (finger.lengths[joint] * 0.35f) +
                                         back * (radius * 0.78f);
                const Frame nail_frame{hand.point(center),
                                       tilt * glm::mat3(-curl_axis, direction, back)};
                mesh.ellipsoid(nail_frame, {radius * 0.7f, finger.lengths[joint] * 0.32f, radius * 0.25f},
                               16, 8, nail);
            }
            start = end;
            radius *= 0.92f;
        }
    }
    // Framing covers palm and fingers; the forearm may run out of the image.
    const std::uint32_t hand_end = mesh.vertex_count();
    mesh.capsule(hand.point({0.0f, -0.40f, 0.0f}), hand.point({0.0f, -1.8f, 0.0f}), 0.30f, 32, 6, skin);
    mesh.capsule(hand.point({0.0f, -1.35f, 0.0f}), hand.point({0.0f, -2.8f, 0.0f}), 0.38f, 32, 6, sleeve);
    // A wall behind the hand, far from the focus plane: a blurred backdrop.
    mesh.grid({-8.0f, -6.0f, -2.8f}, {16.0f, 0.0f, 0.0f}, {0.0f, 13.0f, 0.0f}, 22, 22, wall);

    // Aim at the middle of palm and fingers; focus on the middle finger.
    const glm::vec3 hand_center = hand.point({-0.05f, 0.45f, 0.0f});
    const glm::vec3 eye = hand_center + glm::vec3(0.35f, 0.55f, 3.3f);
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(eye, hand_center, kUp);
    camera.view_close = camera.view_open;
    camera.yfov = framing_yfov(scene, camera.view_open, hand_first, hand_end, aspect, 1.15f);
    camera.znear = 0.05f;
    camera.focus_distance = -(camera.view_open * glm::vec4(middle_finger_focus, 1.0f)).z;
    camera.lens_radius = 0.07f * blur;
    scene.light_direction = glm::normalize(glm::vec3(0.4f, 0.8f, 0.6f));
    scene.background = {0.10f, 0.10f, 0.12f};
    return scene;
}

// ---------------------------------------------------------------------------
// car: ~54k triangles, object motion only. The car drives sideways across
// the view; the street, kerbs and buildings stay put.
Scene make_car(float blur, float aspect) {
    Scene scene;
    scene.name = "car";
    MeshBuilder mesh(scene);
    const std::uint32_t paint = mesh.material({0.78f, 0.10f, 0.08f}, "paint");
    const std::uint32_t glass = mesh.material({0.12f, 0.18f, 0.26f}, "glass");
    const std::uint32_t rubber = mesh.material({0.06f, 0.06f, 0.06f}, "tyre");
    const std::uint32_t chrome = mesh.material({0.75f, 0.76f, 0.78f}, "chrome");
    const std::uint32_t lamp = mesh.material({0.98f, 0.92f, 0.60f}, "lamp");
    const std::uint32_t asphalt = mesh.material({0.22f, 0.22f, 0.24f}, "asphalt");
    const std::uint32_t pavement = mesh.material({0.55f, 0.53f, 0.50f}, "pavement");
    const std::uint32_t brick = mesh.material({0.62f, 0.42f, 0.30f}, "building");

    const std::uint32_t car_first = mesh.vertex_count();
    mesh.superellipsoid(upright({0.0f, 0.66f, 0.0f}), {2.2f, 0.90f, 0.38f}, 0.30f, 0.30f, 160, 56,
                        paint);
    mesh.superellipsoid(upright({-0.25f, 1.10f, 0.0f}), {1.25f, 0.78f, 0.34f}, 0.45f, 0.40f, 128, 40,
                        glass);
    for (float x : {-1.35f, 1.35f}) {
        for (float z : {-0.80f, 0.80f}) {
            // Wheels turn about the z axis (the axle).
            const Frame wheel{{x, 0.37f, z}, glm::mat3(1.0f)};
            mesh.torus(wheel, 0.26f, 0.11f, 72, 24, rubber);
            const Frame hub{{x, 0.37f, z + (z > 0.0f ? 0.06f : -0.06f)}, glm::mat3(1.0f)};
            mesh.ellipsoid(hub, {0.19f, 0.19f, 0.06f}, 32, 16, chrome);
        }
    }
    for (float z : {-0.62f, 0.62f}) {
        mesh.ellipsoid(frame_along({2.17f, 0.78f, z}, {1.0f, 0.0f, 0.0f}), {0.16f, 0.10f, 0.06f}, 24, 12, lamp);
        mesh.ellipsoid(frame_along({-2.17f, 0.78f, z}, {-1.0f, 0.0f, 0.0f}), {0.14f, 0.08f, 0.05f}, 24, 12, lamp);
    }
    mesh.capsule({2.22f, 0.42f, -0.78f}, {2.22f, 0.42f, 0.78f}, 0.08f, 24, 6, chrome);
    mesh.capsule({-2.22f, 0.42f, -0.78f}, {-2.22f, 0.42f, 0.78f}, 0.08f, 24, 6, chrome);
    const std::uint32_t car_end = mesh.vertex_count();

    auto flat = [](float, float) { return 0.0f; };
    mesh.heightfield(-40.0f, 40.0f, -4.0f, 4.0f, 64, 8, flat, asphalt);
    auto kerb = [](float, float) { return 0.12f; };
    mesh.heightfield(-40.0f, 40.0f, 4.0f, 16.0f, 64, 10, kerb, pavement);
    mesh.heightfield(-40.0f, 40.0f, -16.0f, -4.0f, 64, 10, kerb, pavement);
    Random random(0xCA5ull);
    for (float x = -34.0f; x < 34.0f;) {
        const float width = random.uniform(3.0f, 7.0f);
        const float height = random.uniform(3.0f, 12.0f);
        const float depth = random.uniform(3.0f, 6.0f);
        mesh.box({x + 0.5f * width, 0.12f + 0.5f * height, -8.0f - 0.5f * depth},
                 {0.5f * width - 0.1f, 0.5f * height, 0.5f * depth}, random.uniform(-0.05f, 0.05f),
                 3, brick);
        x += width;
    }

    // 0.45 m during the shutter (about 6% of the image width here), centred
    // on the modelled position so the framing does not depend on blur_scale.
    const glm::vec3 travel(0.45f * blur, 0.0f, 0.0f);
    mesh.translate(car_first, car_end, -0.5f * travel, 0.5f * travel);

    const glm::vec3 eye(1.8f, 1.6f, 8.5f);
    const glm::vec3 target(0.1f, 0.8f, 0.0f);
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(eye, target, kUp);
    camera.view_close = camera.view_open;
    camera.yfov = framing_yfov(scene, camera.view_open, car_first, car_end, aspect, 1.4f);
    camera.znear = 0.1f;
    camera.focus_distance = glm::length(target - eye);
    camera.lens_radius = 0.0f;
    scene.light_direction = glm::normalize(glm::vec3(-0.3f, 0.9f, 0.4f));
    scene.background = {0.55f, 0.70f, 0.90f};
    return scene;
}

// ---------------------------------------------------------------------------
// dragonfly: ~85k triangles (centimetres), camera motion only: the camera
// slides and turns a little while the insect sits still on a plant.
Scene make_dragonfly(float blur, float aspect) {
    Scene scene;
    scene.name = "dragonfly";
    MeshBuilder mesh(scene);
    const std::uint32_t body = mesh.material({0.10f, 0.45f, 0.55f}, "body");
    const std::uint32_t eyes = mesh.material({0.35f, 0.12f, 0.08f}, "eyes");
    const std::uint32_t wing = mesh.material({0.80f, 0.86f, 0.90f}, "wing");
    const std::uint32_t legs = mesh.material({0.08f, 0.08f, 0.08f}, "legs");
    const std::uint32_t plant = mesh.material({0.25f, 0.55f, 0.20f}, "plant");
    const std::uint32_t soil = mesh.material({0.40f, 0.33f, 0.22f}, "soil");

    const glm::vec3 origin(0.0f, 12.0f, 0.0f);  // where thorax meets abdomen
    const std::uint32_t insect_first = mesh.vertex_count();
    const glm::vec3 head = origin + glm::vec3(2.25f, 0.15f, 0.0f);
    mesh.ellipsoid(frame_along(head, {1.0f, 0.0f, 0.0f}), {0.45f, 0.45f, 0.40f}, 48, 24, body);
    for (float side : {-1.0f, 1.0f}) {
        mesh.ellipsoid(frame_along(head + glm::vec3(0.22f, 0.18f, 0.36f * side), {0.0f, 0.0f, side}),
                       {0.40f, 0.42f, 0.36f}, 64, 32, eyes);
    }
    mesh.ellipsoid(frame_along(origin + glm::vec3(0.95f, 0.0f, 0.0f), {1.0f, 0.0f, 0.0f}),
                   {0.50f, 0.55f, 0.95f}, 64, 32, body);
    for (int segment = 0; segment < 10; ++segment) {
        const float s = static_cast<float>(segment);
        const glm::vec3 center = origin + glm::vec3(-0.30f - 0.62f * s, -0.012f * s * s, 0.0f);
        const float thickness = 0.24f - 0.008f * s;
        mesh.ellipsoid(frame_along(center, {-1.0f, -0.02f * s, 0.0f}), {thickness, thickness, 0.36f},
                       48, 24, body);
    }
    for (float along : {0.55f, 1.25f}) {
        for (float side : {-1.0f, 1.0f}) {
            const glm::vec3 root = origin + glm::vec3(along, 0.48f, 0.22f * side);
            const float span = along > 1.0f ? 2.9f : 2.7f;
            const float sweep = along > 1.0f ? 0.10f : -0.12f;
            // Span along +-z, chord along x, a hair of thickness along y.
            const glm::vec3 span_direction =
                glm::normalize(glm::vec3(sweep * side, 0.04f, side));
            const glm::vec3 chord = glm::normalize(glm::cross(kUp, span_direction));
            const Frame frame{root + span_direction * span,
                              glm::mat3(chord, glm::cross(span_direction, chord), span_direction)};
            mesh.ellipsoid(frame, {0.42f, 0.025f, span}, 96, 48, wing);
        }
    }
    for (int pair = 0; pair < 3; ++pair) {
        for (float side : {-1.0f, 1.0f}) {
            const float x = 0.55f + 0.35f * static_cast<float>(pair);
            const glm::vec3 hip = origin + glm::vec3(x, -0.35f, 0.18f * side);
            const glm::vec3 knee = origin + glm::vec3(x + 0.25f, -0.75f, 0.65f * side);
            const glm::vec3 foot = origin + glm::vec3(0.95f + 0.15f * static_cast<float>(pair - 1),
                                                      -1.05f, 0.22f * side);
            mesh.capsule(hip, knee, 0.05f, 12, 3, legs);
            mesh.capsule(knee, foot, 0.04f, 12, 3, legs);
        }
    }
    const std::uint32_t insect_end = mesh.vertex_count();

    // The stem ends just under the thorax, where the feet grip it.
    std::vector<glm::vec3> stem;
    std::vector<float> stem_radii;
    for (int i = 0; i <= 24; ++i) {
        const float f = static_cast<float>(i) / 24.0f;
        stem.push_back({0.95f * f * f + 0.4f * std::sin(3.0f * f), 10.9f * f, 0.3f * std::sin(2.0f * f)});
        stem_radii.push_back(0.22f - 0.08f * f);
    }
    mesh.tube(stem, stem_radii, 20, plant);
    for (int leaf = 0; leaf < 3; ++leaf) {
        const float f = 0.25f + 0.2f * static_cast<float>(leaf);
        const glm::vec3 attach = stem[static_cast<std::size_t>(f * 24.0f)];
        const float turn = 2.1f * static_cast<float>(leaf);
        const glm::vec3 out(std::cos(turn), 0.55f, std::sin(turn));
        const glm::vec3 span = glm::normalize(out);
        const Frame frame = frame_along(attach + span * 2.2f, span);
        mesh.ellipsoid(frame, {0.7f, 0.05f, 2.2f}, 48, 24, plant);
    }
    mesh.heightfield(-40.0f, 40.0f, -40.0f, 40.0f, 40, 40,
                     [](float x, float z) { return 0.4f * std::sin(0.2f * x) * std::cos(0.17f * z); },
                     soil);

    const glm::vec3 target = origin + glm::vec3(0.0f, -0.3f, 0.0f);
    const glm::vec3 eye = target + glm::vec3(5.0f, 6.5f, 13.0f);
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(eye, target, kUp);
    // A sideways slide of ~0.45 cm plus a 0.6 degree turn in the same sense:
    // a few percent of the image width.
    camera.view_close = moved_view(camera.view_open, glm::vec3(0.40f, -0.10f, -0.15f) * blur, kUp,
                                   0.0105f * blur);
    camera.yfov = framing_yfov(scene, camera.view_open, insect_first, insect_end, aspect, 1.25f);
    camera.znear = 0.1f;
    camera.focus_distance = glm::length(target - eye);
    camera.lens_radius = 0.0f;
    scene.light_direction = glm::normalize(glm::vec3(0.5f, 0.9f, 0.2f));
    scene.background = {0.62f, 0.75f, 0.85f};
    return scene;
}

// ---------------------------------------------------------------------------
// forest: ~170k triangles, camera motion and defocus. Trees from a metre to
// 110 m away on rolling ground that also runs behind the camera.
float forest_height(float x, float z) {
    return 0.6f * std::sin(0.08f * x) * std::cos(0.06f * z) + 0.3f * std::sin(0.21f * x + 0.13f * z);
}

Scene make_forest(float blur, float aspect) {
    Scene scene;
    scene.name = "forest";
    MeshBuilder mesh(scene);
    const std::uint32_t bark = mesh.material({0.36f, 0.25f, 0.16f}, "bark");
    const std::uint32_t pine = mesh.material({0.10f, 0.36f, 0.18f}, "pine");
    const std::uint32_t leaves = mesh.material({0.38f, 0.58f, 0.18f}, "leaves");
    const std::uint32_t grass = mesh.material({0.30f, 0.45f, 0.20f}, "grass");

    mesh.heightfield(-70.0f, 70.0f, -120.0f, 15.0f, 96, 90, forest_height, grass);

    Random random(0xF0257ull);
    std::vector<glm::vec2> placed;
    const int tree_target = 236;
    for (int attempt = 0; attempt < 20000 && static_cast<int>(placed.size()) < tree_target; ++attempt) {
        const float depth = random.uniform(2.0f, 110.0f);
        const float half_width = 0.8f * depth + 3.0f;
        const glm::vec2 spot(random.uniform(-half_width, half_width), -depth);
        if (glm::length(spot) < 5.0f) continue;
        bool crowded = false;
        for (const glm::vec2& other : placed) {
            if (glm::length(other - spot) < 2.0f) {
                crowded = true;
                break;
            }
        }
        if (crowded) continue;
        placed.push_back(spot);
        const float height = random.uniform(4.0f, 11.0f);
        const glm::vec3 root(spot.x, forest_height(spot.x, spot.y) - 0.2f, spot.y);
        const bool conifer = random.unit() < 0.6f;
        const float trunk_height = (conifer ? 0.35f : 0.5f) * height;
        const float trunk_radius = 0.025f * height;
        mesh.frustum(upright(root), trunk_height + 0.3f, trunk_radius, 0.5f * trunk_radius, 10, 2, bark);
        if (conifer) {
            for (int tier = 0; tier < 3; ++tier) {
                const float t = static_cast<float>(tier);
                const float base = trunk_height * 0.8f + t * 0.2f * height;
                const float tier_height = (0.45f - 0.08f * t) * height;
                mesh.frustum(upright(root + glm::vec3(0.0f, base, 0.0f)), tier_height,
                             (0.22f - 0.05f * t) * height, 0.0f, 20, 4, pine);
            }
        } else {
            const glm::vec3 crown = root + glm::vec3(0.0f, trunk_height + 0.3f * height, 0.0f);
            mesh.ellipsoid(upright(crown), {0.30f * height, 0.27f * height, 0.36f * height}, 28, 14, leaves);
        }
    }

    const glm::vec3 eye(0.0f, forest_height(0.0f, 0.0f) + 2.2f, 0.0f);
    const glm::vec3 target(0.0f, 2.4f, -20.0f);
    Camera& camera = scene.camera;
    camera.view_open = glm::lookAt(eye, target, kUp);
    // Walking forward-right while turning ~0.7 degrees.
    camera.view_close = moved_view(camera.view_open, glm::vec3(0.30f, 0.0f, -0.40f) * blur, kUp,
                                   -0.012f * blur);
    // A fixed ~69 degree horizontal field of view, whatever the aspect.
    camera.yfov = 2.0f * std::atan(std::tan(0.6f) / aspect);
    camera.znear = 0.1f;
    camera.focus_distance = 12.0f;
    camera.lens_radius = 0.035f * blur;
    scene.light_direction = glm::normalize(glm::vec3(-0.4f, 0.8f, 0.3f));
    scene.background = {0.70f, 0.80f, 0.92f};
    return scene;
}

}  // namespace

std::vector<std::string> builtin_scene_names() { return {"hand", "car", "dragonfly", "forest"}; }

Scene make_builtin_scene(const std::string& name, const SceneOptions& options) {
    if (!std::isfinite(options.blur_scale) || options.blur_scale < 0.0f) {
        throw SceneError("scene '" + name + "': blur scale " + std::to_string(options.blur_scale) +
                         " must be finite and non-negative");
    }
    if (!std::isfinite(options.aspect) || !(options.aspect > 0.0f)) {
        throw SceneError("scene '" + name + "': aspect " + std::to_string(options.aspect) +
                         " must be finite and positive");
    }
    Scene scene;
    if (name == "hand") {
        scene = make_hand(options.blur_scale, options.aspect);
    } else if (name == "car") {
        scene = make_car(options.blur_scale, options.aspect);
    } else if (name == "dragonfly") {
        scene = make_dragonfly(options.blur_scale, options.aspect);
    } else if (name == "forest") {
        scene = make_forest(options.blur_scale, options.aspect);
    } else {
        std::string known;
        for (const std::string& candidate : builtin_scene_names()) {
            known += (known.empty() ? "" : ", ") + candidate;
        }
        throw SceneError("unknown scene '" + name + "' (known: " + known + ")");
    }
    validate_scene(scene);
    return scene;
}

Scene make_mostly_static(const Scene& source, int moving_every) {
    if (moving_every < 1) throw SceneError("mostly static scene: moving_every must be >= 1");
    Scene scene = source;
    scene.position_open.clear();
    scene.position_close.clear();
    scene.camera.lens_radius = 0.0f;
    scene.camera.view_close = scene.camera.view_open;
    // The world point the still camera sees where the moving one saw p at
    // close; none when the camera does not move (an inverse times the same
    // matrix would move every point by its rounding).
    const bool camera_moves = source.camera.view_open != source.camera.view_close;
    const glm::mat4 close_motion =
        camera_moves ? glm::inverse(source.camera.view_open) * source.camera.view_close : glm::mat4(1.0f);
    for (std::size_t t = 0; t < source.triangles.size(); ++t) {
        const bool moves = t % static_cast<std::size_t>(moving_every) == 0;
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t v = source.triangles[t][i];
            scene.position_open.push_back(source.position_open[v]);
            const glm::vec3 close =
                camera_moves ? glm::vec3(close_motion * glm::vec4(source.position_close[v], 1.0f)) : source.position_close[v];
            scene.position_close.push_back(moves ? close : source.position_open[v]);
            scene.triangles[t][i] = static_cast<std::uint32_t>(3 * t + static_cast<std::size_t>(i));
        }
    }
    return scene;
}

}  // namespace blurcull::frontend
