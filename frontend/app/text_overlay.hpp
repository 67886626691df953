// Text drawn into an image on the CPU, for `blurcull view`'s overlay: the
// glyphs are stb_easy_font's (libstb-dev) line segments, filled as pixel
// rectangles, on a dark translucent panel so they read on any scene.
#pragma once

#include "render/common/image.hpp"

#include <string>

namespace blurcull::frontend {

// Draws `text` (lines separated by '\n') with its top-left corner at pixel
// (x, y), each font unit `scale` pixels, clipped to the image. Returns how
// many pixel writes had the text colour (0: no glyph landed in the image).
std::size_t draw_text_panel(Image& image, int x, int y, const std::string& text, int scale = 1);

}  // namespace blurcull::frontend
