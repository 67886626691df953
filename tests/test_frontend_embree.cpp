// The Embree reference renderer and the shared camera model, shading and
// image utilities, on tiny scenes built here.
#include "render/common/camera_model.hpp"
#include "render/embree/embree_backend.hpp"
#include "render/common/image.hpp"
#include "render/common/moving_triangle.hpp"
#include "render/common/render_types.hpp"
#include "render/common/shading.hpp"

#include <blurcull/patterns.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

using namespace blurcull::frontend;

namespace {

const glm::vec3 orange{0.9f, 0.5f, 0.1f};
const glm::vec3 green{0.1f, 0.8f, 0.2f};
const glm::vec3 dark_blue{0.0f, 0.0f, 0.2f};

// Camera at the world origin looking down -z; the light faces the camera so
// a quad in a z = const plane is lit fully.
Scene empty_scene() {
    Scene scene;
    scene.name = "test";
    scene.materials = {Material{orange, "orange"}, Material{green, "green"}};
    scene.background = dark_blue;
    scene.light_direction = glm::vec3(0.0f, 0.0f, 1.0f);
    scene.camera.yfov = 0.8f;
    scene.camera.znear = 0.05f;
    scene.camera.lens_radius = 0.0f;
    scene.camera.focus_distance = 10.0f;
    return scene;
}

std::uint32_t add_vertex(Scene& scene, glm::vec3 open, glm::vec3 close) {
    scene.position_open.push_back(open);
    scene.position_close.push_back(close);
    return static_cast<std::uint32_t>(scene.position_open.size() - 1);
}

void add_triangle(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, std::uint32_t material,
                  glm::vec3 motion = glm::vec3(0.0f)) {
    std::uint32_t ia = add_vertex(scene, a, a + motion);
    std::uint32_t ib = add_vertex(scene, b, b + motion);
    std::uint32_t ic = add_vertex(scene, c, c + motion);
    scene.triangles.emplace_back(ia, ib, ic);
    scene.triangle_material.push_back(material);
}

// Axis-aligned rectangle [x0, x1] x [y0, y1] at z = -depth; `right_motion`
// moves only the right edge (the left edge stays put).
void add_rectangle(Scene& scene, float x0, float x1, float y0, float y1, float depth, std::uint32_t material,
                   glm::vec3 right_motion = glm::vec3(0.0f)) {
    glm::vec3 bl(x0, y0, -depth), br(x1, y0, -depth), tr(x1, y1, -depth), tl(x0, y1, -depth);
    std::uint32_t ibl = add_vertex(scene, bl, bl);
    std::uint32_t ibr = add_vertex(scene, br, br + right_motion);
    std::uint32_t itr = add_vertex(scene, tr, tr + right_motion);
    std::uint32_t itl = add_vertex(scene, tl, tl);
    scene.triangles.emplace_back(ibl, ibr, itr);
    scene.triangles.emplace_back(ibl, itr, itl);
    scene.triangle_material.push_back(material);
    scene.triangle_material.push_back(material);
}

RenderSettings small_settings(int width, int height, int spp) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.spp = spp;
    settings.threads = 2;
    settings.progress = false;
    return settings;
}

bool near(glm::vec3 a, glm::vec3 b, float tolerance) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tolerance)));
}

// Fraction of a pixel covered by an orange surface over the background,
// recovered from the red channel (the background has none).
float orange_coverage(const Image& image, int px, int py) {
    return (image.at(px, py).r - dark_blue.r) / (orange.r - dark_blue.r);
}

}  // namespace

