#include "scene/gltf/conformance.hpp"

#include <algorithm>
#include <cctype>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

// "MAJOR.MINOR" (glTF's pattern ^[0-9]+\.[0-9]+$) as two numbers; false for
// anything else. Digits are capped so a long string cannot overflow.
bool parse_version(const std::string& text, long& major, long& minor) {
    const std::size_t dot = text.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == text.size() || text.size() > 16) return false;
    const auto digits = [](const std::string& part) {
        return std::all_of(part.begin(), part.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    };
    const std::string major_text = text.substr(0, dot), minor_text = text.substr(dot + 1);
    if (!digits(major_text) || !digits(minor_text)) return false;
    major = std::stol(major_text);
    minor = std::stol(minor_text);
    return true;
}

bool implemented(const std::string& name) {
    const auto& known = implemented_extensions();
    return std::find(known.begin(), known.end(), name) != known.end();
}

std::string implemented_list() {
    std::string list;
    for (const std::string& name : implemented_extensions()) list += (list.empty() ? "" : ", ") + name;
    return list;
}

}  // namespace

const std::vector<std::string>& implemented_extensions() {
    // KHR_mesh_quantization: integer positions and morph targets, decoded
    // by accessors.cpp; the node transform dequantises them.
    // KHR_lights_punctual: directional, point and spot lights (lights.cpp);
    // KHR_materials_emissive_strength and KHR_materials_unlit (surface.cpp);
    // KHR_texture_transform: offset, rotation, scale (surface.cpp).
    // KHR_materials_transmission and KHR_materials_ior: glass
    // (specular_material.cpp; what is read and what is not: its header).
    // KHR_draco_mesh_compression (draco.cpp) and EXT_meshopt_compression
    // (meshopt.cpp): compressed geometry, decoded when the file is parsed.
    static const std::vector<std::string> names = {"KHR_mesh_quantization",     "KHR_lights_punctual",
                                                   "KHR_texture_transform",     "KHR_materials_transmission",
                                                   "KHR_materials_ior",         "KHR_draco_mesh_compression",
                                                   "EXT_meshopt_compression",   "KHR_materials_emissive_strength",
                                                   "KHR_materials_unlit"};
    return names;
}

void check_declared_version(const tg::Model& model, const Diagnostics& diagnostics) {
    const std::string& version = model.asset.version;
    if (version.empty()) return;
    long major = 0, minor = 0;
    if (!parse_version(version, major, minor)) {
        diagnostics.fail("asset.version '" + Diagnostics::quoted(version) + "' is not a glTF version (MAJOR.MINOR; blurcull reads 2.x)");
    }
    if (major != 2) {
        diagnostics.fail("glTF version " + version + " is not supported (blurcull reads glTF 2.x)");
    }
    const std::string& min_version = model.asset.minVersion;
    if (!min_version.empty()) {
        long min_major = 0, min_minor = 0;
        if (!parse_version(min_version, min_major, min_minor) || min_major != 2 || min_minor > 0) {
            diagnostics.fail("asset.minVersion " + Diagnostics::quoted(min_version) + " is not supported (blurcull reads glTF 2.0)");
        }
    }
    for (const std::string& name : model.extensionsRequired) {
        if (!implemented(name)) {
            diagnostics.fail("required extension " + Diagnostics::quoted(name) + " is not supported (blurcull implements " +
                             implemented_list() + ")");
        }
    }
}

void check_conformance(const tg::Model& model, Diagnostics& diagnostics) {
    if (model.asset.version.empty()) diagnostics.fail("asset.version is missing (a glTF 2.0 file must have one)");
    check_declared_version(model, diagnostics);
    for (const std::string& name : model.extensionsUsed) {
        if (!implemented(name)) {
            diagnostics.warn_once("extension " + name, "extension " + Diagnostics::quoted(name) + " is not read; ignored");
        }
    }
}

}  // namespace blurcull::frontend::gltf
