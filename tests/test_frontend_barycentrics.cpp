// The exact coverage test's hit barycentrics (kernel::covers_hit) against an
// independent intersection: Moller-Trumbore in double on the WORLD-space
// triangle interpolated at t, with the thin-lens ray from the lens point
// through the focus point (not the kernel's sheared clip space); and the
// GLSL bc_covers_hit against kernel<float> bit for bit on llvmpipe.
#include "gl_parity_helpers.hpp"

#include "render/common/camera_model.hpp"
#include "render/common/moving_triangle.hpp"
#include "render/gl/gl_functions.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <vector>

using namespace blurcull;
using namespace blurcull::frontend;
using namespace blurcull::testing;
using Kf = blurcull::kernelf;

namespace {

struct ReferenceHit {
    bool hit = false;
    double depth = 0.0;           // view depth of the hit
    glm::dvec3 barycentric{0.0};  // (1 - b1 - b2, b1, b2)
    double margin = 0.0;          // smallest barycentric: how close to an edge
    double facing = 0.0;          // |cos| of the ray and the normal: small when seen edge-on
};

// Moller-Trumbore (1997) in double: origin + s dir = (1 - b1 - b2) a + b1 b + b2 c.
ReferenceHit moller_trumbore(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    ReferenceHit r;
    const glm::dvec3 e1 = b - a, e2 = c - a;
    const glm::dvec3 p = glm::cross(dir, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return r;
    const glm::dvec3 to_origin = origin - a;
    const double b1 = glm::dot(to_origin, p) / det;
    const glm::dvec3 q = glm::cross(to_origin, e1);
    const double b2 = glm::dot(dir, q) / det;
    const double s = glm::dot(e2, q) / det;
    r.barycentric = glm::dvec3(1.0 - b1 - b2, b1, b2);
    r.margin = std::min({r.barycentric.x, b1, b2});
    r.hit = r.margin >= 0.0 && s > 0.0;
    r.depth = -(origin.z + s * dir.z);
    r.facing = std::fabs(glm::dot(glm::normalize(glm::cross(e1, e2)), glm::normalize(dir)));
    return r;
}

// A random moving triangle in front of a camera that moves too, with a lens.
struct WorldCase {
    Scene scene;
    glm::vec2 ndc{0.0f}, lens{0.0f};
    float time = 0.0f;
};

WorldCase make_world_case(Rng& rng) {
    WorldCase c;
    Scene& s = c.scene;
    const glm::vec3 centre(static_cast<float>(rng.uniform(-1, 1)), static_cast<float>(rng.uniform(-1, 1)),
                           static_cast<float>(-rng.uniform(2, 12)));
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 p = centre + glm::vec3(static_cast<float>(rng.uniform(-2, 2)), static_cast<float>(rng.uniform(-2, 2)),
                                               static_cast<float>(rng.uniform(-1.5, 1.5)));
        const glm::vec3 motion(static_cast<float>(rng.uniform(-0.5, 0.5)), static_cast<float>(rng.uniform(-0.5, 0.5)),
                               static_cast<float>(rng.uniform(-0.5, 0.5)));
        s.position_open.push_back(p);
        s.position_close.push_back(p + motion);
    }
    s.triangles.push_back({0u, 1u, 2u});
    s.triangle_material.push_back(0u);
    s.materials.emplace_back();
    s.camera.view_open = glm::mat4(1.0f);
    s.camera.view_close = glm::translate(glm::mat4(1.0f), glm::vec3(static_cast<float>(rng.uniform(-0.2, 0.2)), 0.0f,
                                                                     static_cast<float>(rng.uniform(-0.3, 0.3))));
    s.camera.lens_radius = static_cast<float>(rng.uniform(0.0, 0.3));
    s.camera.focus_distance = static_cast<float>(rng.uniform(2, 10));
    c.ndc = glm::vec2(static_cast<float>(rng.uniform(-0.9, 0.9)), static_cast<float>(rng.uniform(-0.9, 0.9)));
    const double r = std::sqrt(rng.uniform()), phi = rng.uniform(0, 6.283185307179586);
    c.lens = glm::vec2(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)));
    c.time = static_cast<float>(rng.uniform());
    return c;
}