TEST_CASE("cull method names round-trip and bad names are rejected") {
    for (CullMethod method : {CullMethod::bbox, CullMethod::hull, CullMethod::dualspace, CullMethod::two_stage}) {
        CHECK(parse_cull_method(to_string(method)) == method);
    }
    try {
        parse_cull_method("boxes");
        FAIL("parse_cull_method accepted 'boxes'");
    } catch (const std::invalid_argument& error) {
        std::string message = error.what();
        CHECK(message.find("boxes") != std::string::npos);
        CHECK(message.find("twostage") != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}

TEST_CASE("render stats: STE is hits over tests") {
    RenderStats stats;
    CHECK(stats.ste() == 0.0);
    stats.samples_tested = 200;
    stats.samples_hit = 50;
    CHECK(stats.ste() == doctest::Approx(0.25));
}

TEST_CASE("camera model: coefficients and conventions") {
    Camera camera;
    camera.yfov = 0.9f;
    camera.lens_radius = 0.3f;
    camera.focus_distance = 7.0f;
    camera.znear = 0.2f;
    CameraModel model(camera, 200, 100);
    CHECK(model.k_y == doctest::Approx(1.0 / std::tan(0.45)));
    CHECK(model.k_x == doctest::Approx(model.k_y / 2.0f));
    CHECK(model.a_x == doctest::Approx(-model.k_x * 0.3f));
    CHECK(model.b_y == doctest::Approx(model.k_y * 0.3f / 7.0f));

    SUBCASE("the focus plane is sharp: c(F) = 0") {
        glm::vec2 c = model.coc(7.0f);
        CHECK(std::abs(c.x) < 1e-6f);
        CHECK(std::abs(c.y) < 1e-6f);
        // In front of the focus plane the CoC is negative, behind it positive.
        CHECK(model.coc(1.0f).x < 0.0f);
        CHECK(model.coc(20.0f).y > 0.0f);
        CHECK(model.coc(0.0f).x == doctest::Approx(-model.k_x * 0.3f));
    }

    SUBCASE("a lens ray projects, through its lens point, to its NDC at every depth") {
        std::mt19937 random(7);
        std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
        std::uniform_real_distribution<float> depth(0.2f, 50.0f);
        for (int trial = 0; trial < 1000; ++trial) {
            glm::vec2 ndc(unit(random), unit(random));
            glm::vec2 lens(unit(random), unit(random));
            if (glm::length(lens) > 1.0f) lens /= glm::length(lens);
            Ray ray = model.lens_ray(ndc, lens);
            CHECK(ray.origin.x == doctest::Approx(lens.x * 0.3f));
            CHECK(ray.origin.z == 0.0f);
            float w = depth(random);
            glm::vec3 clip = model.clip_xyw(ray.origin + w * ray.direction);
            CHECK(clip.z == doctest::Approx(w).epsilon(1e-6));
            glm::vec2 seen = model.project(clip, lens);
            // The kernel's formula written out: X = (x + u c_x(w)) / w.
            glm::vec2 c = model.coc(clip.z);
            glm::vec2 formula((clip.x + lens.x * c.x) / clip.z, (clip.y + lens.y * c.y) / clip.z);
            CHECK(std::abs(formula.x - ndc.x) < 1e-4f);
            CHECK(std::abs(formula.y - ndc.y) < 1e-4f);
            CHECK(std::abs(seen.x - formula.x) < 1e-6f);
        }
    }

    SUBCASE("a lens ray starts at the near plane") {
        Ray ray = model.lens_ray(glm::vec2(0.3f, -0.2f), glm::vec2(0.5f, 0.5f));
        CHECK(ray.origin.z + ray.t_near * ray.direction.z == doctest::Approx(-0.2f));
    }

    SUBCASE("pixels: row 0 at the top, raster and NDC round-trip") {
        glm::vec2 top_left = model.sample_ndc(0, 0, glm::vec2(0.0f));
        CHECK(top_left.x == doctest::Approx(-1.0f));
        CHECK(top_left.y == doctest::Approx(1.0f));
        glm::vec2 bottom_right = model.sample_ndc(199, 99, glm::vec2(1.0f));
        CHECK(bottom_right.x == doctest::Approx(1.0f));
        CHECK(bottom_right.y == doctest::Approx(-1.0f));
        glm::vec4 bounds = model.pixel_ndc_bounds(100, 0);
        CHECK(bounds.x == doctest::Approx(0.0f));          // X min
        CHECK(bounds.z == doctest::Approx(0.01f));         // X max
        CHECK(bounds.y == doctest::Approx(1.0f - 0.02f));  // Y min
        CHECK(bounds.w == doctest::Approx(1.0f));          // Y max
        glm::vec2 raster(37.25f, 81.5f);
        glm::vec2 back = model.ndc_to_raster(model.raster_to_ndc(raster));
        CHECK(back.x == doctest::Approx(raster.x));
        CHECK(back.y == doctest::Approx(raster.y));
    }
}

TEST_CASE("camera model: vertex motion is linear in view space") {
    Scene scene = empty_scene();
    add_vertex(scene, glm::vec3(1.0f, 2.0f, 0.0f), glm::vec3(3.0f, 2.0f, -1.0f));
    scene.camera.view_open = glm::mat4(1.0f);
    scene.camera.view_open[3] = glm::vec4(0.0f, 0.0f, -4.0f, 1.0f);  // translate z by -4
    scene.camera.view_close = glm::mat4(1.0f);
    scene.camera.view_close[3] = glm::vec4(-1.0f, 0.0f, -6.0f, 1.0f);
    CameraModel model(scene.camera, 64, 64);
    glm::vec3 open = model.view_position(scene, 0, 0);
    glm::vec3 close = model.view_position(scene, 0, 1);
    CHECK(near(open, glm::vec3(1.0f, 2.0f, -4.0f), 1e-6f));
    CHECK(near(close, glm::vec3(2.0f, 2.0f, -7.0f), 1e-6f));
    CHECK(near(model.view_position_at(scene, 0, 0.25f), glm::vec3(1.25f, 2.0f, -4.75f), 1e-6f));
    glm::vec3 clip = model.clip_xyw(open);
    CHECK(clip.z == doctest::Approx(4.0f));
    CHECK(clip.x == doctest::Approx(model.k_x * 1.0f));
}

TEST_CASE("camera model: unusable cameras are rejected") {
    Camera camera;
    CHECK_THROWS_AS(CameraModel(camera, 0, 10), std::invalid_argument);
    camera.yfov = 0.0f;
    CHECK_THROWS_AS(CameraModel(camera, 10, 10), std::invalid_argument);
    camera.yfov = 0.8f;
    camera.znear = 0.0f;
    CHECK_THROWS_AS(CameraModel(camera, 10, 10), std::invalid_argument);
    camera.znear = 0.1f;
    camera.lens_radius = 0.1f;
    camera.focus_distance = 0.0f;
    CHECK_THROWS_AS(CameraModel(camera, 10, 10), std::invalid_argument);
}

TEST_CASE("shading: flat, two-sided, ambient plus diffuse") {
    Scene scene = empty_scene();
    add_triangle(scene, glm::vec3(0, 0, -1), glm::vec3(1, 0, -1), glm::vec3(0, 1, -1), 0);  // faces +z
    add_triangle(scene, glm::vec3(0, 0, -1), glm::vec3(0, 1, -1), glm::vec3(1, 0, -1), 1);  // faces -z
    scene.light_direction = glm::vec3(0.0f, 0.0f, 2.0f);
    CHECK(near(shade(scene, 0), orange, 1e-6f));
    CHECK(near(shade(scene, 1), green, 1e-6f));  // back face lit the same
    scene.light_direction = glm::vec3(1.0f, 0.0f, 0.0f);  // grazing: ambient only
    CHECK(near(shade(scene, 0), 0.2f * orange, 1e-6f));
    scene.light_direction = glm::vec3(std::sqrt(3.0f), 0.0f, 1.0f);  // 60 degrees off the normal
    CHECK(near(shade(scene, 0), (0.2f + 0.8f * 0.5f) * orange, 1e-6f));
    std::vector<glm::vec3> all = shade_all(scene);
    REQUIRE(all.size() == 2);
    CHECK(near(all[1], shade(scene, 1), 0.0f));
    // Motion does not change the colour: the normal is taken at shutter open.
    scene.position_close[0] = glm::vec3(5.0f, 5.0f, 5.0f);
    CHECK(near(shade(scene, 0), (0.2f + 0.8f * 0.5f) * orange, 1e-6f));
}

TEST_CASE("image: PNG round trip, errors, differences") {
    Image image(5, 3, glm::vec3(0.25f));
    image.at(4, 0) = glm::vec3(1.0f, 0.0f, 0.5f);
    image.at(0, 2) = glm::vec3(2.0f, -1.0f, 0.01f);  // clamped on output
    std::string path = "/tmp/blurcull_test_image_" + std::to_string(::getpid()) + ".png";
    write_png(path, image);
    Image back = read_png(path);
    std::remove(path.c_str());
    REQUIRE(back.width == 5);
    REQUIRE(back.height == 3);
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 5; ++x) {
            glm::vec3 expected = glm::clamp(image.at(x, y), glm::vec3(0.0f), glm::vec3(1.0f));
            for (int channel = 0; channel < 3; ++channel) {
                // One 8-bit step of sRGB, measured in the encoded domain.
                CHECK(std::abs(linear_to_srgb(back.at(x, y)[channel]) - linear_to_srgb(expected[channel])) <=
                      0.5f / 255.0f + 1e-4f);
            }
        }
    }

    try {
        write_png("/nonexistent-blurcull-dir/out.png", image);
        FAIL("write_png wrote into a missing directory");
    } catch (const std::runtime_error& error) {
        CHECK(std::string(error.what()).rfind("cannot write '/nonexistent-blurcull-dir/out.png': ", 0) == 0);
    }
    CHECK_THROWS_AS(read_png("/nonexistent-blurcull-dir/in.png"), std::runtime_error);

    Image zero(2, 2, glm::vec3(0.0f));
    Image half(2, 2, glm::vec3(0.5f));
    CHECK(rmse(zero, zero) == 0.0);
    CHECK(rmse(zero, half) == doctest::Approx(0.5));
    half.at(1, 1) = glm::vec3(-0.5f, 0.5f, 1.5f);
    Image difference = abs_difference(zero, half);
    CHECK(near(difference.at(1, 1), glm::vec3(0.5f, 0.5f, 1.5f), 0.0f));
    CHECK_THROWS_AS(rmse(zero, Image(3, 2)), std::invalid_argument);
    CHECK_THROWS_AS(abs_difference(zero, Image(2, 3)), std::invalid_argument);
    CHECK(linear_to_srgb(srgb_to_linear(0.6f)) == doctest::Approx(0.6f).epsilon(1e-5));
}

