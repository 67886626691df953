// The node hierarchy: each node's local transform (matrix or TRS), which
// nodes the rendered scene contains, and world matrices composed parent
// before child.
#pragma once

#include "scene/gltf/validate.hpp"

#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace blurcull::frontend::gltf {

struct NodeTransform {
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
    bool uses_matrix = false;
    glm::mat4 matrix{1.0f};

    // The node's matrix, or T * R * S.
    glm::mat4 local() const;
};

// World matrix of every node at the two shutter ends, and its morph target
// weights there (empty for a node without morph targets; morph.hpp).
struct NodePoses {
    std::vector<glm::mat4> open;
    std::vector<glm::mat4> close;
    std::vector<std::vector<float>> weights_open;
    std::vector<std::vector<float>> weights_close;
};

// The nodes of the default scene (else scene 0, else every parentless node),
// depth first in file order, each once.
std::vector<int> rendered_nodes(const tinygltf::Model& model, const NodeTree& tree);

// Every node's transform as the file gives it, before animation.
std::vector<NodeTransform> file_transforms(const tinygltf::Model& model);

// World matrices: rotations normalised (a zero quaternion becomes the
// identity), each local transform composed with its parent's world matrix.
std::vector<glm::mat4> world_matrices(const NodeTree& tree, std::vector<NodeTransform> transforms);

}  // namespace blurcull::frontend::gltf
