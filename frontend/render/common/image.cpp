#include "render/common/image.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "third_party/stb_codecs.hpp"

namespace blurcull::frontend {

Image::Image(int image_width, int image_height, glm::vec3 fill) : width(image_width), height(image_height) {
    if (image_width < 0 || image_height < 0) {
        throw std::invalid_argument("image size must not be negative, got " + std::to_string(image_width) + "x" +
                                    std::to_string(image_height));
    }
    pixels.assign(static_cast<std::size_t>(image_width) * static_cast<std::size_t>(image_height), fill);
}

float linear_to_srgb(float linear) {
    float c = std::clamp(linear, 0.0f, 1.0f);
    if (!(c == c)) c = 0.0f;  // NaN: clamp keeps it, the PNG should not
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float encoded) {
    float c = std::clamp(encoded, 0.0f, 1.0f);
    if (!(c == c)) c = 0.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

namespace {

void require_same_size(const Image& a, const Image& b, const char* what) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) {
        throw std::invalid_argument(std::string(what) + ": image sizes differ (" + std::to_string(a.width) + "x" +
                                    std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                                    std::to_string(b.height) + ")");
    }
}

}  // namespace

void write_png(const std::string& path, const Image& image) {
    const auto fail = [&](const std::string& reason) {
        return std::runtime_error("cannot write '" + path + "': " + reason);
    };
    if (image.width < 1 || image.height < 1) throw fail("image is empty");
    if (image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
        throw fail("pixel count does not match the image size");
    }
    std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int channel = 0; channel < 3; ++channel) {
            float encoded = linear_to_srgb(image.pixels[i][channel]);
            bytes[3 * i + static_cast<std::size_t>(channel)] = static_cast<std::uint8_t>(std::lround(encoded * 255.0f));
        }
    }
    const std::vector<std::uint8_t> png = codecs::encode_png(image.width, image.height, 3, bytes.data());
    if (png.empty()) throw fail("PNG encoding failed");
    // An ofstream of our own so the failure reason (errno) is ours to report.
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw fail(std::strerror(errno));
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    out.flush();
    if (!out) throw fail(std::strerror(errno));
}

Image read_png(const std::string& path) {
    const auto fail = [&](const std::string& reason) { return std::runtime_error("cannot read '" + path + "': " + reason); };
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fail(std::strerror(errno));
    const std::vector<std::uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw fail(std::strerror(errno));
    codecs::DecodedImage decoded;
    std::string error;
    if (!codecs::decode_image(file.data(), file.size(), 3, decoded, error)) throw fail(error);
    Image image(decoded.width, decoded.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int channel = 0; channel < 3; ++channel) {
            float encoded = static_cast<float>(decoded.bytes[3 * i + static_cast<std::size_t>(channel)]) / 255.0f;
            image.pixels[i][channel] = srgb_to_linear(encoded);
        }
    }
    return image;
}

ImageFormat image_format_for_path(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    std::string extension = dot == std::string::npos || (slash != std::string::npos && dot < slash)
                                ? std::string()
                                : path.substr(dot);
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension == ".png") return ImageFormat::png;
    if (extension == ".exr") return ImageFormat::exr;
    throw std::invalid_argument("'" + path + "': unknown image type " +
                                (extension.empty() ? std::string("(no extension)") : "'" + extension + "'") +
                                " (expected .png or .exr)");
}

std::string image_encoding(ImageFormat format, ExrPixelType exr_type) {
    if (format == ImageFormat::png) return "sRGB 8-bit RGB";
    return std::string("linear ") + (exr_type == ExrPixelType::half ? "half" : "float") + " RGBA, alpha = coverage";
}

void write_image(const std::string& path, const Image& image, ImageFormat format, ExrPixelType exr_type) {
    // Same folder, so the rename cannot cross file systems; the pid keeps
    // two renders of one path from sharing a temporary file.
    const std::string partial = path + ".partial-" + std::to_string(static_cast<long>(getpid()));
    try {
        if (format == ImageFormat::png) {
            write_png(partial, image);
        } else {
            write_exr(partial, image, exr_type);
        }
    } catch (const std::runtime_error& error) {
        std::remove(partial.c_str());
        // The reason without the temporary name: "cannot write 'x.partial-1': r" -> r.
        const std::string message = error.what();
        const std::size_t reason = message.find("': ");
        throw std::runtime_error("cannot write '" + path +
                                 "': " + (reason == std::string::npos ? message : message.substr(reason + 3)));
    }
    if (std::rename(partial.c_str(), path.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        std::remove(partial.c_str());
        throw std::runtime_error("cannot write '" + path + "': " + reason);
    }
}

double rmse(const Image& a, const Image& b) {
    require_same_size(a, b, "rmse");
    if (a.pixels.empty()) return 0.0;
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        for (int channel = 0; channel < 3; ++channel) {
            double d = static_cast<double>(a.pixels[i][channel]) - static_cast<double>(b.pixels[i][channel]);
            sum += d * d;
        }
    }
    return std::sqrt(sum / (3.0 * static_cast<double>(a.pixels.size())));
}

Image abs_difference(const Image& a, const Image& b) {
    require_same_size(a, b, "abs_difference");
    Image difference(a.width, a.height);
    for (std::size_t i = 0; i < a.pixels.size(); ++i) difference.pixels[i] = glm::abs(a.pixels[i] - b.pixels[i]);
    return difference;
}

}  // namespace blurcull::frontend
