// A linear-RGB float image, row 0 at the top, with the per-pixel sample
// coverage the renderers report, and the few operations the backends, the
// command and the tests need: PNG and OpenEXR output and input (by the
// path's extension, written under a temporary name and renamed), and image
// differences.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace blurcull::frontend {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> pixels;  // width * height, row-major, row 0 = top
    // Per pixel, the fraction of its samples that hit a triangle (the EXR's
    // alpha; resolve_coverage). Empty when the renderer did not report it.
    std::vector<float> coverage;

    Image() = default;
    // Throws std::invalid_argument for a negative size.
    Image(int image_width, int image_height, glm::vec3 fill = glm::vec3(0.0f));

    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }
    glm::vec3& at(int x, int y) { return pixels[index(x, y)]; }
    const glm::vec3& at(int x, int y) const { return pixels[index(x, y)]; }
};

// A pixel's coverage: the fraction of its `spp` samples that hit a triangle.
inline float resolve_coverage(std::uint32_t hit_samples, int spp) {
    return static_cast<float>(hit_samples) / static_cast<float>(spp);
}

// The sRGB transfer function and its inverse, on one channel clamped to [0, 1].
float linear_to_srgb(float linear);
float srgb_to_linear(float encoded);

// 8-bit sRGB PNG of the clamped linear values. Throws std::runtime_error
// "cannot write 'path': reason" on failure.
void write_png(const std::string& path, const Image& image);

// Reads an 8-bit PNG (RGB or RGBA; alpha dropped) back into linear values.
// Throws std::runtime_error "cannot read 'path': reason" on failure.
Image read_png(const std::string& path);

// The image files blurcull writes, chosen by the output path's extension.
enum class ImageFormat {
    png,  // 8-bit sRGB-encoded RGB
    exr,  // OpenEXR, linear RGBA, alpha = coverage
};

// The sample type of an EXR's channels.
enum class ExrPixelType { half, full_float };

// The format for `path`'s extension (.png or .exr, in any case). Throws
// std::invalid_argument "'path': unknown image type '.ext' (expected .png or
// .exr)" for any other.
ImageFormat image_format_for_path(const std::string& path);

// One phrase naming what a file of this format holds, for the JSON summary:
// "sRGB 8-bit RGB", "linear half RGBA, alpha = coverage" (or float).
std::string image_encoding(ImageFormat format, ExrPixelType exr_type);

// OpenEXR of the linear values (unclamped) with alpha = image.coverage
// (1 where the image has no coverage), ZIP-compressed, one part. Throws
// std::runtime_error "cannot write 'path': reason" on failure.
void write_exr(const std::string& path, const Image& image, ExrPixelType type = ExrPixelType::half);

// Reads an OpenEXR's R, G, B (0 where missing) and A (1 where missing, as
// the coverage). Throws std::runtime_error "cannot read 'path': reason".
Image read_exr(const std::string& path);

// write_png or write_exr by `format`, to a temporary name beside `path`
// that is renamed to `path` once the file is complete, so a failed write
// leaves no partial file (and an existing `path` untouched). Throws
// std::runtime_error "cannot write 'path': reason".
void write_image(const std::string& path, const Image& image, ImageFormat format,
                 ExrPixelType exr_type = ExrPixelType::half);

// Root-mean-square difference over all pixels and channels. Throws
// std::invalid_argument when the sizes differ.
double rmse(const Image& a, const Image& b);

// Per-pixel |a - b| per channel. Throws std::invalid_argument when the sizes differ.
Image abs_difference(const Image& a, const Image& b);

}  // namespace blurcull::frontend
