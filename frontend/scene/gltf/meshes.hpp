// The triangles of the rendered mesh nodes: primitive modes converted to
// triangle lists, indices checked, positions put in the world at both
// shutter ends (node transform or skin), base colours turned into
// materials, all appended to the Scene.
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/nodes.hpp"
#include "scene/scene.hpp"

#include <tiny_gltf.h>

#include <vector>

namespace blurcull::frontend::gltf {

// Appends every primitive of every rendered node that has a mesh, in node
// order. Points, lines, primitives without POSITION and primitives with
// non-finite positions are skipped with a warning; anything malformed fails.
void add_mesh_instances(const tinygltf::Model& model, const std::vector<int>& rendered, const NodePoses& poses,
                        Scene& scene, Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
