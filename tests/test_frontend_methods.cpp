// The interleave, interval and accumulation-buffer renderers: exact on a
// static in-focus quad, identical to a brute-force render of the very samples
// they document (so their boxes never lose a hit), converging to the
// stochastic reference as N (K) grows, deterministic whatever the threads.
#include "frontend_test_helpers.hpp"
#include "render/common/camera_model.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/common/image.hpp"
#include "render/cpu/methods.hpp"
#include "render/common/moving_triangle.hpp"
#include "render/common/shading.hpp"

#include <blurcull/kernel.hpp>
#include <blurcull/interleaved_tiles.hpp>
#include <blurcull/patterns.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using namespace blurcull::frontend;
using namespace blurcull::frontend::test;
using K = blurcull::kernel<double>;

namespace {

constexpr int width = 32, height = 24;

RenderSettings settings_for(int spp, const std::string& method) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.spp = spp;
    settings.progress = false;
    settings.method = parse_render_method(method);
    settings.seed = 3;
    return settings;
}

// A static quad at depth 5 whose edges fall on pixel boundaries: columns
// 8 .. 19 and rows 6 .. 15 of a 32 x 24 image, no lens.
Scene static_quad_scene() {
    Scene scene;
    scene.name = "static-quad";
    scene.materials = {Material{{0.9f, 0.4f, 0.1f}, "quad"}};
    scene.camera.yfov = 0.9f;
    const CameraModel model(scene.camera, width, height);
    const float depth = 5.0f;
    auto world_x = [&](int column) { return (-1.0f + 2.0f * float(column) / width) * depth / model.k_x; };
    auto world_y = [&](int row) { return (1.0f - 2.0f * float(row) / height) * depth / model.k_y; };
    const float x0 = world_x(8), x1 = world_x(20), y0 = world_y(16), y1 = world_y(6);
    add_quad(scene, {x0, y0, -depth}, {x1, y0, -depth}, {x1, y1, -depth}, {x0, y1, -depth}, {0, 0, 0}, 0);
    return scene;
}

// Motion (objects and camera) and defocus at several depths, overlapping.
Scene blurred_scene() {
    Scene scene;
    scene.name = "blurred";
    scene.materials = {Material{{0.9f, 0.3f, 0.2f}, "near"}, Material{{0.2f, 0.8f, 0.3f}, "focus"},
                       Material{{0.3f, 0.4f, 0.9f}, "far"}};
    add_quad(scene, {-1.2f, -0.8f, -3.0f}, {-0.2f, -0.9f, -3.2f}, {-0.3f, 0.5f, -3.1f}, {-1.1f, 0.4f, -3.0f},
             {0.9f, 0.2f, 0.0f}, 0);
    add_quad(scene, {-0.5f, -1.0f, -5.0f}, {1.5f, -1.0f, -5.0f}, {1.5f, 0.9f, -5.0f}, {-0.5f, 0.9f, -5.0f},
             {-0.4f, 0.3f, 0.5f}, 1);
    add_quad(scene, {-4.0f, -3.0f, -9.0f}, {4.0f, -3.0f, -9.0f}, {4.0f, 3.0f, -9.5f}, {-4.0f, 3.0f, -9.5f},
             {0.0f, 0.0f, 0.0f}, 2);
    scene.camera.yfov = 0.9f;
    scene.camera.lens_radius = 0.12f;
    scene.camera.focus_distance = 5.0f;
    scene.camera.view_close = glm::mat4(1.0f);
    scene.camera.view_close[3] = glm::vec4(0.15f, 0.0f, 0.0f, 1.0f);
    return scene;
}

RenderResult render(const Scene& scene, const RenderSettings& settings, int tile_width = 6) {
    if (settings.method == RenderMethod::interleave) {
        InterleaveOptions options;
        options.tile_width = tile_width;
        return render_interleave(scene, settings, options);
    }
    return render_with_method(scene, settings);
}

// A sample as the renderers document it: NDC position, lens, time.
struct Sample {
    K::vec2 ndc;
    K::vec2 lens;
    double time;
};

