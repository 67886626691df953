// The glTF loader's steps strung together, without the final
// validate_scene: for load_scene (scene/load_scene.hpp), which applies its
// camera overrides first and then validates once. Everything else calls
// load_gltf_scene (gltf_loader.hpp).
#pragma once

#include "scene/gltf/gltf_loader.hpp"

#include <string>

namespace blurcull::frontend::gltf {

// Checks the options, parses and validates the file, samples the nodes at
// both shutter ends, appends the meshes and sets up the camera.
Scene build_scene(const std::string& path, const GltfOptions& options, const WarningSink& warn);

// validate_scene with a failure worded as the loader's ("<path>: scene
// ..."); marks the scene validated.
void validate_loaded_scene(Scene& scene, const std::string& path);

}  // namespace blurcull::frontend::gltf
