// Linear blend skinning at both shutter ends: joint matrices from the
// joints' world matrices and the inverse bind matrices, every JOINTS_n /
// WEIGHTS_n set blended, weights renormalised.
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/nodes.hpp"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace blurcull::frontend::gltf {

// Skins the primitive's positions at open and close (`raw_open`,
// `raw_close`: x y z per vertex, already morphed) with the node's skin into
// world positions at open and close (sized to the vertex count). Returns
// false, leaving the node transform to the caller, when no vertex has any
// weight. `name` names the primitive in messages.
bool skin_vertices(const tinygltf::Model& model, const NodePoses& poses, const std::vector<double>& raw_open,
                   const std::vector<double>& raw_close, const tinygltf::Node& node, const tinygltf::Primitive& primitive, const std::string& name,
                   std::vector<glm::vec3>& open, std::vector<glm::vec3>& close, Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
