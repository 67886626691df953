#include "scene/gltf/validate.hpp"

#include "scene/gltf/accessors.hpp"

#include <cmath>
#include <string>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

void check_view_index(const tg::Model& model, int view, const std::string& owner, const Diagnostics& diagnostics) {
    if (view < 0 || static_cast<std::size_t>(view) >= model.bufferViews.size()) {
        diagnostics.fail(owner + " refers to buffer view " + std::to_string(view) + ", which does not exist");
    }
}

void validate_buffer_views(const tg::Model& model, const Diagnostics& diagnostics) {
    for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
        const tg::BufferView& view = model.bufferViews[v];
        if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
            diagnostics.fail("buffer view " + std::to_string(v) + " refers to buffer " + std::to_string(view.buffer) +
                             ", which does not exist");
        }
        const std::size_t buffer_size = model.buffers[static_cast<std::size_t>(view.buffer)].data.size();
        if (!span_fits(view.byteOffset, 1, 1, view.byteLength, buffer_size)) {
            diagnostics.fail("buffer view " + std::to_string(v) + " (offset " + std::to_string(view.byteOffset) +
                             ", length " + std::to_string(view.byteLength) + ") reads past the end of buffer " +
                             std::to_string(view.buffer) + " (" + std::to_string(buffer_size) + " bytes)");
        }
    }
}

void validate_sparse(const tg::Model& model, const tg::Accessor& accessor, const ElementLayout& layout,
                     const std::string& name, const Diagnostics& diagnostics) {
    const auto& sparse = accessor.sparse;
    if (sparse.count < 0 || static_cast<std::size_t>(sparse.count) > accessor.count) {
        diagnostics.fail(name + ": sparse count " + std::to_string(sparse.count) + " exceeds its count " +
                         std::to_string(accessor.count));
    }
    const std::size_t index_bytes = component_size(sparse.indices.componentType);
    if (index_bytes == 0 || sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        diagnostics.fail(name + ": sparse indices have an invalid component type");
    }
    check_view_index(model, sparse.indices.bufferView, name + " (sparse indices)", diagnostics);
    check_view_index(model, sparse.values.bufferView, name + " (sparse values)", diagnostics);
    const auto count = static_cast<std::size_t>(sparse.count);
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0 ||
        !span_fits(static_cast<std::size_t>(sparse.indices.byteOffset), count, index_bytes, index_bytes,
                   model.bufferViews[static_cast<std::size_t>(sparse.indices.bufferView)].byteLength)) {
        diagnostics.fail(name + ": sparse indices read past the end of buffer view " +
                         std::to_string(sparse.indices.bufferView));
    }
    if (!span_fits(static_cast<std::size_t>(sparse.values.byteOffset), count, layout.size, layout.size,
                   model.bufferViews[static_cast<std::size_t>(sparse.values.bufferView)].byteLength)) {
        diagnostics.fail(name + ": sparse values read past the end of buffer view " +
                         std::to_string(sparse.values.bufferView));
    }
}

void validate_accessor(const tg::Model& model, std::size_t index, const Diagnostics& diagnostics) {
    const tg::Accessor& accessor = model.accessors[index];
    const std::string name = "accessor " + std::to_string(index);
    const ElementLayout layout = layout_of(accessor);
    if (layout.size == 0) {
        diagnostics.fail(name + " has an unknown component type " + std::to_string(accessor.componentType) +
                         " or type " + std::to_string(accessor.type));
    }
    if (accessor.bufferView >= 0) {
        check_view_index(model, accessor.bufferView, name, diagnostics);
        const tg::BufferView& view = model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
        const std::size_t stride = view.byteStride == 0 ? layout.size : view.byteStride;
        if (stride < layout.size) {
            diagnostics.fail(name + ": buffer view " + std::to_string(accessor.bufferView) + " stride " +
                             std::to_string(stride) + " is smaller than an element (" +
                             std::to_string(layout.size) + " bytes)");
        }
        if (!span_fits(accessor.byteOffset, accessor.count, stride, layout.size, view.byteLength)) {
            diagnostics.fail(name + " reads past the end of buffer view " + std::to_string(accessor.bufferView));
        }
    } else if (accessor.bufferView != -1) {
        check_view_index(model, accessor.bufferView, name, diagnostics);
    } else if (accessor.count > kMaxElementsWithoutView) {
        diagnostics.fail(name + " has no buffer view and count " + std::to_string(accessor.count) + " (limit " +
                         std::to_string(kMaxElementsWithoutView) + ")");
    }
    if (accessor.sparse.isSparse) validate_sparse(model, accessor, layout, name, diagnostics);
}