// The reference in view space of the world triangle at c.time (each
// vertex's world position at an end through that end's view, mixed at t),
// hit by the thin-lens ray from lens point (u R, v R, 0) through the focus
// point of the pinhole ray at c.ndc, with R and F as the float camera model
// rounded them (a = -k R, b = k R / F per axis): origin (-u a_x / k_x,
// -v a_y / k_y, 0), direction ((X - u b_x) / k_x, (Y - v b_y) / k_y, -1).
ReferenceHit reference_in_world(const WorldCase& c, const CameraModel& model) {
    glm::dvec3 v[3];
    const double t = c.time;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 open = glm::dmat4(model.view_open) * glm::dvec4(glm::dvec3(c.scene.position_open[i]), 1.0);
        const glm::dvec3 close = glm::dmat4(model.view_close) * glm::dvec4(glm::dvec3(c.scene.position_close[i]), 1.0);
        v[i] = (1.0 - t) * open + t * close;
    }
    const double u = c.lens.x, w = c.lens.y, kx = model.k_x, ky = model.k_y;
    const glm::dvec3 origin(-u * double(model.a_x) / kx, -w * double(model.a_y) / ky, 0.0);
    const glm::dvec3 direction((double(c.ndc.x) - u * double(model.b_x)) / kx, (double(c.ndc.y) - w * double(model.b_y)) / ky,
                               -1.0);
    return moller_trumbore(origin, direction, v[0], v[1], v[2]);
}

// A screen position the triangle likely covers: a random point of it at
// c.time seen through c.lens (most samples hit, some land outside the
// triangle through rounding of nothing: the point is inside).
glm::vec2 aim_at_triangle(const WorldCase& c, const CameraModel& model, Rng& rng) {
    double b1 = rng.uniform(-0.1, 1.0), b2 = rng.uniform(-0.1, 1.0);
    if (b1 + b2 > 1.1) b1 = 1.1 - b1, b2 = 1.1 - b2;
    const double b[3] = {1.0 - b1 - b2, b1, b2};
    glm::vec3 point(0.0f);
    for (int i = 0; i < 3; ++i) point += static_cast<float>(b[i]) * model.view_position_at(c.scene, static_cast<std::size_t>(i), c.time);
    return model.project(model.clip_xyw(point), c.lens);
}

template <class Real>
void check_against_world_reference(double barycentric_tolerance, double margin_floor) {
    using K = kernel<Real>;
    Rng rng(0xba7c3ull + sizeof(Real));
    int compared = 0, hits = 0;
    for (int n = 0; n < 40000; ++n) {
        WorldCase c = make_world_case(rng);
        const CameraModel model(c.scene.camera, 64, 64);
        if (n % 4 != 0) c.ndc = aim_at_triangle(c, model, rng);
        const typename K::MovingTriangle tri = make_moving_triangle<Real>(c.scene, model, 0);
        Real depth = Real(0);
        typename K::vec3 b{};
        const bool got = K::covers_hit(tri, typename K::vec2(c.ndc), typename K::vec2(c.lens), static_cast<Real>(c.time),
                                       static_cast<Real>(model.znear), depth, b);
        const ReferenceHit want = reference_in_world(c, model);
        // Within rounding of an edge either verdict is right.
        if (std::fabs(want.margin) < margin_floor) continue;
        ++compared;
        REQUIRE_MESSAGE(got == want.hit, "case " << n);
        if (!got) {
            CHECK(b == typename K::vec3(Real(0)));
            continue;
        }
        ++hits;
        const double conditioned = barycentric_tolerance / std::max(want.facing, 1e-3);
        for (int i = 0; i < 3; ++i) CHECK(std::fabs(double(b[i]) - want.barycentric[i]) < conditioned);
        CHECK(std::fabs(double(b.x) + double(b.y) + double(b.z) - 1.0) < barycentric_tolerance);
        // A triangle seen nearly edge-on has a depth as sensitive as 1 / facing.
        CHECK(double(depth) == doctest::Approx(want.depth).epsilon(conditioned));
    }
    MESSAGE(compared << " samples compared, " << hits << " hits");
    CHECK(hits > 20000);
    CHECK(compared > 35000);
}

}  // namespace

