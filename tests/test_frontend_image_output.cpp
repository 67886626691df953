// Image files: the EXR round trip (linear values and alpha = coverage read
// back with the library that wrote them), the choice of format by
// extension, writes that leave nothing half-written, and the coverage every
// backend reports (cpu = embree on the same samples, gl = cpu).
#include "frontend_test_helpers.hpp"

#include "render/common/image.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/cpu/methods.hpp"
#include "render/embree/embree_backend.hpp"
#include "render/gl/gl_backend.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

namespace {

using namespace blurcull::frontend;
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    const fs::path folder = fs::temp_directory_path() / "blurcull_image_output_test";
    fs::create_directories(folder);
    return folder / name;
}

// A 7x5 image of values an 8-bit PNG cannot hold (negative, above 1, tiny),
// with a coverage ramp.
Image hdr_test_image() {
    Image image(7, 5);
    image.coverage.resize(image.pixels.size());
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const float f = static_cast<float>(i);
        image.pixels[i] = glm::vec3(0.013f * f, 3.75f - 0.31f * f, f == 3.0f ? 1e-4f : 12.5f + f);
        image.coverage[i] = static_cast<float>(i % 5) / 4.0f;
    }
    return image;
}

std::string file_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// No "x.partial-PID" left beside `path`.
bool no_partial_files(const fs::path& path) {
    for (const fs::directory_entry& entry : fs::directory_iterator(path.parent_path())) {
        if (entry.path().filename().string().find(".partial-") != std::string::npos) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("EXR float: the linear values and the coverage come back exactly") {
    const Image image = hdr_test_image();
    const std::string path = scratch("round_trip_float.exr").string();
    write_image(path, image, ImageFormat::exr, ExrPixelType::full_float);
    const Image back = read_exr(path);
    REQUIRE(back.width == image.width);
    REQUIRE(back.height == image.height);
    CHECK(back.pixels == image.pixels);
    CHECK(back.coverage == image.coverage);
}

TEST_CASE("EXR half: the values within half precision, coverage (multiples of 1/4) exactly") {
    const Image image = hdr_test_image();
    const std::string path = scratch("round_trip_half.exr").string();
    write_exr(path, image, ExrPixelType::half);
    const Image back = read_exr(path);
    REQUIRE(back.pixels.size() == image.pixels.size());
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float want = image.pixels[i][c], got = back.pixels[i][c];
            // Half has an 11-bit significand: relative error at most 2^-11 (denormals below 6e-5 aside).
            CHECK(std::abs(got - want) <= std::abs(want) * 0.00049f + 6e-8f);
        }
    }
    CHECK(back.coverage == image.coverage);
    // Half files are smaller than float ones.
    write_exr(scratch("size_float.exr").string(), image, ExrPixelType::full_float);
    CHECK(fs::file_size(path) < fs::file_size(scratch("size_float.exr")));
}

TEST_CASE("EXR without coverage: alpha is 1") {
    Image image(3, 2, glm::vec3(0.5f));
    const std::string path = scratch("no_coverage.exr").string();
    write_exr(path, image, ExrPixelType::full_float);
    const Image back = read_exr(path);
    CHECK(back.coverage == std::vector<float>(6, 1.0f));
    image.coverage = {0.5f};  // wrong size
    CHECK_THROWS_WITH_AS(write_exr(path, image), doctest::Contains("coverage count"), std::runtime_error);
}

TEST_CASE("the output format is chosen by extension; others are refused in one line") {
    CHECK(image_format_for_path("a.png") == ImageFormat::png);
    CHECK(image_format_for_path("dir.x/A.PNG") == ImageFormat::png);
    CHECK(image_format_for_path("out.exr") == ImageFormat::exr);
    CHECK(image_format_for_path("out.EXR") == ImageFormat::exr);
    CHECK_THROWS_WITH_AS(image_format_for_path("out.tiff"), doctest::Contains("unknown image type '.tiff'"),
                         std::invalid_argument);
    CHECK_THROWS_WITH_AS(image_format_for_path("out"), doctest::Contains("(no extension)"), std::invalid_argument);
    CHECK_THROWS_WITH_AS(image_format_for_path("dir.png/out"), doctest::Contains("(no extension)"),
                         std::invalid_argument);
    CHECK(image_encoding(ImageFormat::png, ExrPixelType::half) == "sRGB 8-bit RGB");
    CHECK(image_encoding(ImageFormat::exr, ExrPixelType::half) == "linear half RGBA, alpha = coverage");
    CHECK(image_encoding(ImageFormat::exr, ExrPixelType::full_float) == "linear float RGBA, alpha = coverage");
}

