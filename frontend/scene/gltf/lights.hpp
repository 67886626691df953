// KHR_lights_punctual: the first directional light on a rendered node becomes
// the scene's light (direction and colour x intensity); without one the
// default light stays. Other lights are ignored with a warning.
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/nodes.hpp"
#include "scene/scene.hpp"

#include <tiny_gltf.h>

#include <vector>

namespace blurcull::frontend::gltf {

// Sets scene.light_direction (towards the light: the node's +Z in the world
// at shutter open) and scene.light_color from the first directional light.
void setup_light(const tinygltf::Model& model, const std::vector<int>& rendered, const NodePoses& poses, Scene& scene,
                 Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
