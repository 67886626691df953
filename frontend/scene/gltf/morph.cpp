#include "scene/gltf/morph.hpp"

#include "scene/gltf/accessors.hpp"

#include <algorithm>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

// The morph target count of mesh `m`: the same for every primitive, as glTF
// requires, and matched by mesh.weights when the mesh has them.
std::size_t target_count(const tg::Model& model, std::size_t m, const Diagnostics& diagnostics) {
    const tg::Mesh& mesh = model.meshes[m];
    const std::string name = "mesh " + std::to_string(m);
    const std::size_t count = mesh.primitives.empty() ? 0 : mesh.primitives.front().targets.size();
    for (std::size_t p = 1; p < mesh.primitives.size(); ++p) {
        if (mesh.primitives[p].targets.size() != count) {
            diagnostics.fail(name + " primitive " + std::to_string(p) + " has " +
                             std::to_string(mesh.primitives[p].targets.size()) + " morph targets, primitive 0 has " +
                             std::to_string(count));
        }
    }
    if (!mesh.weights.empty() && mesh.weights.size() != count) {
        diagnostics.fail(name + " has " + std::to_string(mesh.weights.size()) + " weights for " +
                         std::to_string(count) + " morph targets");
    }
    return count;
}

std::vector<float> to_weights(const std::vector<double>& values, const std::string& owner,
                              const Diagnostics& diagnostics) {
    if (!finite_values(values)) diagnostics.fail(owner + " has a non-finite morph weight");
    return std::vector<float>(values.begin(), values.end());
}

// node.weights, else mesh.weights, else zeros, for every node with a mesh.
NodeWeights default_weights(const tg::Model& model, const Diagnostics& diagnostics) {
    std::vector<std::size_t> counts(model.meshes.size());
    for (std::size_t m = 0; m < model.meshes.size(); ++m) counts[m] = target_count(model, m, diagnostics);
    NodeWeights weights(model.nodes.size());
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
        const tg::Node& node = model.nodes[n];
        if (node.mesh < 0) continue;
        const auto m = static_cast<std::size_t>(node.mesh);
        const std::string name = "node " + std::to_string(n);
        if (!node.weights.empty()) {
            if (node.weights.size() != counts[m]) {
                diagnostics.fail(name + " has " + std::to_string(node.weights.size()) + " weights but mesh " +
                                 std::to_string(m) + " has " + std::to_string(counts[m]) + " morph targets");
            }
            weights[n] = to_weights(node.weights, name, diagnostics);
        } else if (!model.meshes[m].weights.empty()) {
            weights[n] = to_weights(model.meshes[m].weights, "mesh " + std::to_string(m), diagnostics);
        } else {
            weights[n].assign(counts[m], 0.0f);
        }
    }
    return weights;
}

}  // namespace

NodeWeights morph_weights(const tg::Model& model, const AnimationSamplers& samplers, int animation_index, float t,
                          Diagnostics& diagnostics) {
    NodeWeights weights = default_weights(model, diagnostics);
    if (animation_index < 0 || static_cast<std::size_t>(animation_index) >= model.animations.size()) return weights;
    const auto a = static_cast<std::size_t>(animation_index);
    const auto& channels = model.animations[a].channels;
    for (std::size_t c = 0; c < channels.size(); ++c) {
        const tg::AnimationChannel& channel = channels[c];
        if (channel.target_path != "weights" || channel.target_node < 0) continue;
        std::vector<float>& node_weights = weights[static_cast<std::size_t>(channel.target_node)];
        const std::string name = "animation " + std::to_string(a) + " channel " + std::to_string(c);
        if (node_weights.empty()) {
            diagnostics.warn_once("weights without targets",
                                  name + " animates the weights of node " + std::to_string(channel.target_node) +
                                      ", which has no morph targets; ignored");
            continue;
        }
        const Sampler& sampler = samplers[a][static_cast<std::size_t>(channel.sampler)];
        if (sampler.components != node_weights.size()) {
            diagnostics.fail(name + " has " + std::to_string(sampler.components) + " weights per key for node " +
                             std::to_string(channel.target_node) + "'s " + std::to_string(node_weights.size()) +
                             " morph targets");
        }
        node_weights = evaluate(sampler, t, false);
    }
    return weights;
}

MorphedPositions morphed_positions(const tg::Model& model, const tg::Primitive& primitive,
                                   const std::vector<double>& base, const std::vector<float>& weights_open,
                                   const std::vector<float>& weights_close, const std::string& name,
                                   Diagnostics& diagnostics) {
    MorphedPositions positions{base, base};
    const std::size_t vertex_count = base.size() / 3;
    const std::size_t targets = std::min(primitive.targets.size(), std::min(weights_open.size(), weights_close.size()));
    for (std::size_t k = 0; k < targets; ++k) {
        const auto& target = primitive.targets[k];
        if (target.size() > target.count("POSITION")) {
            diagnostics.warn_once("morph attributes", "morph target attributes other than POSITION are ignored");
        }
        const auto position = target.find("POSITION");
        if (position == target.end()) continue;
        const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(position->second)];
        const std::string target_name = name + " morph target " + std::to_string(k) + " POSITION";
        if (accessor.type != TINYGLTF_TYPE_VEC3) diagnostics.fail(target_name + " is not VEC3");
        if (accessor.count != vertex_count) {
            diagnostics.fail(target_name + " has " + std::to_string(accessor.count) + " elements for " +
                             std::to_string(vertex_count) + " vertices");
        }
        const double w_open = weights_open[k], w_close = weights_close[k];
        if (w_open == 0.0 && w_close == 0.0) continue;
        const std::vector<double> offsets = read_values(model, position->second, diagnostics);
        for (std::size_t i = 0; i < base.size(); ++i) {
            positions.open[i] += w_open * offsets[i];
            positions.close[i] += w_close * offsets[i];
        }
    }
    return positions;
}

}  // namespace blurcull::frontend::gltf