TEST_CASE("embree: a static in-focus quad covers exactly the left half") {
    Scene scene = empty_scene();
    add_rectangle(scene, -20.0f, 0.0f, -20.0f, 20.0f, 5.0f, 0);
    RenderResult result = render_embree(scene, small_settings(32, 24, 4));
    const Image& image = result.image;
    REQUIRE(image.width == 32);
    REQUIRE(image.height == 24);
    glm::vec3 lit = shade(scene, 0);
    int wrong = 0;
    for (int y = 0; y < 24; ++y) {
        for (int x = 0; x < 32; ++x) {
            glm::vec3 expected = x < 16 ? lit : scene.background;
            if (!near(image.at(x, y), expected, 1e-6f)) ++wrong;
        }
    }
    CHECK(wrong == 0);
    CHECK(result.stats.samples_tested == 32u * 24u * 4u);
    CHECK(result.stats.samples_hit == 16u * 24u * 4u);
    CHECK(result.stats.triangles == 2);
    REQUIRE(result.stats.ms_per_phase.size() >= 3);
    CHECK(result.stats.ms_total >= 0.0);
}

TEST_CASE("embree: row 0 is the top of the image") {
    Scene scene = empty_scene();
    add_rectangle(scene, -20.0f, 20.0f, 0.0f, 20.0f, 5.0f, 0);  // upper half of view space
    RenderResult result = render_embree(scene, small_settings(8, 8, 4));
    CHECK(near(result.image.at(3, 0), shade(scene, 0), 1e-6f));
    CHECK(near(result.image.at(3, 7), scene.background, 1e-6f));
}

