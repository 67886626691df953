// Morph targets: every node's target weights at one animation time
// (node.weights, else its mesh's weights, else zeros, then the animation's
// "weights" channels), and a primitive's POSITION moved by its weighted
// targets. glTF's order is morph, then skin, then node transform: the
// morphed positions are what skin.hpp and the node matrix then move.
#pragma once

#include "scene/gltf/animation.hpp"
#include "scene/gltf/diagnostics.hpp"

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace blurcull::frontend::gltf {

// weights[node][target]; empty for a node without a mesh or whose mesh has
// no morph targets.
using NodeWeights = std::vector<std::vector<float>>;

// Every node's morph weights at animation time t (animation
// `animation_index`, -1 for none), interpolated as animation.hpp's
// `evaluate` does. Fails when a mesh's primitives disagree on their target
// count, when node.weights, mesh.weights or a weights channel has another
// count, or when a weight is not finite; a weights channel on a node
// without morph targets is ignored with a warning.
NodeWeights morph_weights(const tinygltf::Model& model, const AnimationSamplers& samplers, int animation_index,
                          float t, Diagnostics& diagnostics);

// The primitive's positions at the two shutter ends: `base` (x y z per
// vertex, as read_values gives POSITION) plus the sum of weight * target
// POSITION over its targets (sparse accessors included), with the node's
// weights at open and at close. A target is read once, and not at all when
// both its weights are 0. Fails for a target POSITION that is not VEC3 or
// has another vertex count, naming the primitive as `name`. Other target
// attributes warn once and are ignored.
struct MorphedPositions {
    std::vector<double> open;
    std::vector<double> close;
};
MorphedPositions morphed_positions(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                   const std::vector<double>& base, const std::vector<float>& weights_open,
                                   const std::vector<float>& weights_close, const std::string& name,
                                   Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