TEST_CASE("a failed write leaves the old file untouched and no partial file") {
    for (const ImageFormat format : {ImageFormat::png, ImageFormat::exr}) {
        const fs::path path = scratch(format == ImageFormat::png ? "kept.png" : "kept.exr");
        write_image(path.string(), hdr_test_image(), format);
        const std::string before = file_bytes(path);
        REQUIRE(!before.empty());
        const Image empty;
        CHECK_THROWS_WITH_AS(write_image(path.string(), empty, format),
                             doctest::Contains(("cannot write '" + path.string() + "': image is empty").c_str()),
                             std::runtime_error);
        CHECK(file_bytes(path) == before);
        CHECK(no_partial_files(path));
        // A folder that does not exist: the message names the path asked for.
        CHECK_THROWS_WITH_AS(write_image("/nonexistent-folder/x.exr", hdr_test_image(), format),
                             doctest::Contains("cannot write '/nonexistent-folder/x.exr'"), std::runtime_error);
    }
}

TEST_CASE("coverage: every backend reports it; cpu = embree on the same samples, gl = cpu") {
    // Two moving, defocused quads on the background (the built-in scenes fill the frame).
    Scene scene;
    scene.materials.push_back(Material{});
    scene.materials.push_back(Material{glm::vec3(0.2f, 0.7f, 0.3f), "green"});
    test::add_quad(scene, {-1.0f, -1.0f, -5.0f}, {1.0f, -1.0f, -5.0f}, {1.0f, 1.0f, -5.0f}, {-1.0f, 1.0f, -5.0f},
                   {0.6f, 0.0f, 0.0f}, 0);
    test::add_quad(scene, {-0.5f, -1.5f, -3.0f}, {0.2f, -1.5f, -3.0f}, {0.2f, 0.0f, -3.0f}, {-0.5f, 0.0f, -3.0f},
                   {0.0f, 0.4f, -0.5f}, 1);
    scene.camera.lens_radius = 0.05f;
    scene.camera.focus_distance = 5.0f;
    const RenderSettings settings = test::quiet_settings(64, 48, 8);
    const RenderResult cpu = render_cpu(scene, settings);
    REQUIRE(cpu.image.coverage.size() == cpu.image.pixels.size());
    std::size_t empty = 0, full = 0;
    for (std::size_t i = 0; i < cpu.image.coverage.size(); ++i) {
        const float covered = cpu.image.coverage[i] * 8.0f;
        CHECK(covered == std::round(covered));  // a whole number of the pixel's samples
        if (covered == 0.0f) {
            ++empty;
            // No sample hit: the background alone (summed spp times, then divided).
            CHECK(glm::all(glm::lessThan(glm::abs(cpu.image.pixels[i] - scene.background), glm::vec3(1e-6f))));
        }
        full += covered == 8.0f;
    }
    CHECK(empty > 0);
    CHECK(full > 0);

    const RenderResult embree = render_embree(scene, settings);
    REQUIRE(embree.image.coverage.size() == cpu.image.coverage.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < cpu.image.coverage.size(); ++i) {
        const float d = std::abs(embree.image.coverage[i] - cpu.image.coverage[i]);
        CHECK(d <= 1.0f / 8.0f);  // a sample on an edge at most
        differ += d > 0.0f;
    }
    CHECK(static_cast<double>(differ) <= 0.01 * static_cast<double>(cpu.image.coverage.size()));

    RenderSettings interleave = settings;
    interleave.spp = 16;
    interleave.method = RenderMethod::interleave;
    const RenderResult method = render_with_method(scene, interleave);
    REQUIRE(method.image.coverage.size() == method.image.pixels.size());
    double method_sum = 0.0, cpu_sum = 0.0;
    for (float c : method.image.coverage) method_sum += c;
    for (float c : cpu.image.coverage) cpu_sum += c;
    CHECK(method_sum == doctest::Approx(cpu_sum).epsilon(0.05));  // other samples, the same silhouette

    GlRenderer* gl = test::renderer_or_skip();
    if (gl == nullptr) return;
    const RenderResult on_gl = gl->render(scene, settings, GlOptions{});
    REQUIRE(on_gl.image.coverage.size() == cpu.image.coverage.size());
    std::size_t gl_differ = 0;
    for (std::size_t i = 0; i < cpu.image.coverage.size(); ++i) {
        gl_differ += on_gl.image.coverage[i] != cpu.image.coverage[i];
    }
    CHECK(static_cast<double>(gl_differ) <= 0.01 * static_cast<double>(cpu.image.coverage.size()));
}