TEST_CASE("embree: a horizontally moving edge blurs into a linear ramp") {
    // The right edge of a wide quad at depth 5 moves from x = -3 to x = +3
    // during the shutter; a pixel's coverage is the mean over t of the part
    // of it left of the edge.
    const int width = 64;
    const int height = 16;
    const float depth = 5.0f;
    Scene scene = empty_scene();
    add_rectangle(scene, -50.0f, -3.0f, -20.0f, 20.0f, depth, 0, glm::vec3(6.0f, 0.0f, 0.0f));
    RenderResult result = render_embree(scene, small_settings(width, height, 64));
    CameraModel model(scene.camera, width, height);
    const float edge_open = model.ndc_to_raster(glm::vec2(model.k_x * -3.0f / depth, 0.0f)).x;
    const float edge_close = model.ndc_to_raster(glm::vec2(model.k_x * 3.0f / depth, 0.0f)).x;
    REQUIRE(edge_close - edge_open > 15.0f);  // the ramp spans many pixels

    std::vector<double> measured(width), analytic(width);
    for (int x = 0; x < width; ++x) {
        double sum = 0.0;
        for (int y = 0; y < height; ++y) sum += orange_coverage(result.image, x, y);
        measured[static_cast<std::size_t>(x)] = sum / height;
        const int steps = 20000;
        double integral = 0.0;
        for (int i = 0; i < steps; ++i) {
            double t = (i + 0.5) / steps;
            double edge = edge_open + t * (edge_close - edge_open);
            integral += std::clamp(edge - x, 0.0, 1.0);
        }
        analytic[static_cast<std::size_t>(x)] = integral / steps;
    }
    double measured_ramp = 0.0, analytic_ramp = 0.0;
    int ramp_pixels = 0;
    for (int x = 0; x < width; ++x) {
        auto i = static_cast<std::size_t>(x);
        CHECK(std::abs(measured[i] - analytic[i]) < 0.06);
        if (x > 0) CHECK(measured[i] <= measured[i - 1] + 0.03);  // monotone up to noise
        if (analytic[i] > 0.02 && analytic[i] < 0.98) {
            measured_ramp += measured[i];
            analytic_ramp += analytic[i];
            ++ramp_pixels;
        }
    }
    REQUIRE(ramp_pixels > 15);
    CHECK(std::abs(measured_ramp - analytic_ramp) / ramp_pixels < 0.02);
    CHECK(measured.front() > 0.999);
    CHECK(measured.back() < 0.001);
    // Linear: halfway through the motion the coverage is one half.
    const int middle = static_cast<int>(0.5f * (edge_open + edge_close));
    CHECK(measured[static_cast<std::size_t>(middle)] == doctest::Approx(analytic[static_cast<std::size_t>(middle)]).epsilon(0.15));
}