// Node `index`'s children in range, none of them itself, none with a
// parent already; records it as their parent.
void record_children(const tg::Model& model, std::size_t index, std::vector<int>& parents,
                     const Diagnostics& diagnostics) {
    const std::string name = "node " + std::to_string(index);
    for (int child : model.nodes[index].children) {
        if (child < 0 || static_cast<std::size_t>(child) >= model.nodes.size()) {
            diagnostics.fail(name + " has child " + std::to_string(child) + ", which does not exist");
        }
        if (static_cast<std::size_t>(child) == index) diagnostics.fail("node cycle: " + name + " is its own child");
        int& parent = parents[static_cast<std::size_t>(child)];
        if (parent >= 0) {
            diagnostics.fail("node " + std::to_string(child) + " has two parents (nodes " + std::to_string(parent) +
                             " and " + std::to_string(index) + ")");
        }
        parent = static_cast<int>(index);
    }
}

// Mesh, camera and skin references in range; transform arrays of the right
// size and finite.
void validate_node_contents(const tg::Model& model, std::size_t index, const Diagnostics& diagnostics) {
    const tg::Node& node = model.nodes[index];
    const std::string name = "node " + std::to_string(index);
    auto check_reference = [&](int value, std::size_t available, const char* what) {
        if (value < -1 || (value >= 0 && static_cast<std::size_t>(value) >= available)) {
            diagnostics.fail(name + " refers to " + what + " " + std::to_string(value) + ", which does not exist");
        }
    };
    check_reference(node.mesh, model.meshes.size(), "mesh");
    check_reference(node.camera, model.cameras.size(), "camera");
    check_reference(node.skin, model.skins.size(), "skin");
    if (!node.matrix.empty() && node.matrix.size() != 16) diagnostics.fail(name + " matrix does not have 16 numbers");
    if (!node.translation.empty() && node.translation.size() != 3) {
        diagnostics.fail(name + " translation does not have 3 numbers");
    }
    if (!node.rotation.empty() && node.rotation.size() != 4) diagnostics.fail(name + " rotation does not have 4 numbers");
    if (!node.scale.empty() && node.scale.size() != 3) diagnostics.fail(name + " scale does not have 3 numbers");
    if (!finite_values(node.matrix) || !finite_values(node.translation) || !finite_values(node.rotation) ||
        !finite_values(node.scale)) {
        diagnostics.fail(name + " has a non-finite transform");
    }
}

// Every node has at most one parent, so walking up terminates unless there
// is a cycle; depths are memoised.
std::vector<std::size_t> node_depths(const std::vector<int>& parent, const Diagnostics& diagnostics) {
    const std::size_t count = parent.size();
    std::vector<std::size_t> depths(count, 0);
    std::vector<char> known(count, 0);
    for (std::size_t start = 0; start < count; ++start) {
        std::vector<std::size_t> chain;
        std::size_t node = start;
        while (!known[node] && parent[node] >= 0) {
            chain.push_back(node);
            if (chain.size() > count) {
                diagnostics.fail("node cycle: node " + std::to_string(start) + " is its own ancestor");
            }
            node = static_cast<std::size_t>(parent[node]);
        }
        std::size_t depth = known[node] ? depths[node] : 0;
        known[node] = 1;
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            depths[*it] = ++depth;
            known[*it] = 1;
        }
        if (depth > kMaxNodeDepth) {
            diagnostics.fail("node " + std::to_string(start) + " is nested " + std::to_string(depth) +
                             " levels deep (limit " + std::to_string(kMaxNodeDepth) + ")");
        }
    }
    return depths;
}

NodeTree validate_nodes(const tg::Model& model, const Diagnostics& diagnostics) {
    NodeTree tree;
    tree.parent.assign(model.nodes.size(), -1);
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        record_children(model, i, tree.parent, diagnostics);
        validate_node_contents(model, i, diagnostics);
    }
    tree.depth = node_depths(tree.parent, diagnostics);
    for (std::size_t s = 0; s < model.scenes.size(); ++s) {
        for (int root : model.scenes[s].nodes) {
            if (root < 0 || static_cast<std::size_t>(root) >= model.nodes.size()) {
                diagnostics.fail("scene " + std::to_string(s) + " refers to node " + std::to_string(root) +
                                 ", which does not exist");
            }
        }
    }
    return tree;
}

