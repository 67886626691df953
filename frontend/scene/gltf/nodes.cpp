#include "scene/gltf/nodes.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>

namespace blurcull::frontend::gltf {

namespace tg = tinygltf;

glm::mat4 NodeTransform::local() const {
    if (uses_matrix) return matrix;
    return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
           glm::scale(glm::mat4(1.0f), scale);
}

std::vector<int> rendered_nodes(const tg::Model& model, const NodeTree& tree) {
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        const std::size_t scene =
            model.defaultScene >= 0 && static_cast<std::size_t>(model.defaultScene) < model.scenes.size()
                ? static_cast<std::size_t>(model.defaultScene)
                : 0;
        roots = model.scenes[scene].nodes;
    } else {
        for (std::size_t i = 0; i < model.nodes.size(); ++i) {
            if (tree.parent[i] < 0) roots.push_back(static_cast<int>(i));
        }
    }
    std::vector<int> rendered;
    std::vector<char> seen(model.nodes.size(), 0);
    std::vector<int> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
        const int node = stack.back();
        stack.pop_back();
        if (seen[static_cast<std::size_t>(node)]) continue;
        seen[static_cast<std::size_t>(node)] = 1;
        rendered.push_back(node);
        const auto& children = model.nodes[static_cast<std::size_t>(node)].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
    }
    return rendered;
}

std::vector<NodeTransform> file_transforms(const tg::Model& model) {
    std::vector<NodeTransform> transforms(model.nodes.size());
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const tg::Node& node = model.nodes[i];
        NodeTransform& transform = transforms[i];
        if (node.matrix.size() == 16) {
            transform.uses_matrix = true;
            for (int k = 0; k < 16; ++k) {
                glm::value_ptr(transform.matrix)[k] = static_cast<float>(node.matrix[static_cast<std::size_t>(k)]);
            }
        }
        if (node.translation.size() == 3) {
            transform.translation =
                glm::vec3(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                          static_cast<float>(node.translation[2]));
        }
        if (node.rotation.size() == 4) {
            transform.rotation = glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                                           static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
        }
        if (node.scale.size() == 3) {
            transform.scale = glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                                        static_cast<float>(node.scale[2]));
        }
    }
    return transforms;
}

std::vector<glm::mat4> world_matrices(const NodeTree& tree, std::vector<NodeTransform> transforms) {
    const std::size_t count = transforms.size();
    for (NodeTransform& transform : transforms) {
        const float length = glm::length(transform.rotation);
        transform.rotation = length > 0.0f ? transform.rotation / length : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    }
    // Parents before children: process in order of depth.
    std::vector<std::size_t> order(count);
    for (std::size_t i = 0; i < count; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return tree.depth[a] < tree.depth[b]; });
    std::vector<glm::mat4> world(count, glm::mat4(1.0f));
    for (std::size_t i : order) {
        const glm::mat4 local = transforms[i].local();
        world[i] = tree.parent[i] >= 0 ? world[static_cast<std::size_t>(tree.parent[i])] * local : local;
    }
    return world;
}

}  // namespace blurcull::frontend::gltf
