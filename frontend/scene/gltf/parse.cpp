#include "scene/gltf/parse.hpp"

#include "scene/gltf/compressed_json.hpp"
#include "scene/gltf/conformance.hpp"
#include "scene/gltf/draco.hpp"
#include "scene/gltf/meshopt.hpp"
#include "scene/scene_name.hpp"

#include <climits>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

std::string directory_of(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash + 1);
}

// tinygltf reports several lines; a SceneError is one line.
std::string one_line(const std::string& text) {
    std::string out;
    bool pending_separator = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pending_separator = !out.empty();
            continue;
        }
        if (pending_separator) {
            out += "; ";
            pending_separator = false;
        }
        out += c;
    }
    return out;
}

// Images are kept encoded (as_is): decoding is the shading side's job, so a
// broken or exotic image never stops a scene from loading. tinygltf hands
// an image in a buffer view over without checking the view against its
// buffer; `user_data` is the model being filled, whose views come first.
bool keep_encoded_image(tg::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void* user_data) {
    if (size <= 0) return true;
    if (image->bufferView >= 0) {
        const auto* model = static_cast<const tg::Model*>(user_data);
        const tg::BufferView& view = model->bufferViews[static_cast<std::size_t>(image->bufferView)];
        const std::size_t buffer_size = model->buffers[static_cast<std::size_t>(view.buffer)].data.size();
        if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) return true;
    }
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

// tinygltf's own line for an image file it could not read (a warning only
// for images: buffers are required, so their failures are errors);
// image_warnings says it better, once per image.
bool is_image_file_warning(const std::string& line) {
    return line.rfind("Failed to load external 'uri' for image[", 0) == 0 ||
           line.rfind("File not found : ", 0) == 0 || line.rfind("File read error : ", 0) == 0 ||
           line.rfind("File is empty : ", 0) == 0;
}

std::string without_image_file_warnings(const std::string& text) {
    std::string kept;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        if (!is_image_file_warning(line)) kept += line + "\n";
        start = end + 1;
    }
    return kept;
}

// An image whose bytes could not be read (a missing external file, or a
// buffer view outside its buffer) warns once; its textures are left to
// fall back to their factors.
void image_warnings(const tg::Model& model, Diagnostics& diagnostics) {
    for (std::size_t i = 0; i < model.images.size(); ++i) {
        const tg::Image& image = model.images[i];
        if (!image.image.empty()) continue;
        const std::string source = image.uri.empty() ? "buffer view " + std::to_string(image.bufferView)
                                                     : "'" + Diagnostics::quoted(image.uri) + "'";
        diagnostics.warn_once("image " + std::to_string(i), "image " + std::to_string(i) + " (" + source +
                                                               ") cannot be read; its textures fall back to "
                                                               "their factors");
    }
}

std::vector<unsigned char> read_bytes(const Diagnostics& diagnostics) {
    std::ifstream file(diagnostics.path(), std::ios::binary);
    if (!file) diagnostics.fail("cannot open file");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (file.bad()) diagnostics.fail("cannot read file");
    if (bytes.size() >= UINT_MAX) diagnostics.fail("file is larger than 4 GiB");
    return bytes;
}

// tinygltf trusts the GLB chunk lengths; check them first.
void check_glb_header(const std::vector<unsigned char>& bytes, const Diagnostics& diagnostics) {
    auto u32 = [&](std::size_t offset) {
        std::uint32_t v;
        std::memcpy(&v, bytes.data() + offset, sizeof v);
        return v;  // GLB is little-endian, as is every platform blurcull runs on
    };
    if (bytes.size() < 20) diagnostics.fail("GLB file is shorter than its 20-byte header");
    if (std::memcmp(bytes.data(), "glTF", 4) != 0) diagnostics.fail("GLB file does not start with 'glTF'");
    if (u32(4) != 2) {
        diagnostics.fail("GLB container version " + std::to_string(u32(4)) +
                         " is not supported (blurcull reads glTF 2.x, GLB version 2)");
    }
    if (u32(8) > bytes.size()) {
        diagnostics.fail("GLB header says " + std::to_string(u32(8)) + " bytes but the file has " +
                         std::to_string(bytes.size()));
    }
    const std::uint64_t json_end = 20ull + u32(12);
    if (json_end > u32(8)) diagnostics.fail("GLB JSON chunk runs past the end of the file");
    if (u32(16) != 0x4E4F534Au) diagnostics.fail("GLB first chunk is not JSON");
    // tinygltf 2.7 checks the BIN chunk's length without its 8-byte header
    // and would read up to 8 bytes past the declared end.
    if (json_end + 12 <= u32(8) && json_end + 8 + u32(static_cast<std::size_t>(json_end)) > u32(8)) {
        diagnostics.fail("GLB BIN chunk runs past the end of the file");
    }
}

}  // namespace

tg::Model parse_file(Diagnostics& diagnostics) {
    const std::string& path = diagnostics.path();
    std::vector<unsigned char> bytes = read_bytes(diagnostics);
    const bool binary = scene_file_type(path) == SceneFileType::glb;
    if (binary) check_glb_header(bytes, diagnostics);
    bytes = with_compression_rewrites(std::move(bytes), binary);
    if (bytes.size() >= UINT_MAX) diagnostics.fail("file is larger than 4 GiB");
    const auto length = static_cast<unsigned int>(bytes.size());

    tg::Model model;
    tg::TinyGLTF parser;
    parser.SetImageLoader(keep_encoded_image, &model);
    std::string error;
    std::string warning;
    bool ok = false;
    if (binary) {
        ok = parser.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), length, directory_of(path));
    } else {
        if (bytes.empty()) diagnostics.fail("file is empty");
        ok = parser.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(bytes.data()),
                                        length, directory_of(path));
    }
    if (!ok) {
        check_declared_version(model, diagnostics);
        const std::string reason = one_line(error.empty() ? warning : error);
        diagnostics.fail("cannot parse glTF: " + (reason.empty() ? std::string("unknown error") : reason));
    }
    check_conformance(model, diagnostics);
    const std::string other_warnings = one_line(without_image_file_warnings(warning));
    if (!other_warnings.empty()) diagnostics.warn_once("tinygltf", other_warnings);
    image_warnings(model, diagnostics);
    // Compressed geometry, decoded into plain buffer views and accessors:
    // meshopt's views first (a Draco mesh could sit in one).
    decode_meshopt_views(model, diagnostics);
    decode_draco_primitives(model, diagnostics);
    return model;
}

}  // namespace blurcull::frontend::gltf
