#include "scene/gltf/meshes.hpp"

#include "scene/gltf/accessors.hpp"
#include "scene/gltf/morph.hpp"
#include "scene/gltf/skin.hpp"
#include "scene/gltf/surface.hpp"
#include "scene/gltf/textures.hpp"
#include "scene/scene_builder.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

// The primitive's mode (TRIANGLES when absent) when it is made of
// triangles; -1, after a warning, for points and lines. Fails for an
// unknown mode.
int triangle_mode(const tg::Primitive& primitive, const std::string& name, Diagnostics& diagnostics) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode == TINYGLTF_MODE_POINTS) {
        diagnostics.warn_once("points", "points primitives are skipped");
        return -1;
    }
    if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
        diagnostics.warn_once("lines", "line primitives are skipped");
        return -1;
    }
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        diagnostics.fail(name + " has unknown mode " + std::to_string(mode));
    }
    return mode;
}

// The primitive's vertex indices, each below vertex_count; 0, 1, 2, ...
// for a primitive without indices.
std::vector<std::uint32_t> primitive_indices(const tg::Model& model, const tg::Primitive& primitive,
                                             std::size_t vertex_count, const std::string& name,
                                             const Diagnostics& diagnostics) {
    std::vector<std::uint32_t> indices;
    if (primitive.indices >= 0) {
        if (model.accessors[static_cast<std::size_t>(primitive.indices)].type != TINYGLTF_TYPE_SCALAR) {
            diagnostics.fail(name + " index accessor " + std::to_string(primitive.indices) + " is not SCALAR");
        }
        indices = read_integers(model, primitive.indices, name + " index", diagnostics);
        for (std::size_t i = 0; i < indices.size(); ++i) {
            if (indices[i] >= vertex_count) {
                diagnostics.fail(name + ": index value " + std::to_string(indices[i]) + " (at " + std::to_string(i) +
                                 ") is not below the vertex count " + std::to_string(vertex_count));
            }
        }
    } else {
        if (vertex_count > std::numeric_limits<std::uint32_t>::max()) diagnostics.fail(name + " has too many vertices");
        indices.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<std::uint32_t>(i);
    }
    return indices;
}

// Triangle list, strip or fan indices as triangles.
std::vector<glm::uvec3> assemble_triangles(int mode, const std::vector<std::uint32_t>& indices,
                                           const std::string& name, Diagnostics& diagnostics) {
    std::vector<glm::uvec3> triangles;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (indices.size() % 3 != 0) {
            diagnostics.warn_once("partial " + name, name + ": index count is not a multiple of 3; the rest is ignored");
        }
        for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
            triangles.emplace_back(indices[i], indices[i + 1], indices[i + 2]);
        }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Every other triangle swaps its first two corners to keep the winding.
        for (std::size_t i = 0; i + 2 < indices.size(); ++i) {
            if (i % 2 == 0) triangles.emplace_back(indices[i], indices[i + 1], indices[i + 2]);
            else triangles.emplace_back(indices[i + 1], indices[i], indices[i + 2]);
        }
    } else {
        for (std::size_t i = 1; i + 1 < indices.size(); ++i) {
            triangles.emplace_back(indices[i], indices[i + 1], indices[0]);
        }
    }
    return triangles;
}

bool all_finite(const std::vector<glm::vec3>& open, const std::vector<glm::vec3>& close) {
    for (std::size_t v = 0; v < open.size(); ++v) {
        for (const glm::vec3& q : {open[v], close[v]}) {
            if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return false;
        }
    }
    return true;
}

// m * (x, y, z, 1) for every vertex of `raw` (x y z per vertex).
void transform_positions(const glm::mat4& m, const std::vector<double>& raw, std::vector<glm::vec3>& out) {
    for (std::size_t v = 0; v < out.size(); ++v) {
        const glm::vec4 p(static_cast<float>(raw[3 * v]), static_cast<float>(raw[3 * v + 1]),
                          static_cast<float>(raw[3 * v + 2]), 1.0f);
        out[v] = glm::vec3(m * p);
    }
}

class MeshInstancer {
public:
    MeshInstancer(const tg::Model& model, const NodePoses& poses, Scene& scene, Diagnostics& diagnostics)
        : model_(model), poses_(poses), scene_(scene), diagnostics_(diagnostics) {}

