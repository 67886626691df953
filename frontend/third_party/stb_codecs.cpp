#include "third_party/stb_codecs.hpp"

#include <climits>

// stb's own code is not held to the project's warning flags. Static: the
// Debian tinygltf library exports stb_image symbols of its own.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace blurcull::frontend::codecs {

namespace {

// stb takes lengths as int.
bool fits_stb(std::size_t length, std::string& error) {
    if (length <= static_cast<std::size_t>(INT_MAX)) return true;
    error = "image is larger than 2 GiB";
    return false;
}

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* first = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), first, first + size);
}

}  // namespace

bool read_image_header(const std::uint8_t* bytes, std::size_t length, ImageHeader& header, std::string& error) {
    if (!fits_stb(length, error)) return false;
    if (stbi_info_from_memory(bytes, static_cast<int>(length), &header.width, &header.height, &header.channels)) {
        return true;
    }
    error = stbi_failure_reason();
    return false;
}

bool decode_image(const std::uint8_t* bytes, std::size_t length, int channels, DecodedImage& image,
                  std::string& error) {
    if (!fits_stb(length, error)) return false;
    int stored = 0;
    stbi_uc* pixels =
        stbi_load_from_memory(bytes, static_cast<int>(length), &image.width, &image.height, &stored, channels);
    if (pixels == nullptr) {
        error = stbi_failure_reason();
        return false;
    }
    image.channels = channels;
    const std::size_t count = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
                              static_cast<std::size_t>(channels);
    image.bytes.assign(pixels, pixels + count);
    stbi_image_free(pixels);
    return true;
}

std::vector<std::uint8_t> encode_png(int width, int height, int channels, const std::uint8_t* pixels) {
    std::vector<std::uint8_t> out;
    if (!stbi_write_png_to_func(append_bytes, &out, width, height, channels, pixels, width * channels)) out.clear();
    return out;
}

}  // namespace blurcull::frontend::codecs
