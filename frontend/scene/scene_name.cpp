#include "scene/scene_name.hpp"

#include <cctype>

namespace blurcull::frontend {

namespace {

std::string lowercase(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

std::string base_name(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

SceneFileType scene_file_type(const std::string& name_or_path) {
    const std::string base = base_name(name_or_path);
    const std::size_t dot = base.find_last_of('.');
    if (dot == std::string::npos) return SceneFileType::none;
    const std::string extension = lowercase(base.substr(dot));
    if (extension == ".gltf") return SceneFileType::gltf;
    if (extension == ".glb") return SceneFileType::glb;
    return SceneFileType::unsupported;
}

bool is_gltf_file(const std::string& name_or_path) {
    const SceneFileType type = scene_file_type(name_or_path);
    return type == SceneFileType::gltf || type == SceneFileType::glb;
}

std::string stem(const std::string& path) {
    const std::string base = base_name(path);
    const std::size_t dot = base.find_last_of('.');
    return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

}  // namespace blurcull::frontend
