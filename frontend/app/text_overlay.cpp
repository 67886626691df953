#include "app/text_overlay.hpp"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace blurcull::frontend {
namespace {

struct EasyFontVertex {  // stb_easy_font's vertex layout
    float x, y, z;
    unsigned char colour[4];
};
static_assert(sizeof(EasyFontVertex) == 16, "stb_easy_font writes 16-byte vertices");

// Blends `colour` over the pixels of [x0, x1) x [y0, y1), clipped; returns how many were set.
std::size_t fill(Image& image, int x0, int y0, int x1, int y1, glm::vec3 colour, float opacity) {
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, image.width);
    y1 = std::min(y1, image.height);
    std::size_t count = 0;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            glm::vec3& pixel = image.at(x, y);
            pixel = glm::mix(pixel, colour, opacity);
            ++count;
        }
    }
    return count;
}

}  // namespace

std::size_t draw_text_panel(Image& image, int x, int y, const std::string& text, int scale) {
    if (text.empty() || scale < 1) return 0;
    std::string copy = text;  // stb_easy_font takes a char*
    const int margin = 4;
    const int text_width = stb_easy_font_width(copy.data());
    const int text_height = stb_easy_font_height(copy.data());
    fill(image, x, y, x + (text_width + 2 * margin) * scale, y + (text_height + 2 * margin) * scale,
         glm::vec3(0.0f), 0.6f);
    // ~270 bytes per character, as stb_easy_font documents.
    std::vector<EasyFontVertex> vertices(copy.size() * 20 + 64);
    const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, vertices.data(),
                                          static_cast<int>(vertices.size() * sizeof(EasyFontVertex)));
    std::size_t lit = 0;
    for (int q = 0; q < quads; ++q) {
        const EasyFontVertex* quad = &vertices[static_cast<std::size_t>(q) * 4];
        // Axis-aligned: corners 0 and 2 are opposite.
        auto pixel = [&](float font_units, int origin) {
            return origin + (margin + static_cast<int>(std::lround(font_units))) * scale;
        };
        lit += fill(image, pixel(std::min(quad[0].x, quad[2].x), x), pixel(std::min(quad[0].y, quad[2].y), y),
                    pixel(std::max(quad[0].x, quad[2].x), x), pixel(std::max(quad[0].y, quad[2].y), y),
                    glm::vec3(1.0f, 0.95f, 0.6f), 1.0f);
    }
    return lit;
}

}  // namespace blurcull::frontend