    void add_node(int node_index) {
        const tg::Node& node = model_.nodes[static_cast<std::size_t>(node_index)];
        const tg::Mesh& mesh = model_.meshes[static_cast<std::size_t>(node.mesh)];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            add_primitive(node_index, mesh.primitives[p],
                          "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p));
        }
    }

private:
    void add_primitive(int node_index, const tg::Primitive& primitive, const std::string& name) {
        const int mode = triangle_mode(primitive, name, diagnostics_);
        if (mode < 0) return;
        const auto position_attribute = primitive.attributes.find("POSITION");
        if (position_attribute == primitive.attributes.end()) {
            diagnostics_.warn_once("no position", name + " has no POSITION attribute; skipped");
            return;
        }
        const int position_accessor = position_attribute->second;
        if (model_.accessors[static_cast<std::size_t>(position_accessor)].type != TINYGLTF_TYPE_VEC3) {
            diagnostics_.fail(name + " POSITION accessor " + std::to_string(position_accessor) + " is not VEC3");
        }
        const std::vector<double> raw = read_values(model_, position_accessor, diagnostics_);
        const std::size_t vertex_count = raw.size() / 3;
        if (!finite_values(raw)) {
            diagnostics_.warn_once("nonfinite " + name, name + " has non-finite positions; skipped");
            return;
        }
        const std::vector<glm::uvec3> triangles = assemble_triangles(
            mode, primitive_indices(model_, primitive, vertex_count, name, diagnostics_), name, diagnostics_);
        if (triangles.empty()) return;

        std::vector<glm::vec3> open(vertex_count), close(vertex_count);
        const bool skinned = world_positions(node_index, primitive, raw, name, open, close);
        if (!all_finite(open, close)) {
            diagnostics_.warn_once("nonfinite " + name, name + " has non-finite transformed positions; skipped");
            return;
        }
        if (scene_.position_open.size() + vertex_count > std::numeric_limits<std::uint32_t>::max()) {
            diagnostics_.fail("scene has too many vertices");
        }
        const std::size_t first_vertex = scene_.position_open.size();
        append_mesh(scene_, open, close, triangles, material_for(primitive.material));
        append_surface_attributes(model_, primitive, poses_.open[static_cast<std::size_t>(node_index)], skinned,
                                  first_vertex, vertex_count, name, scene_, diagnostics_);
    }

    // glTF's order: morph targets (morph.hpp), then skinning when the node
    // has a skin and the primitive has joints (returns true), else the node's
    // world matrix.
    bool world_positions(int node_index, const tg::Primitive& primitive, const std::vector<double>& raw,
                         const std::string& name, std::vector<glm::vec3>& open, std::vector<glm::vec3>& close) {
        const auto node_slot = static_cast<std::size_t>(node_index);
        const tg::Node& node = model_.nodes[node_slot];
        const MorphedPositions morphed = morphed_positions(
            model_, primitive, raw, poses_.weights_open[node_slot], poses_.weights_close[node_slot], name, diagnostics_);
        if (node.skin >= 0 && primitive.attributes.count("JOINTS_0") && primitive.attributes.count("WEIGHTS_0") &&
            skin_vertices(model_, poses_, morphed.open, morphed.close, node, primitive, name, open, close,
                          diagnostics_)) {
            return true;
        }
        transform_positions(poses_.open[node_slot], morphed.open, open);
        transform_positions(poses_.close[node_slot], morphed.close, close);
        return false;
    }

    // The scene material of a glTF material index (-1: the grey "default"),
    // added on first use.
    std::uint32_t material_for(int gltf_material) {
        const auto found = material_map_.find(gltf_material);
        if (found != material_map_.end()) return found->second;
        Material material;
        if (gltf_material >= 0) {
            const tg::Material& source = model_.materials[static_cast<std::size_t>(gltf_material)];
            material.name = source.name;
            const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
            if (factor.size() >= 3 && finite_values(factor)) {
                material.base_color = glm::clamp(glm::vec3(static_cast<float>(factor[0]),
                                                           static_cast<float>(factor[1]),
                                                           static_cast<float>(factor[2])),
                                                 0.0f, 1.0f);
            }
            read_surface_material(source, textures_, material, diagnostics_);
        } else {
            material.name = "default";
        }
        const std::uint32_t index = add_material(scene_, material);
        material_map_.emplace(gltf_material, index);
        return index;
    }

    const tg::Model& model_;
    const NodePoses& poses_;
    Scene& scene_;
    Diagnostics& diagnostics_;
    std::map<int, std::uint32_t> material_map_;
    TextureLoader textures_{model_, scene_, diagnostics_};
};

}  // namespace

void add_mesh_instances(const tg::Model& model, const std::vector<int>& rendered, const NodePoses& poses,
                        Scene& scene, Diagnostics& diagnostics) {
    MeshInstancer instancer(model, poses, scene, diagnostics);
    for (int node : rendered) {
        if (model.nodes[static_cast<std::size_t>(node)].mesh >= 0) instancer.add_node(node);
    }
}

}  // namespace blurcull::frontend::gltf