TEST_CASE("embree: an out-of-focus triangle spreads over its circle of confusion") {
    const int size = 64;
    const float depth = 2.5f;
    Scene scene = empty_scene();
    scene.camera.focus_distance = 10.0f;
    const glm::vec3 a(-0.05f, -0.05f, -depth), b(0.12f, -0.03f, -depth), c(0.0f, 0.1f, -depth);
    add_triangle(scene, a, b, c, 0);

    RenderSettings settings = small_settings(size, size, 64);
    RenderResult sharp = render_embree(scene, settings);
    scene.camera.lens_radius = 0.5f;
    RenderResult blurred = render_embree(scene, settings);

    CameraModel model(scene.camera, size, size);
    // Through lens (u, v) a point at depth w moves by (u c_x, v c_y) / w in
    // NDC: a disk of this radius in pixels (k_x W = k_y H, so it is round).
    const float coc_pixels = std::abs(model.coc(depth).x) / depth * 0.5f * static_cast<float>(size);
    REQUIRE(coc_pixels > 8.0f);
    std::vector<glm::vec2> corners;
    for (glm::vec3 p : {a, b, c}) {
        glm::vec3 clip = model.clip_xyw(p);
        corners.push_back(model.ndc_to_raster(glm::vec2(clip.x, clip.y) / clip.z));
    }
    const glm::vec2 centroid = (corners[0] + corners[1] + corners[2]) / 3.0f;
    float triangle_reach = 0.0f;
    for (glm::vec2 corner : corners) triangle_reach = std::max(triangle_reach, glm::length(corner - centroid));
    const glm::vec2 e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
    const double triangle_area = 0.5 * std::abs(static_cast<double>(e1.x * e2.y - e1.y * e2.x));

    int sharp_pixels = 0, blurred_pixels = 0, outside_bound = 0;
    double sharp_area = 0.0, blurred_area = 0.0;
    float farthest = 0.0f;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            float f_sharp = orange_coverage(sharp.image, x, y);
            float f_blurred = orange_coverage(blurred.image, x, y);
            sharp_area += f_sharp;
            blurred_area += f_blurred;
            if (f_sharp > 1e-4f) ++sharp_pixels;
            if (f_blurred > 1e-4f) {
                ++blurred_pixels;
                // Nearest point of the pixel square to the centroid.
                glm::vec2 nearest = glm::clamp(centroid, glm::vec2(x, y), glm::vec2(x + 1, y + 1));
                if (glm::length(nearest - centroid) > coc_pixels + triangle_reach + 1e-3f) ++outside_bound;
                glm::vec2 pixel_centre(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
                farthest = std::max(farthest, glm::length(pixel_centre - centroid));
            }
        }
    }
    CHECK(outside_bound == 0);
    CHECK(blurred_pixels > 4 * sharp_pixels);
    CHECK(farthest > 0.7f * coc_pixels);
    // The lens only translates a plane at fixed depth: the covered area is conserved.
    CHECK(sharp_area == doctest::Approx(triangle_area).epsilon(0.1));
    CHECK(blurred_area == doctest::Approx(triangle_area).epsilon(0.2));
}

