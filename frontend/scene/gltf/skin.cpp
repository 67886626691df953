#include "scene/gltf/skin.hpp"

#include "scene/gltf/accessors.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

std::vector<glm::mat4> joint_matrices(const tg::Model& model, const tg::Skin& skin,
                                      const std::vector<glm::mat4>& world, const Diagnostics& diagnostics) {
    std::vector<glm::mat4> inverse_bind(skin.joints.size(), glm::mat4(1.0f));
    if (skin.inverseBindMatrices >= 0) {
        const std::vector<double> values = read_values(model, skin.inverseBindMatrices, diagnostics);
        for (std::size_t j = 0; j < skin.joints.size(); ++j) {
            for (std::size_t k = 0; k < 16; ++k) {
                glm::value_ptr(inverse_bind[j])[k] = static_cast<float>(values[j * 16 + k]);
            }
        }
    }
    std::vector<glm::mat4> joints(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        joints[j] = world[static_cast<std::size_t>(skin.joints[j])] * inverse_bind[j];
    }
    return joints;
}

// Sums of weight * joint matrix per vertex at both shutter ends, and of the weights.
struct Blend {
    std::vector<glm::mat4> open;
    std::vector<glm::mat4> close;
    std::vector<float> weight_sum;
};

// Adds one JOINTS_n / WEIGHTS_n set to the blend.
void blend_set(const tg::Model& model, const tg::Skin& skin, int joints_accessor_index, int weights_accessor_index,
               int set, const std::string& name, const std::vector<glm::mat4>& joints_open,
               const std::vector<glm::mat4>& joints_close, Blend& blend, const Diagnostics& diagnostics) {
    const std::size_t vertex_count = blend.weight_sum.size();
    const std::string set_name = name + " JOINTS_" + std::to_string(set);
    const tg::Accessor& joints_accessor = model.accessors[static_cast<std::size_t>(joints_accessor_index)];
    const tg::Accessor& weights_accessor = model.accessors[static_cast<std::size_t>(weights_accessor_index)];
    if (joints_accessor.type != TINYGLTF_TYPE_VEC4 || weights_accessor.type != TINYGLTF_TYPE_VEC4) {
        diagnostics.fail(set_name + " / WEIGHTS_" + std::to_string(set) + " are not VEC4");
    }
    if (joints_accessor.count != vertex_count || weights_accessor.count != vertex_count) {
        diagnostics.fail(set_name + " / WEIGHTS_" + std::to_string(set) + " do not have one entry per vertex");
    }
    const std::vector<std::uint32_t> joint_ids = read_integers(model, joints_accessor_index, set_name, diagnostics);
    const std::vector<double> weights = read_values(model, weights_accessor_index, diagnostics);
    for (std::size_t v = 0; v < vertex_count; ++v) {
        for (std::size_t k = 0; k < 4; ++k) {
            const auto weight = static_cast<float>(weights[4 * v + k]);
            if (!std::isfinite(weight)) diagnostics.fail(name + " has a non-finite skin weight");
            if (weight == 0.0f) continue;
            const std::uint32_t joint = joint_ids[4 * v + k];
            if (joint >= skin.joints.size()) {
                diagnostics.fail(set_name + ": joint " + std::to_string(joint) + " of vertex " + std::to_string(v) +
                                 " is not below the skin's joint count " + std::to_string(skin.joints.size()));
            }
            blend.open[v] += weight * joints_open[joint];
            blend.close[v] += weight * joints_close[joint];
            blend.weight_sum[v] += weight;
        }
    }
}

// Vertex v of x y z positions as a point.
glm::vec4 vertex(const std::vector<double>& raw, std::size_t v) {
    return glm::vec4(static_cast<float>(raw[3 * v]), static_cast<float>(raw[3 * v + 1]),
                     static_cast<float>(raw[3 * v + 2]), 1.0f);
}

}  // namespace

bool skin_vertices(const tg::Model& model, const NodePoses& poses, const std::vector<double>& raw_open,
                   const std::vector<double>& raw_close, const tg::Node& node, const tg::Primitive& primitive, const std::string& name,
                   std::vector<glm::vec3>& open, std::vector<glm::vec3>& close, Diagnostics& diagnostics) {
    const tg::Skin& skin = model.skins[static_cast<std::size_t>(node.skin)];
    const std::size_t vertex_count = raw_open.size() / 3;
    const std::vector<glm::mat4> joints_open = joint_matrices(model, skin, poses.open, diagnostics);
    const std::vector<glm::mat4> joints_close = joint_matrices(model, skin, poses.close, diagnostics);
    Blend blend{std::vector<glm::mat4>(vertex_count, glm::mat4(0.0f)),
                std::vector<glm::mat4>(vertex_count, glm::mat4(0.0f)), std::vector<float>(vertex_count, 0.0f)};
    for (int set = 0;; ++set) {
        const auto joints = primitive.attributes.find("JOINTS_" + std::to_string(set));
        const auto weights = primitive.attributes.find("WEIGHTS_" + std::to_string(set));
        if (joints == primitive.attributes.end() || weights == primitive.attributes.end()) break;
        blend_set(model, skin, joints->second, weights->second, set, name, joints_open, joints_close, blend,
                  diagnostics);
    }
    bool any_weight = false;
    for (std::size_t v = 0; v < vertex_count; ++v) {
        const glm::vec4 p0 = vertex(raw_open, v), p1 = vertex(raw_close, v);
        if (blend.weight_sum[v] > 0.0f) {
            any_weight = true;
            // Exporters round weights; renormalise instead of shrinking.
            open[v] = glm::vec3(blend.open[v] * p0) / blend.weight_sum[v];
            close[v] = glm::vec3(blend.close[v] * p1) / blend.weight_sum[v];
        } else {
            diagnostics.warn_once("unweighted " + name,
                                  name + " has vertices without skin weights; they are left untransformed");
            open[v] = glm::vec3(p0);
            close[v] = glm::vec3(p1);
        }
    }
    return any_weight;
}

}  // namespace blurcull::frontend::gltf
