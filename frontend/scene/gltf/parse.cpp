#include "scene/gltf/parse.hpp"

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

// Images are irrelevant to blurcull (flat base colours only): skip decoding,
// so a broken or exotic texture never stops a scene from loading.
bool ignore_image(tg::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                  void*) {
    return true;
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
    if (u32(4) != 2) diagnostics.fail("GLB version " + std::to_string(u32(4)) + " is not 2");
    if (u32(8) > bytes.size()) {
        diagnostics.fail("GLB header says " + std::to_string(u32(8)) + " bytes but the file has " +
                         std::to_string(bytes.size()));
    }
    const std::uint64_t json_end = 20ull + u32(12);
    if (json_end > u32(8)) diagnostics.fail("GLB JSON chunk runs past the end of the file");
    if (u32(16) != 0x4E4F534Au) diagnostics.fail("GLB first chunk is not JSON");
}

}  // namespace

tg::Model parse_file(Diagnostics& diagnostics) {
    const std::string& path = diagnostics.path();
    const std::vector<unsigned char> bytes = read_bytes(diagnostics);
    const auto length = static_cast<unsigned int>(bytes.size());

    tg::Model model;
    tg::TinyGLTF parser;
    parser.SetImageLoader(ignore_image, nullptr);
    std::string error;
    std::string warning;
    bool ok = false;
    if (scene_file_type(path) == SceneFileType::glb) {
        check_glb_header(bytes, diagnostics);
        ok = parser.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), length, directory_of(path));
    } else {
        if (bytes.empty()) diagnostics.fail("file is empty");
        ok = parser.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(bytes.data()),
                                        length, directory_of(path));
    }
    if (!ok) {
        const std::string reason = one_line(error.empty() ? warning : error);
        diagnostics.fail("cannot parse glTF: " + (reason.empty() ? std::string("unknown error") : reason));
    }
    if (!warning.empty()) diagnostics.warn_once("tinygltf", one_line(warning));
    return model;
}

}  // namespace blurcull::frontend::gltf
