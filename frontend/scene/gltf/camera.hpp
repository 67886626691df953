// The scene's camera: the chosen (or first) perspective camera of the file,
// its view taken from the camera node's world matrix at both shutter ends,
// or an automatic camera framing the scene's bounds; then the thin lens.
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/gltf/nodes.hpp"
#include "scene/scene.hpp"
#include "scene/scene_checks.hpp"

#include <tiny_gltf.h>

#include <vector>

namespace blurcull::frontend::gltf {

// Sets scene.camera from the file (options.camera_index, or the first
// perspective camera in `rendered` order) or automatically, with
// options.aspect, options.lens_radius and options.focus_distance. Fails for
// a camera index the file does not have, an orthographic or unattached
// chosen camera, and a zero-scale camera node. `framing`: the bounds to
// frame (and focus on the centre of) instead of the scene's own.
void setup_camera(const tinygltf::Model& model, const std::vector<int>& rendered, const NodePoses& poses,
                  const GltfOptions& options, Scene& scene, Diagnostics& diagnostics,
                  const SceneStats* framing = nullptr);

}  // namespace blurcull::frontend::gltf