// Every sample against every triangle, no boxes: what the renderers must
// reproduce exactly. Returns the image; `hits` counts covered pairs.
Image brute_force(const Scene& scene, const RenderSettings& settings,
                  const std::function<Sample(int px, int py, int j, const CameraModel&)>& sample_of, std::uint64_t& hits) {
    const CameraModel model(scene.camera, settings.width, settings.height);
    const std::vector<glm::vec3> colours = shade_all(scene);
    std::vector<K::MovingTriangle> triangles;
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) triangles.push_back(make_moving_triangle<double>(scene, model, i));
    Image image(settings.width, settings.height);
    hits = 0;
    for (int py = 0; py < settings.height; ++py) {
        for (int px = 0; px < settings.width; ++px) {
            glm::vec3 sum(0.0f);
            for (int j = 0; j < settings.spp; ++j) {
                const Sample s = sample_of(px, py, j, model);
                double nearest = std::numeric_limits<double>::infinity();
                std::size_t hit = triangles.size();
                for (std::size_t i = 0; i < triangles.size(); ++i) {
                    double z = 0.0;
                    if (!K::covers(triangles[i], s.ndc, s.lens, s.time, double(model.znear), z)) continue;
                    ++hits;
                    if (z < nearest) {
                        nearest = z;
                        hit = i;
                    }
                }
                sum += hit == triangles.size() ? scene.background : colours[hit];
            }
            image.at(px, py) = resolve_box(sum, settings.spp);
        }
    }
    return image;
}

std::function<Sample(int, int, int, const CameraModel&)> interleave_samples(const blurcull::InterleavedTiles& tiles,
                                                                             int side, std::uint32_t seed) {
    return [&tiles, side, seed](int px, int py, int j, const CameraModel& model) {
        const int sx = j % side, sy = j / side;
        const auto gx = static_cast<std::uint32_t>(px * side + sx), gy = static_cast<std::uint32_t>(py * side + sy);
        const glm::vec2 jitter = blurcull::patternsf::interleaved_jitter(gx, gy, seed);
        const glm::vec2 offset((float(sx) + jitter.x) / float(side), (float(sy) + jitter.y) / float(side));
        // The renderer rounds the tuples to float, as every pattern's samples are.
        const glm::dvec3 tuple(glm::vec3(tiles.tuples[std::size_t(tiles.tuple_at(gx, gy))]));
        return Sample{K::vec2(model.sample_ndc(px, py, glm::min(offset, glm::vec2(0.99999994f)))),
                      K::vec2(tuple.x, tuple.y), tuple.z};
    };
}

Sample interval_sample(int px, int py, int j, int spp, std::uint32_t seed, const CameraModel& model) {
    const blurcull::kernelf::PixelSample s = blurcull::patternsf::interval_sample(
        std::uint32_t(px), std::uint32_t(py), std::uint32_t(j), std::uint32_t(spp), seed);
    return Sample{K::vec2(model.sample_ndc(px, py, s.offset)), K::vec2(s.lens), double(s.time)};
}

Sample accum_sample(int px, int py, int k, std::uint32_t seed, const CameraModel& model) {
    const blurcull::kernelf::PixelSample s = blurcull::patternsf::accum_sample(std::uint32_t(k), seed);
    return Sample{K::vec2(model.sample_ndc(px, py, s.offset)), K::vec2(s.lens), double(s.time)};
}

}  // namespace

TEST_CASE("a static in-focus quad renders exactly with every method") {
    const Scene scene = static_quad_scene();
    // A fully covered pixel: the quad's colour summed 16 times, then divided (float).
    glm::vec3 sum(0.0f);
    for (int j = 0; j < 16; ++j) sum += shade(scene, 0);
    const glm::vec3 colour = resolve_box(sum, 16);
    const RenderResult reference = render_cpu(scene, settings_for(16, "stochastic"));
    for (const std::string method : {"interleave", "interval", "accum"}) {
        CAPTURE(method);
        const RenderResult result = render(scene, settings_for(16, method));
        REQUIRE(result.image.width == width);
        int differing = 0;
        double coverage = 0.0;
        for (int py = 0; py < height; ++py) {
            for (int px = 0; px < width; ++px) {
                const glm::vec3 value = result.image.at(px, py);
                const bool inside = px >= 8 && px < 20 && py >= 6 && py < 16;
                const bool border = (px == 7 || px == 8 || px == 19 || px == 20) || (py == 5 || py == 6 || py == 15 || py == 16);
                coverage += double((value.x - scene.background.x) / (colour.x - scene.background.x));
                if (value != reference.image.at(px, py)) ++differing;
                if (border) continue;  // a sample may sit on the edge itself
                if (inside) {
                    CHECK(value == colour);
                } else {
                    CHECK(value == scene.background);
                }
            }
        }
        // Every sample lands on the right side of the pixel-aligned edges
        // (unless one sits within float rounding of them).
        CHECK(differing <= 1);
        CHECK(coverage == doctest::Approx(12.0 * 10.0).epsilon(0.01));
        CHECK(result.stats.samples_hit == std::uint64_t(12 * 10 * 16));
        CHECK(result.stats.samples_tested >= result.stats.samples_hit);
        CHECK(result.stats.ms_per_phase.size() == 3);
        CHECK(result.stats.triangles == 2);
    }
}

