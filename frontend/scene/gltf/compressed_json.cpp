#include "scene/gltf/compressed_json.hpp"

#include "scene/gltf/meshopt.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace blurcull::frontend::gltf {

const char* const kDracoIndicesKey = "blurcull_indices";

namespace {

using json = nlohmann::json;

std::uint32_t read_u32(const std::vector<unsigned char>& bytes, std::size_t offset) {
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + offset, sizeof v);
    return v;
}

void append_u32(std::vector<unsigned char>& bytes, std::uint32_t v) {
    unsigned char raw[4];
    std::memcpy(raw, &v, sizeof raw);
    bytes.insert(bytes.end(), raw, raw + 4);
}

// The object at object[key] when it is one, else null.
json* member_object(json& object, const char* key) {
    const auto it = object.find(key);
    return it != object.end() && it->is_object() ? &*it : nullptr;
}

bool placeholder_fallbacks(json& document) {
    const auto buffers = document.find("buffers");
    if (buffers == document.end() || !buffers->is_array()) return false;
    bool changed = false;
    for (json& buffer : *buffers) {
        if (!buffer.is_object() || buffer.contains("uri")) continue;
        json* extensions = member_object(buffer, "extensions");
        json* extension = extensions ? member_object(*extensions, "EXT_meshopt_compression") : nullptr;
        if (extension == nullptr) continue;
        const auto fallback = extension->find("fallback");
        if (fallback == extension->end() || !fallback->is_boolean() || !fallback->get<bool>()) continue;
        buffer["uri"] = kMeshoptPlaceholderUri;
        buffer["byteLength"] = 4;
        changed = true;
    }
    return changed;
}

bool move_draco_indices(json& document) {
    const auto meshes = document.find("meshes");
    if (meshes == document.end() || !meshes->is_array()) return false;
    bool changed = false;
    for (json& mesh : *meshes) {
        if (!mesh.is_object()) continue;
        const auto primitives = mesh.find("primitives");
        if (primitives == mesh.end() || !primitives->is_array()) continue;
        for (json& primitive : *primitives) {
            if (!primitive.is_object() || !primitive.contains("indices")) continue;
            json* extensions = member_object(primitive, "extensions");
            json* extension = extensions ? member_object(*extensions, "KHR_draco_mesh_compression") : nullptr;
            if (extension == nullptr) continue;
            (*extension)[kDracoIndicesKey] = primitive["indices"];
            primitive.erase("indices");
            changed = true;
        }
    }
    return changed;
}

// The JSON with the rewrites, or empty when nothing changed.
std::string rewritten_json(const char* begin, const char* end) {
    const std::string text(begin, end);
    const bool meshopt = text.find("EXT_meshopt_compression") != std::string::npos;
    const bool draco = text.find("KHR_draco_mesh_compression") != std::string::npos;
    if (!meshopt && !draco) return {};
    json document = json::parse(text, nullptr, false);
    if (document.is_discarded() || !document.is_object()) return {};
    bool changed = false;
    if (meshopt) changed = placeholder_fallbacks(document);
    if (draco) changed = move_draco_indices(document) || changed;
    return changed ? document.dump(-1, ' ', false, json::error_handler_t::replace) : std::string();
}

}  // namespace

std::vector<unsigned char> with_compression_rewrites(std::vector<unsigned char> bytes, bool binary) {
    if (!binary) {
        const auto* text = reinterpret_cast<const char*>(bytes.data());
        const std::string json_text = rewritten_json(text, text + bytes.size());
        if (json_text.empty()) return bytes;
        return std::vector<unsigned char>(json_text.begin(), json_text.end());
    }
    // 12-byte header, the JSON chunk (8-byte header), then the rest: the
    // declared length grows or shrinks with the JSON, and any bytes past it
    // stay, as tinygltf would have seen them.
    const std::size_t json_length = read_u32(bytes, 12);
    const std::size_t total = read_u32(bytes, 8);
    const auto* text = reinterpret_cast<const char*>(bytes.data()) + 20;
    std::string json_text = rewritten_json(text, text + json_length);
    if (json_text.empty()) return bytes;
    while (json_text.size() % 4 != 0) json_text += ' ';
    const std::size_t rest = bytes.size() - 20 - json_length;
    if (json_text.size() + rest + 20 >= std::numeric_limits<std::uint32_t>::max()) return bytes;
    std::vector<unsigned char> rebuilt(bytes.begin(), bytes.begin() + 8);
    append_u32(rebuilt, static_cast<std::uint32_t>(total - json_length + json_text.size()));
    append_u32(rebuilt, static_cast<std::uint32_t>(json_text.size()));
    append_u32(rebuilt, 0x4E4F534Au);  // "JSON"
    rebuilt.insert(rebuilt.end(), json_text.begin(), json_text.end());
    const auto rest_begin = bytes.begin() + static_cast<std::ptrdiff_t>(20 + json_length);
    rebuilt.insert(rebuilt.end(), rest_begin, rest_begin + static_cast<std::ptrdiff_t>(rest));
    return rebuilt;
}

}  // namespace blurcull::frontend::gltf