TEST_CASE("covers_hit: barycentrics of the world-space triangle at t on the thin-lens ray, double") {
    check_against_world_reference<double>(1e-9, 1e-9);
}

TEST_CASE("covers_hit: barycentrics of the world-space triangle at t on the thin-lens ray, float") {
    // The float scene's clip coordinates are rounded once: barycentrics to ~1e-4.
    check_against_world_reference<float>(2e-3, 2e-3);
}

TEST_CASE_TEMPLATE("covers_hit: same verdict and depth as covers, interpolates the vertices", Real, float, double) {
    using K = kernel<Real>;
    Rng rng(77);
    int hits = 0;
    for (int n = 0; n < 20000; ++n) {
        const Family family = static_cast<Family>(n % 12);
        const Config cfg = make_config(rng, family);
        const typename K::MovingTriangle tri = to_real<Real>(cfg.tri);
        const Sample5 smp = make_sample(rng, cfg);
        const typename K::vec2 s(smp.s), uv(smp.uv);
        const Real t = static_cast<Real>(smp.t), near = static_cast<Real>(cfg.near);
        Real depth = Real(0), hit_depth = Real(0);
        typename K::vec3 b{};
        const bool covered = K::covers(tri, s, uv, t, near, depth);
        REQUIRE(K::covers_hit(tri, s, uv, t, near, hit_depth, b) == covered);
        CHECK(std::memcmp(&depth, &hit_depth, sizeof(Real)) == 0);
        if (!covered) continue;
        ++hits;
        CHECK((b.x >= Real(0) && b.y >= Real(0) && b.z >= Real(0)));
        // b interpolates the sheared vertices to a point on the sample's ray
        // at the hit depth; checked on the well-conditioned families (the
        // adversarial ones, huge motion, tiny w, ..., make the point itself
        // ill-conditioned).
        if (family != Family::motion && family != Family::defocus && family != Family::both) continue;
        glm::dvec3 v[3], point(0.0);
        for (int i = 0; i < 3; ++i) v[i] = glm::dvec3(K::vertex_at(tri, i, t, uv));
        for (int i = 0; i < 3; ++i) point += double(b[i]) * v[i];
        const glm::dvec3 ray(double(s.x), double(s.y), 1.0);
        if (std::fabs(glm::dot(glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0])), glm::normalize(ray))) < 0.1) continue;
        double scale = 0.0;
        for (int i = 0; i < 3; ++i) scale = std::max(scale, glm::length(v[i]));
        const double tolerance = (sizeof(Real) == 4 ? 5e-3 : 1e-8) * scale + 1e-30;
        CHECK(std::fabs(point.z - double(depth)) <= tolerance);
        CHECK(std::fabs(point.x - double(s.x) * double(depth)) <= tolerance + std::fabs(double(s.x)) * tolerance);
    }
    CHECK(hits > 2000);
}

