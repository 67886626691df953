// The one rule that tells a scene file from a built-in scene name, used by
// every loader and by the command: a name whose extension (the part after the
// last '.' of the last path component) is .gltf or .glb, in any case, is a
// glTF file; any other extension is an unsupported file; no extension is a
// built-in scene name.
#pragma once

#include <string>

namespace blurcull::frontend {

enum class SceneFileType {
    none,         // no extension: a built-in scene name
    gltf,         // .gltf (JSON), any case
    glb,          // .glb (binary glTF), any case
    unsupported,  // another extension
};

// Applies the rule above to a scene name or path.
SceneFileType scene_file_type(const std::string& name_or_path);

// True for .gltf and .glb (any case): the file goes to the glTF loader.
bool is_gltf_file(const std::string& name_or_path);

// The last path component without its extension ("scenes/a.gltf" -> "a").
// A name whose only dot is its first character keeps it (".glb" -> ".glb").
std::string stem(const std::string& path);

}  // namespace blurcull::frontend