TEST_CASE("each method equals a brute-force render of the samples it documents") {
    const Scene scene = blurred_scene();
    const int spp = 16;
    const RenderSettings interleave = settings_for(spp, "interleave");
    const blurcull::InterleavedTiles tiles = blurcull::make_interleaved_tiles(
        blurcull::InterleavedTileOptions{6, 2, 0.5, interleave.seed});  // motion and defocus: q = 0.5
    std::uint64_t hits = 0;
    const Image interleave_reference = brute_force(scene, interleave, interleave_samples(tiles, 4, interleave.seed), hits);
    const RenderResult interleave_result = render_interleave(scene, interleave);
    CHECK(same_pixels(interleave_result.image, interleave_reference));
    CHECK(interleave_result.stats.samples_hit == hits);
    // The boxes cull: far fewer tests than samples x triangles.
    CHECK(interleave_result.stats.samples_tested < std::uint64_t(width * height * spp) * scene.triangles.size() / 2);

    const RenderSettings interval = settings_for(spp, "interval");
    const Image interval_reference = brute_force(
        scene, interval,
        [&](int px, int py, int j, const CameraModel& model) { return interval_sample(px, py, j, spp, interval.seed, model); },
        hits);
    const RenderResult interval_result = render_interval(scene, interval);
    CHECK(same_pixels(interval_result.image, interval_reference));
    CHECK(interval_result.stats.samples_hit == hits);

    const RenderSettings accum = settings_for(spp, "accum");
    const Image accum_reference = brute_force(
        scene, accum, [&](int px, int py, int k, const CameraModel& model) { return accum_sample(px, py, k, accum.seed, model); },
        hits);
    const RenderResult accum_result = render_accum(scene, accum);
    CHECK(same_pixels(accum_result.image, accum_reference));
    CHECK(accum_result.stats.samples_hit == hits);
}

TEST_CASE("each method converges to the stochastic reference as N (K) grows") {
    const Scene scene = blurred_scene();
    RenderSettings reference_settings = settings_for(1024, "stochastic");
    reference_settings.seed = 99;
    const Image reference = render_cpu(scene, reference_settings).image;
    struct Step {
        int spp;
        int tile_width;  // interleave: N = tile_width^2 = spp, one tile per pixel at the end
    };
    const Step steps[] = {{4, 2}, {16, 4}, {64, 8}};
    for (const std::string method : {"stochastic", "interleave", "interval", "accum"}) {
        CAPTURE(method);
        double errors[3];
        for (int i = 0; i < 3; ++i) {
            const RenderSettings settings = settings_for(steps[i].spp, method);
            errors[i] = rmse(render(scene, settings, steps[i].tile_width).image, reference);
        }
        MESSAGE(method << " RMSE vs 1024 spp stochastic, N = 4, 16, 64: " << errors[0] << ", " << errors[1] << ", "
                       << errors[2]);
        std::printf("%-10s RMSE at N = 4, 16, 64: %.4f %.4f %.4f\n", method.c_str(), errors[0], errors[1], errors[2]);
        CHECK(errors[1] < errors[0]);
        CHECK(errors[2] < errors[1]);
        CHECK(errors[2] < 0.6 * errors[0]);
    }
}

TEST_CASE("every method is deterministic whatever the thread count") {
    const Scene scene = blurred_scene();
    for (const std::string method : {"interleave", "interval", "accum"}) {
        CAPTURE(method);
        RenderSettings settings = settings_for(16, method);
        settings.threads = 1;
        const RenderResult one = render_with_method(scene, settings);
        settings.threads = 3;
        const RenderResult three = render_with_method(scene, settings);
        const RenderResult again = render_with_method(scene, settings);
        CHECK(same_pixels(one.image, three.image));
        CHECK(same_pixels(three.image, again.image));
        CHECK(one.stats.samples_tested == three.stats.samples_tested);
        CHECK(one.stats.samples_hit == three.stats.samples_hit);
        CHECK(one.stats.bounds_computed == three.stats.bounds_computed);
    }
    // The seed moves every method's samples (accum's by a Cranley-Patterson
    // rotation of its passes), and the same seed gives the same image.
    for (const std::string method : {"interleave", "interval", "accum"}) {
        CAPTURE(method);
        RenderSettings seeded = settings_for(16, method);
        const Image first = render_with_method(scene, seeded).image;
        CHECK(same_pixels(first, render_with_method(scene, seeded).image));
        seeded.seed = 4;
        CHECK(!same_pixels(first, render_with_method(scene, seeded).image));
    }
}

