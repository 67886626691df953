// Nothing in a file is trusted: every index and byte range of a parsed model
// is checked here, before any data is read (animation samplers are checked
// as they are decoded, in animation.hpp).
#pragma once

#include "scene/gltf/diagnostics.hpp"

#include <tiny_gltf.h>

#include <cstddef>
#include <vector>

namespace blurcull::frontend::gltf {

constexpr std::size_t kMaxNodeDepth = 1000;

// The node hierarchy once cycles and second parents are ruled out.
struct NodeTree {
    std::vector<int> parent;          // -1 for a node without a parent
    std::vector<std::size_t> depth;   // 0 for a root; at most kMaxNodeDepth
};

// Checks, in this order: buffer views against their buffers and every
// accessor (types, strides, byte ranges, sparse parts); nodes (children,
// references, transform sizes, finiteness, cycles, depth) and scene roots;
// mesh primitives, skins and materials; cameras. Fails on the first problem;
// returns the node tree.
NodeTree validate_model(const tinygltf::Model& model, const Diagnostics& diagnostics);

// Fails unless `accessor` indexes an accessor of the model, naming `owner`.
void check_accessor_index(const tinygltf::Model& model, int accessor, const std::string& owner,
                          const Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
