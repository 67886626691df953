// KHR_lights_punctual: every light on a rendered node. The first directional
// light becomes the scene's light (direction and colour x intensity); point,
// spot and further directional lights go to Scene::lights (at most
// max_punctual_lights, the rest ignored with one warning). A file whose
// rendered nodes carry lights but no directional one turns the default light
// off: its own lights light it.
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/nodes.hpp"
#include "scene/scene.hpp"

#include <tiny_gltf.h>

#include <vector>

namespace blurcull::frontend::gltf {

// Sets scene.light_direction (towards the light: the node's +Z in the world
// at shutter open), scene.light_color and scene.lights (positions and spot
// axes from the node's world transform at shutter open).
void setup_light(const tinygltf::Model& model, const std::vector<int>& rendered, const NodePoses& poses, Scene& scene,
                 Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