TEST_CASE("methods: dispatch and bad input") {
    const Scene scene = blurred_scene();
    CHECK(render_method_names() ==
          std::vector<std::string>{"stochastic", "interleave", "interval", "accum", "dof-secondary"});
    RenderSettings settings = settings_for(4, "stochastic");
    CHECK(same_pixels(render_with_method(scene, settings).image, render_cpu(scene, settings).image));
    settings.method = RenderMethod::interval;
    CHECK(same_pixels(render_with_method(scene, settings).image, render_interval(scene, settings).image));
    // An unknown name is refused where names become methods.
    CHECK_THROWS_WITH_AS(parse_render_method("stratified"),
                         "unknown render method 'stratified' (valid: stochastic, interleave, interval, accum, dof-secondary)",
                         std::invalid_argument);
    CHECK(parse_render_method("accum") == RenderMethod::accum);
    settings.method = RenderMethod::interleave;
    settings.spp = 8;
    CHECK_THROWS_WITH_AS(render_with_method(scene, settings),
                         "interleave: samples per pixel must be a square (1, 4, 9, 16, ...), got 8", std::invalid_argument);
    settings.spp = 16;
    InterleaveOptions options;
    options.tile_width = 40;
    CHECK_THROWS_AS(render_interleave(scene, settings, options), std::invalid_argument);
    settings.method = RenderMethod::accum;
    settings.width = 0;
    CHECK_THROWS_AS(render_with_method(scene, settings), std::invalid_argument);
}

TEST_CASE("picture of the interleaved tile layout (docs/images/interleaved-tiles.png)") {
    // Cells coloured by their tuple (red = t, green = u, blue = v), tile
    // borders dark, each lattice corner marked in its colour (red, green, blue).
    const blurcull::InterleavedTiles tiles = blurcull::make_interleaved_tiles(blurcull::InterleavedTileOptions{});
    const int tiles_x = 6, tiles_y = 4, cell = 12, w = tiles.width;
    Image image(tiles_x * w * cell + 1, tiles_y * w * cell + 1, glm::vec3(0.05f));
    for (int gy = 0; gy < tiles_y * w; ++gy) {
        for (int gx = 0; gx < tiles_x * w; ++gx) {
            const glm::dvec3 tuple = tiles.tuples[std::size_t(tiles.tuple_at(std::uint32_t(gx), std::uint32_t(gy)))];
            const glm::vec3 colour(float(tuple.z), float(0.5 * (tuple.x + 1.0)), float(0.5 * (tuple.y + 1.0)));
            const bool tile_left = gx % w == 0, tile_top = gy % w == 0;
            for (int y = 1; y < cell; ++y) {
                for (int x = 1; x < cell; ++x) image.at(gx * cell + x, gy * cell + y) = colour;
            }
            for (int k = 0; k <= cell; ++k) {
                for (int thick = 0; thick < 2; ++thick) {
                    if (tile_left && gx * cell + thick < image.width) image.at(gx * cell + thick, gy * cell + k) = glm::vec3(0.0f);
                    if (tile_top && gy * cell + thick < image.height) image.at(gx * cell + k, gy * cell + thick) = glm::vec3(0.0f);
                }
            }
        }
    }
    const glm::vec3 marks[3] = {{1.0f, 0.1f, 0.1f}, {0.1f, 1.0f, 0.1f}, {0.2f, 0.3f, 1.0f}};
    for (int cy = 0; cy <= tiles_y; ++cy) {
        for (int cx = 0; cx <= tiles_x; ++cx) {
            const std::uint32_t colour = blurcull::patternsf::interleaved_corner_colour(std::uint32_t(cx), std::uint32_t(cy), tiles.seed);
            for (int y = -6; y <= 6; ++y) {
                for (int x = -6; x <= 6; ++x) {
                    const int ix = cx * w * cell + x, iy = cy * w * cell + y;
                    const bool ring = std::abs(x) == 6 || std::abs(y) == 6;
                    if (ix >= 0 && iy >= 0 && ix < image.width && iy < image.height)
                        image.at(ix, iy) = ring ? glm::vec3(0.0f) : marks[colour];
                }
            }
        }
    }
    const char* to_docs = std::getenv("BLURCULL_WRITE_DOC_IMAGES");
    const std::string path = to_docs != nullptr && std::string(to_docs) == "1"
                                 ? std::string(BLURCULL_SOURCE_DIR) + "/docs/images/interleaved-tiles.png"
                                 : (std::filesystem::temp_directory_path() / "blurcull-interleaved-tiles.png").string();
    write_png(path, image);
    const Image back = read_png(path);
    CHECK(back.width == image.width);
    CHECK(back.height == image.height);
    CHECK(rmse(back, image) < 0.01);
}
