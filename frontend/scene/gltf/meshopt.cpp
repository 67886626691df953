#include "scene/gltf/meshopt.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace blurcull::frontend::gltf {

const char* const kMeshoptPlaceholderUri = "data:application/octet-stream;base64,AAAAAA==";

namespace {

namespace tg = tinygltf;

constexpr const char* kExtension = "EXT_meshopt_compression";

// A decoded view may be at most this many times its compressed bytes (plus
// kDecodedSlack): meshoptimizer's streams shrink data by at most 64x (an
// all-zero vertex stream: 2 header bits per 16 bytes), so a larger claim is
// refused before anything is allocated.
constexpr std::size_t kMaxExpansion = 128;
constexpr std::size_t kDecodedSlack = 64 * 1024;

// A property of the extension object as a count or offset; `fallback` when
// absent and not required. Fails for anything but a non-negative integer.
std::size_t size_property(const tg::Value& object, const char* key, bool required, std::size_t fallback,
                          const std::string& owner, const Diagnostics& diagnostics) {
    if (!object.Has(key)) {
        if (required) diagnostics.fail(owner + ": " + kExtension + " has no " + key);
        return fallback;
    }
    const tg::Value& value = object.Get(key);
    const double number = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
    if (!(number >= 0.0) || number > 4294967295.0 || std::floor(number) != number) {
        diagnostics.fail(owner + ": " + kExtension + " " + key + " is not a non-negative integer");
    }
    return static_cast<std::size_t>(number);
}

std::string string_property(const tg::Value& object, const char* key, const std::string& fallback) {
    if (!object.Has(key) || !object.Get(key).IsString()) return fallback;
    return object.Get(key).Get<std::string>();
}

bool is_placeholder(const tg::Buffer& buffer) {
    return buffer.uri == kMeshoptPlaceholderUri && buffer.extensions.count(kExtension) != 0;
}

// The decoded bytes of buffer view `index` (whose extension is `extension`).
std::vector<unsigned char> decode_view(const tg::Model& model, std::size_t index, const tg::Value& extension,
                                       const Diagnostics& diagnostics) {
    const std::string owner = "buffer view " + std::to_string(index);
    const tg::BufferView& view = model.bufferViews[index];
    if (!extension.IsObject()) diagnostics.fail(owner + ": " + kExtension + " is not an object");
    const std::size_t buffer_index = size_property(extension, "buffer", true, 0, owner, diagnostics);
    const std::size_t offset = size_property(extension, "byteOffset", false, 0, owner, diagnostics);
    const std::size_t length = size_property(extension, "byteLength", true, 0, owner, diagnostics);
    const std::size_t stride = size_property(extension, "byteStride", true, 0, owner, diagnostics);
    const std::size_t count = size_property(extension, "count", true, 0, owner, diagnostics);
    const std::string mode = string_property(extension, "mode", "");
    const std::string filter = string_property(extension, "filter", "NONE");

    if (buffer_index >= model.buffers.size()) {
        diagnostics.fail(owner + ": " + kExtension + " buffer " + std::to_string(buffer_index) + " does not exist");
    }
    const tg::Buffer& buffer = model.buffers[buffer_index];
    if (is_placeholder(buffer)) {
        diagnostics.fail(owner + ": " + kExtension + " buffer " + std::to_string(buffer_index) +
                         " is a fallback buffer without data");
    }
    const std::size_t buffer_size = buffer.data.size();
    if (offset > buffer_size || length > buffer_size - offset) {
        diagnostics.fail(owner + ": " + kExtension + " data (offset " + std::to_string(offset) + ", length " +
                         std::to_string(length) + ") runs past the end of buffer " + std::to_string(buffer_index) +
                         " (" + std::to_string(buffer_size) + " bytes)");
    }

    if (mode == "ATTRIBUTES") {
        if (stride == 0 || stride % 4 != 0 || stride > 256) {
            diagnostics.fail(owner + ": " + kExtension + " ATTRIBUTES byteStride " + std::to_string(stride) +
                             " is not a multiple of 4 up to 256");
        }
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
        if (stride != 2 && stride != 4) {
            diagnostics.fail(owner + ": " + kExtension + " " + mode + " byteStride " + std::to_string(stride) +
                             " is not 2 or 4");
        }
        if (mode == "TRIANGLES" && count % 3 != 0) {
            diagnostics.fail(owner + ": " + kExtension + " TRIANGLES count " + std::to_string(count) +
                             " is not a multiple of 3");
        }
        if (filter != "NONE") diagnostics.fail(owner + ": " + kExtension + " filter " + Diagnostics::quoted(filter) +
                                               " is only for ATTRIBUTES");
    } else {
        diagnostics.fail(owner + ": " + kExtension + " mode '" + Diagnostics::quoted(mode) +
                         "' is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    const bool filter_fits = filter == "NONE" || (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8)) ||
                             (filter == "QUATERNION" && stride == 8) || (filter == "EXPONENTIAL" && stride % 4 == 0);
    if (!filter_fits) {
        diagnostics.fail(owner + ": " + kExtension + " filter '" + Diagnostics::quoted(filter) +
                         "' is unknown or does not fit byteStride " + std::to_string(stride));
    }

    // count * stride, checked against the view and the compressed size
    // before any allocation.
    if (count > std::numeric_limits<std::size_t>::max() / stride || count * stride != view.byteLength) {
        diagnostics.fail(owner + ": " + kExtension + " count " + std::to_string(count) + " x byteStride " +
                         std::to_string(stride) + " is not the view's byteLength " +
                         std::to_string(view.byteLength));
    }
    const std::size_t decoded_size = count * stride;
    if (length > (std::numeric_limits<std::size_t>::max() - kDecodedSlack) / kMaxExpansion ||
        decoded_size > length * kMaxExpansion + kDecodedSlack) {
        diagnostics.fail(owner + ": " + kExtension + " claims " + std::to_string(decoded_size) + " bytes from " +
                         std::to_string(length) + " compressed bytes");
    }

    std::vector<unsigned char> decoded(decoded_size);
    const unsigned char* source = buffer.data.data() + offset;
    int result = 0;
    if (mode == "ATTRIBUTES") {
        result = meshopt_decodeVertexBuffer(decoded.data(), count, stride, source, length);
    } else if (mode == "TRIANGLES") {
        result = meshopt_decodeIndexBuffer(decoded.data(), count, stride, source, length);
    } else {
        result = meshopt_decodeIndexSequence(decoded.data(), count, stride, source, length);
    }
    if (result != 0) {
        diagnostics.fail(owner + ": " + kExtension + " " + mode + " data (" + std::to_string(length) +
                         " bytes) cannot be decoded (meshoptimizer error " + std::to_string(result) + ")");
    }
    if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(decoded.data(), count, stride);
    if (filter == "QUATERNION") meshopt_decodeFilterQuat(decoded.data(), count, stride);
    if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data(), count, stride);
    return decoded;
}

}  // namespace

void decode_meshopt_views(tg::Model& model, const Diagnostics& diagnostics) {
    tg::Buffer decoded;
    decoded.name = "EXT_meshopt_compression (decoded)";
    const std::size_t decoded_index = model.buffers.size();
    bool any = false;
    // Views may share one stream: the whole file's decoded bytes are held to
    // the same bound against all its buffers' bytes.
    std::size_t buffer_bytes = 0;
    for (const tg::Buffer& buffer : model.buffers) buffer_bytes += buffer.data.size();
    const std::size_t total_limit = buffer_bytes * kMaxExpansion + kDecodedSlack;
    for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
        tg::BufferView& view = model.bufferViews[v];
        const auto extension = view.extensions.find(kExtension);
        if (extension == view.extensions.end()) {
            if (view.buffer >= 0 && static_cast<std::size_t>(view.buffer) < model.buffers.size() &&
                is_placeholder(model.buffers[static_cast<std::size_t>(view.buffer)])) {
                diagnostics.fail("buffer view " + std::to_string(v) + " reads buffer " +
                                 std::to_string(view.buffer) + ", a " + kExtension +
                                 " fallback buffer without data, but is not compressed");
            }
            continue;
        }
        const std::vector<unsigned char> bytes = decode_view(model, v, extension->second, diagnostics);
        if (bytes.size() > total_limit - std::min(total_limit, decoded.data.size())) {
            diagnostics.fail("buffer view " + std::to_string(v) + ": " + kExtension + " views decode to more than " +
                             std::to_string(total_limit) + " bytes in all, " + std::to_string(kMaxExpansion) +
                             " times the file's buffers");
        }
        while (decoded.data.size() % 4 != 0) decoded.data.push_back(0);
        any = true;
        view.buffer = static_cast<int>(decoded_index);
        view.byteOffset = decoded.data.size();
        view.byteLength = bytes.size();
        decoded.data.insert(decoded.data.end(), bytes.begin(), bytes.end());
    }
    if (any) model.buffers.push_back(std::move(decoded));
}

}  // namespace blurcull::frontend::gltf