TEST_CASE("embree: deterministic for a seed, whatever the thread count") {
    Scene scene = empty_scene();
    scene.camera.lens_radius = 0.3f;
    scene.camera.focus_distance = 6.0f;
    add_rectangle(scene, -1.0f, 0.5f, -1.0f, 1.0f, 3.0f, 0, glm::vec3(0.8f, 0.3f, 0.0f));
    add_triangle(scene, glm::vec3(-2, -2, -9), glm::vec3(2, -1, -9), glm::vec3(0, 2, -8), 1,
                 glm::vec3(-0.5f, 0.0f, 0.0f));
    RenderSettings settings = small_settings(40, 30, 8);
    settings.seed = 42;
    settings.threads = 1;
    RenderResult one = render_embree(scene, settings);
    settings.threads = 2;
    RenderResult two = render_embree(scene, settings);
    RenderResult again = render_embree(scene, settings);
    CHECK(one.image.pixels == two.image.pixels);
    CHECK(two.image.pixels == again.image.pixels);
    CHECK(one.stats.samples_hit == two.stats.samples_hit);
    settings.seed = 43;
    RenderResult other = render_embree(scene, settings);
    CHECK(other.image.pixels != two.image.pixels);
    CHECK(rmse(other.image, two.image) < 0.2);  // same picture, different noise
}