void validate_primitives(const tg::Model& model, const Diagnostics& diagnostics) {
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        const auto& primitives = model.meshes[m].primitives;
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            const tg::Primitive& primitive = primitives[p];
            const std::string name = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            for (const auto& attribute : primitive.attributes) {
                check_accessor_index(model, attribute.second, name + " attribute " + attribute.first, diagnostics);
            }
            for (std::size_t k = 0; k < primitive.targets.size(); ++k) {
                for (const auto& attribute : primitive.targets[k]) {
                    check_accessor_index(model, attribute.second,
                                         name + " morph target " + std::to_string(k) + " " + attribute.first,
                                         diagnostics);
                }
            }
            if (primitive.indices != -1) check_accessor_index(model, primitive.indices, name + " indices", diagnostics);
            if (primitive.material < -1 ||
                (primitive.material >= 0 && static_cast<std::size_t>(primitive.material) >= model.materials.size())) {
                diagnostics.fail(name + " refers to material " + std::to_string(primitive.material) +
                                 ", which does not exist");
            }
        }
    }
}

void validate_skins(const tg::Model& model, const Diagnostics& diagnostics) {
    for (std::size_t s = 0; s < model.skins.size(); ++s) {
        const tg::Skin& skin = model.skins[s];
        const std::string name = "skin " + std::to_string(s);
        for (int joint : skin.joints) {
            if (joint < 0 || static_cast<std::size_t>(joint) >= model.nodes.size()) {
                diagnostics.fail(name + " refers to joint node " + std::to_string(joint) + ", which does not exist");
            }
        }
        if (skin.inverseBindMatrices == -1) continue;
        check_accessor_index(model, skin.inverseBindMatrices, name + " inverseBindMatrices", diagnostics);
        const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(skin.inverseBindMatrices)];
        if (accessor.type != TINYGLTF_TYPE_MAT4 || accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
            diagnostics.fail(name + " inverseBindMatrices accessor is not float MAT4");
        }
        if (accessor.count < skin.joints.size()) {
            diagnostics.fail(name + " has " + std::to_string(skin.joints.size()) + " joints but only " +
                             std::to_string(accessor.count) + " inverse bind matrices");
        }
    }
}

void validate_cameras(const tg::Model& model, const Diagnostics& diagnostics) {
    for (std::size_t c = 0; c < model.cameras.size(); ++c) {
        const tg::Camera& camera = model.cameras[c];
        const std::string name = "camera " + std::to_string(c);
        if (camera.type == "perspective") {
            const double yfov = camera.perspective.yfov;
            if (!std::isfinite(yfov) || yfov <= 0.0 || yfov >= 3.14159265) {
                diagnostics.fail(name + " has yfov " + std::to_string(yfov) + " (must be in (0, pi))");
            }
            const double znear = camera.perspective.znear;
            if (!std::isfinite(znear) || znear <= 0.0) {
                diagnostics.fail(name + " has znear " + std::to_string(znear) + " (must be positive)");
            }
            // zfar 0 is tinygltf's "absent" (an infinite projection).
            const double zfar = camera.perspective.zfar;
            if (zfar != 0.0 && !(zfar > znear)) {
                diagnostics.fail(name + " has zfar " + std::to_string(zfar) + " (must be greater than znear " +
                                 std::to_string(znear) + ")");
            }
        } else if (camera.type != "orthographic") {
            diagnostics.fail(name + " has unknown type '" + camera.type + "'");
        }
    }
}

}  // namespace

void check_accessor_index(const tg::Model& model, int accessor, const std::string& owner,
                          const Diagnostics& diagnostics) {
    if (accessor < 0 || static_cast<std::size_t>(accessor) >= model.accessors.size()) {
        diagnostics.fail(owner + " refers to accessor " + std::to_string(accessor) + ", which does not exist");
    }
}

NodeTree validate_model(const tg::Model& model, const Diagnostics& diagnostics) {
    validate_buffer_views(model, diagnostics);
    for (std::size_t a = 0; a < model.accessors.size(); ++a) validate_accessor(model, a, diagnostics);
    NodeTree tree = validate_nodes(model, diagnostics);
    validate_primitives(model, diagnostics);
    validate_skins(model, diagnostics);
    validate_cameras(model, diagnostics);
    return tree;
}

}  // namespace blurcull::frontend::gltf
