#pragma once
// PNG and JPEG through stb_image / stb_image_write (Debian's libstb-dev),
// behind a small API so the library is compiled once (stb_codecs.cpp) and its
// warnings stay out of the project's files. The scene layer decodes glTF
// textures with it, render/common reads and writes PNG images.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace blurcull::frontend::codecs {

/// What an encoded image's header says, read without decoding the pixels.
struct ImageHeader {
    int width = 0;
    int height = 0;
    int channels = 0;  ///< channels stored in the file (1 to 4)
};

/// Decoded 8-bit pixels: `channels` bytes per pixel, rows top to bottom.
struct DecodedImage {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<std::uint8_t> bytes;
};

/// Reads the header of PNG or JPEG bytes. False, with stb's reason in
/// `error`, when the bytes are neither or are damaged.
bool read_image_header(const std::uint8_t* bytes, std::size_t length, ImageHeader& header, std::string& error);

/// Decodes PNG or JPEG bytes into `channels` (1 to 4) 8-bit channels per
/// pixel, converting from what the file stores. False, with stb's reason in
/// `error`, when it cannot (not an image, damaged, over 2 GiB).
bool decode_image(const std::uint8_t* bytes, std::size_t length, int channels, DecodedImage& image,
                  std::string& error);

/// Encodes `width` x `height` pixels of `channels` (1 to 4) 8-bit channels,
/// rows top to bottom and packed, as PNG bytes. Empty on failure.
std::vector<std::uint8_t> encode_png(int width, int height, int channels, const std::uint8_t* pixels);

}  // namespace blurcull::frontend::codecs