TEST_CASE("embree: nothing closer than znear is visible") {
    Scene scene = empty_scene();
    scene.camera.znear = 1.0f;
    add_rectangle(scene, -5.0f, 5.0f, -5.0f, 5.0f, 0.5f, 0);  // in front of the near plane
    RenderSettings settings = small_settings(16, 12, 4);
    RenderResult only_near = render_embree(scene, settings);
    CHECK(only_near.stats.samples_hit == 0);
    for (const glm::vec3& pixel : only_near.image.pixels) CHECK(near(pixel, scene.background, 1e-6f));

    add_rectangle(scene, -50.0f, 50.0f, -50.0f, 50.0f, 5.0f, 1);  // behind it: seen through it
    RenderResult with_far = render_embree(scene, settings);
    CHECK(with_far.stats.samples_hit == 16u * 12u * 4u);
    for (const glm::vec3& pixel : with_far.image.pixels) CHECK(near(pixel, shade(scene, 2), 1e-6f));
}

TEST_CASE("embree: bad settings and scenes are rejected with a message") {
    Scene scene = empty_scene();
    add_rectangle(scene, -1.0f, 1.0f, -1.0f, 1.0f, 3.0f, 0);
    RenderSettings settings = small_settings(8, 8, 0);
    CHECK_THROWS_AS(render_embree(scene, settings), std::invalid_argument);
    settings.spp = 1;
    settings.width = 0;
    CHECK_THROWS_AS(render_embree(scene, settings), std::invalid_argument);
    settings.width = 8;
    settings.method = RenderMethod::accum;  // the rasterizers' method: refused, naming those that take it
    CHECK_THROWS_WITH_AS(render_embree(scene, settings),
                         "render method accum: only the cpu and gl backends take it (backend embree)",
                         std::invalid_argument);
    settings.method = RenderMethod::stochastic;
    scene.triangle_material[0] = 9;
    CHECK_THROWS_WITH_AS(render_embree(scene, settings), doctest::Contains("material 9"), std::runtime_error);
}

TEST_CASE("embree: an empty scene renders the background") {
    Scene scene = empty_scene();
    RenderResult result = render_embree(scene, small_settings(4, 4, 2));
    CHECK(result.stats.samples_hit == 0);
    for (const glm::vec3& pixel : result.image.pixels) CHECK(near(pixel, scene.background, 0.0f));
}

TEST_CASE("moving triangle: clip vertices and circles of confusion at both shutter ends") {
    Scene scene = empty_scene();
    scene.camera.lens_radius = 0.2f;
    scene.camera.focus_distance = 4.0f;
    scene.camera.view_close[3] = glm::vec4(0.3f, 0.0f, -0.5f, 1.0f);  // the camera moves too
    add_triangle(scene, glm::vec3(-1, 0, -3), glm::vec3(1, 0, -3), glm::vec3(0, 1, -6), 0,
                 glm::vec3(0.5f, 0.2f, -1.0f));
    CameraModel model(scene.camera, 80, 60);
    const auto tri_f = make_moving_triangle<float>(scene, model, 0);
    const auto tri_d = make_moving_triangle<double>(scene, model, 0);
    for (int end = 0; end < 2; ++end) {
        for (int i = 0; i < 3; ++i) {
            const std::size_t j = static_cast<std::size_t>(i + 3 * end);
            glm::vec3 clip = model.clip_xyw(model.view_position(scene, scene.triangles[0][i], end));
            glm::vec2 c = model.coc(clip.z);
            CHECK(near(tri_f.p[j], clip, 1e-5f));
            CHECK(std::abs(tri_f.c[j].x - c.x) < 1e-6f);
            CHECK(std::abs(tri_f.c[j].y - c.y) < 1e-6f);
            CHECK(near(glm::vec3(tri_d.p[j]), clip, 1e-5f));
            CHECK(std::abs(static_cast<float>(tri_d.c[j].y) - c.y) < 1e-6f);
        }
    }
    // The second vertex moves closer (w from 3 to 4.5): it reaches the focus plane.
    CHECK(tri_d.p[4].z == doctest::Approx(4.5));
    CHECK(std::abs(blurcull::kerneld::coc_at(blurcull::kerneld::vec2(model.a_x, model.b_x), 4.0)) < 1e-6);
}