namespace {

const char* const kBarycentricMain = R"glsl(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { float values[]; };
layout(std430, binding = 1) writeonly buffer Outputs { uint results[]; };
uniform uint input_count;
void main() {
    uint n = gl_GlobalInvocationID.x;
    if (n >= input_count) return;
    uint at = n * 36u;
    MovingTriangle tri;
    for (int j = 0; j < 6; ++j) {
        tri.p[j] = vec3(values[at + 3u * uint(j)], values[at + 3u * uint(j) + 1u], values[at + 3u * uint(j) + 2u]);
        tri.c[j] = vec2(values[at + 18u + 2u * uint(j)], values[at + 19u + 2u * uint(j)]);
    }
    float depth;
    vec3 b;
    bool covered = bc_covers_hit(tri, vec2(values[at + 30u], values[at + 31u]), vec2(values[at + 32u], values[at + 33u]),
                                 values[at + 34u], values[at + 35u], depth, b);
    results[n * 5u] = covered ? 1u : 0u;
    results[n * 5u + 1u] = floatBitsToUint(depth);
    results[n * 5u + 2u] = floatBitsToUint(b.x);
    results[n * 5u + 3u] = floatBitsToUint(b.y);
    results[n * 5u + 4u] = floatBitsToUint(b.z);
}
)glsl";

}  // namespace

TEST_CASE("covers_hit in GLSL gives kernel<float>'s verdict, depth and barycentrics, bit for bit") {
    auto context = test::context_or_skip();
    if (!context) return;
    constexpr int inputs = 32768;
    Rng rng(0x5ade);
    std::vector<float> values;
    values.reserve(static_cast<std::size_t>(inputs) * 36);
    for (int n = 0; n < inputs; ++n) {
        const Config cfg = make_config(rng, static_cast<Family>(n % 12));
        const Kf::MovingTriangle tri = to_real<float>(cfg.tri);
        const Sample5 smp = make_sample(rng, cfg);
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 3; ++k) values.push_back(tri.p[j][k]);
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 2; ++k) values.push_back(tri.c[j][k]);
        for (double v : {smp.s.x, smp.s.y, smp.uv.x, smp.uv.y, smp.t, cfg.near}) values.push_back(static_cast<float>(v));
    }
    const gl::Functions& f = context->gl();
    gl::Program program(f, {{GL_COMPUTE_SHADER, {glsl::kernel_source(), kBarycentricMain}}});
    gl::Buffer input(f, GL_SHADER_STORAGE_BUFFER, values.size() * sizeof(float), values.data());
    std::vector<std::uint32_t> gpu(static_cast<std::size_t>(inputs) * 5, 0xdeadbeefu);
    gl::Buffer output(f, GL_SHADER_STORAGE_BUFFER, gpu.size() * sizeof(std::uint32_t), gpu.data());
    input.bind_base(0);
    output.bind_base(1);
    f.UseProgram(program.id());
    f.Uniform1ui(f.GetUniformLocation(program.id(), "input_count"), static_cast<std::uint32_t>(inputs));
    f.DispatchCompute((inputs + 63) / 64, 1, 1);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    f.Finish();
    gl::check_gl(f, "running the barycentric parity shader");
    output.read(gpu.data(), gpu.size() * sizeof(std::uint32_t));
    f.UseProgram(0);

    long differing = 0, covered = 0;
    for (int n = 0; n < inputs; ++n) {
        const float* in = &values[static_cast<std::size_t>(n) * 36];
        Kf::MovingTriangle tri;
        for (int j = 0; j < 6; ++j) {
            tri.p[j] = Kf::vec3(in[3 * j], in[3 * j + 1], in[3 * j + 2]);
            tri.c[j] = Kf::vec2(in[18 + 2 * j], in[19 + 2 * j]);
        }
        float depth = 0.0f;
        Kf::vec3 b{};
        const bool hit = Kf::covers_hit(tri, Kf::vec2(in[30], in[31]), Kf::vec2(in[32], in[33]), in[34], in[35], depth, b);
        const std::uint32_t host[5] = {hit ? 1u : 0u, test::bits_of(depth), test::bits_of(b.x), test::bits_of(b.y), test::bits_of(b.z)};
        covered += hit;
        for (int k = 0; k < 5; ++k) differing += host[k] != gpu[static_cast<std::size_t>(n) * 5 + static_cast<std::size_t>(k)];
    }
    MESSAGE(context->renderer() << ": " << inputs << " inputs, " << covered << " covered, " << differing << " values differ");
    CHECK(differing == 0);
    CHECK(covered > 2000);
}
