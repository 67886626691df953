// A linear-RGB float image, row 0 at the top, and the few operations the
// backends and tests need: PNG output, PNG input, and image differences.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace blurcull::frontend {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> pixels;  // width * height, row-major, row 0 = top

    Image() = default;
    // Throws std::invalid_argument for a negative size.
    Image(int image_width, int image_height, glm::vec3 fill = glm::vec3(0.0f));

    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }
    glm::vec3& at(int x, int y) { return pixels[index(x, y)]; }
    const glm::vec3& at(int x, int y) const { return pixels[index(x, y)]; }
};

// The sRGB transfer function and its inverse, on one channel clamped to [0, 1].
float linear_to_srgb(float linear);
float srgb_to_linear(float encoded);

// 8-bit sRGB PNG of the clamped linear values. Throws std::runtime_error
// "cannot write 'path': reason" on failure.
void write_png(const std::string& path, const Image& image);

// Reads an 8-bit PNG (RGB or RGBA; alpha dropped) back into linear values.
// Throws std::runtime_error "cannot read 'path': reason" on failure.
Image read_png(const std::string& path);

// Root-mean-square difference over all pixels and channels. Throws
// std::invalid_argument when the sizes differ.
double rmse(const Image& a, const Image& b);

// Per-pixel |a - b| per channel. Throws std::invalid_argument when the sizes differ.
Image abs_difference(const Image& a, const Image& b);

}  // namespace blurcull::frontend
