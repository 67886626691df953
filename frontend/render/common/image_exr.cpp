// OpenEXR output and input (Debian's libopenexr-dev, the format's reference
// library; docs/building.md says why): linear RGB and alpha = coverage.
#include "render/common/image.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <half.h>

#include <array>
#include <exception>
#include <stdexcept>

namespace blurcull::frontend {

namespace {

constexpr std::array<const char*, 4> channel_names{"R", "G", "B", "A"};

// The four slices of an interleaved RGBA buffer of Sample (float or half)
// whose pixel (0, 0) is at `origin` (OpenEXR addresses pixels from the data
// window's corner). Reading converts to the slice's type; writing does not.
template <class Sample>
Imf::FrameBuffer rgba_slices(Sample* origin, int width) {
    constexpr Imf::PixelType type = sizeof(Sample) == sizeof(float) ? Imf::FLOAT : Imf::HALF;
    constexpr std::array<double, 4> fill{0.0, 0.0, 0.0, 1.0};  // a missing channel: black, alpha 1
    Imf::FrameBuffer frame;
    const std::size_t x_stride = 4 * sizeof(Sample);
    const std::size_t y_stride = x_stride * static_cast<std::size_t>(width);
    for (std::size_t c = 0; c < channel_names.size(); ++c) {
        frame.insert(channel_names[c],
                     Imf::Slice(type, reinterpret_cast<char*>(origin + c), x_stride, y_stride, 1, 1, fill[c]));
    }
    return frame;
}

// The image's RGB and coverage (1 where it has none) interleaved as Sample.
template <class Sample>
std::vector<Sample> interleaved_rgba(const Image& image) {
    std::vector<Sample> rgba(4 * image.pixels.size());
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) rgba[4 * i + static_cast<std::size_t>(c)] = Sample(image.pixels[i][c]);
        rgba[4 * i + 3] = Sample(image.coverage.empty() ? 1.0f : image.coverage[i]);
    }
    return rgba;
}

template <class Sample>
void write_rgba(const std::string& path, const Image& image, Imf::Header& header) {
    constexpr Imf::PixelType type = sizeof(Sample) == sizeof(float) ? Imf::FLOAT : Imf::HALF;
    for (const char* name : channel_names) header.channels().insert(name, Imf::Channel(type));
    std::vector<Sample> rgba = interleaved_rgba<Sample>(image);
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(rgba_slices(rgba.data(), image.width));
    file.writePixels(image.height);
}

}  // namespace

void write_exr(const std::string& path, const Image& image, ExrPixelType type) {
    const auto fail = [&](const std::string& reason) {
        return std::runtime_error("cannot write '" + path + "': " + reason);
    };
    if (image.width < 1 || image.height < 1) throw fail("image is empty");
    if (image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
        throw fail("pixel count does not match the image size");
    }
    if (!image.coverage.empty() && image.coverage.size() != image.pixels.size()) {
        throw fail("coverage count does not match the image size");
    }
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::addComments(header, "blurcull: linear RGB (background included where samples missed); "
                                 "A = fraction of the pixel's samples that hit a triangle");
        if (type == ExrPixelType::half) {
            write_rgba<half>(path, image, header);
        } else {
            write_rgba<float>(path, image, header);
        }
    } catch (const std::exception& error) {
        throw fail(error.what());
    }
}

Image read_exr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const int width = window.max.x - window.min.x + 1;
        const int height = window.max.y - window.min.y + 1;
        std::vector<float> rgba(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
        // The slice's origin is where pixel (0, 0) would be, before the window's corner.
        const std::ptrdiff_t corner = static_cast<std::ptrdiff_t>(window.min.y) * width + window.min.x;
        file.setFrameBuffer(rgba_slices(rgba.data() - 4 * corner, width));
        file.readPixels(window.min.y, window.max.y);
        Image image(width, height);
        image.coverage.resize(image.pixels.size());
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            image.pixels[i] = glm::vec3(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]);
            image.coverage[i] = rgba[4 * i + 3];
        }
        return image;
    } catch (const std::exception& error) {
        throw std::runtime_error("cannot read '" + path + "': " + error.what());
    }
}

}  // namespace blurcull::frontend