TEST_CASE("embree agrees with the kernel's exact coverage oracle, sample by sample") {
    // Overlapping triangles with object motion, camera motion and defocus,
    // one of them crossing the focus plane during the shutter.
    Scene scene = empty_scene();
    scene.camera.lens_radius = 0.25f;
    scene.camera.focus_distance = 5.0f;
    scene.camera.view_close[3] = glm::vec4(-0.2f, 0.1f, 0.0f, 1.0f);
    scene.light_direction = glm::vec3(0.3f, 0.8f, 0.5f);
    add_triangle(scene, glm::vec3(-1.5f, -1, -4), glm::vec3(1, -1.2f, -5), glm::vec3(0, 1.3f, -4.5f), 0,
                 glm::vec3(0.6f, 0.1f, -1.5f));
    add_triangle(scene, glm::vec3(-2, 0.5f, -7), glm::vec3(2.5f, 0, -6), glm::vec3(0.5f, -2, -8), 1,
                 glm::vec3(-0.8f, 0.3f, 0.0f));
    add_triangle(scene, glm::vec3(-0.3f, -0.2f, -2), glm::vec3(0.4f, -0.1f, -2.2f), glm::vec3(0, 0.5f, -2.1f), 0,
                 glm::vec3(0.0f, -0.3f, 0.2f));
    const int width = 48;
    const int height = 36;
    const int spp = 8;
    RenderSettings settings = small_settings(width, height, spp);
    settings.seed = 5;
    RenderResult embree = render_embree(scene, settings);

    CameraModel model(scene.camera, width, height);
    std::vector<blurcull::kerneld::MovingTriangle> triangles;
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        triangles.push_back(make_moving_triangle<double>(scene, model, t));
    }
    const std::vector<glm::vec3> colours = shade_all(scene);
    Image oracle(width, height);
    std::uint64_t hits = 0;
    for (int py = 0; py < height; ++py) {
        for (int px = 0; px < width; ++px) {
            glm::vec3 sum(0.0f);
            // The samples of the settings' sampler (the default), as every backend draws them.
            const blurcull::patternsf::SamplerSetup pattern = blurcull::patternsf::sampler_setup(
                settings.sampler, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py),
                static_cast<std::uint32_t>(spp), settings.seed);
            for (int j = 0; j < spp; ++j) {
                const auto sample = blurcull::patternsf::sampler_sample(pattern, static_cast<std::uint32_t>(j));
                const glm::dvec2 s(model.sample_ndc(px, py, sample.offset));
                double nearest = std::numeric_limits<double>::infinity();
                glm::vec3 colour = scene.background;
                for (std::size_t t = 0; t < triangles.size(); ++t) {
                    double depth = 0.0;
                    if (blurcull::kerneld::covers(triangles[t], s, glm::dvec2(sample.lens), sample.time,
                                                  model.znear, depth) &&
                        depth < nearest) {
                        nearest = depth;
                        colour = colours[t];
                    }
                }
                if (nearest < std::numeric_limits<double>::infinity()) ++hits;
                sum += colour;
            }
            oracle.at(px, py) = resolve_box(sum, spp);
        }
    }
    int differing_pixels = 0;
    for (std::size_t i = 0; i < oracle.pixels.size(); ++i) {
        if (!near(oracle.pixels[i], embree.image.pixels[i], 1e-5f)) ++differing_pixels;
    }
    // Float rays and double edge tests may disagree on a sample that grazes an edge.
    const double total_samples = static_cast<double>(width * height * spp);
    CHECK(hits > static_cast<std::uint64_t>(0.1 * total_samples));
    CHECK(std::abs(static_cast<double>(hits) - static_cast<double>(embree.stats.samples_hit)) < 0.002 * total_samples);
    CHECK(differing_pixels <= width * height / 200);
    CHECK(rmse(oracle, embree.image) < 0.01);
}
