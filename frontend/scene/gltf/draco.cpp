#include "scene/gltf/draco.hpp"

#include "scene/gltf/accessors.hpp"
#include "scene/gltf/compressed_json.hpp"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

constexpr const char* kExtension = "KHR_draco_mesh_compression";

// The bytes of a new accessor's values go into one buffer for the whole
// file; each gets its own view.
struct DecodedBuffer {
    std::size_t index = 0;  // in model.buffers, once pushed
    tg::Buffer buffer;
    bool used = false;
    // Primitives may share one Draco mesh: the file's decoded bytes are held
    // to 256 times all its buffers' bytes (plus 1 MiB), checked per mesh
    // before its values are converted.
    std::size_t limit = 0;

    bool fits(std::size_t more) const { return more <= limit - std::min(limit, buffer.data.size()); }

    // A view over `bytes` appended to the buffer; returns its index.
    int add_view(tg::Model& model, const std::vector<unsigned char>& bytes) {
        while (buffer.data.size() % 4 != 0) buffer.data.push_back(0);
        tg::BufferView view;
        view.buffer = static_cast<int>(index);
        view.byteOffset = buffer.data.size();
        view.byteLength = bytes.size();
        buffer.data.insert(buffer.data.end(), bytes.begin(), bytes.end());
        model.bufferViews.push_back(view);
        used = true;
        return static_cast<int>(model.bufferViews.size() - 1);
    }
};

// One converted value per component, in the accessor's component type.
template <typename T>
bool convert_values(const draco::PointAttribute& attribute, std::size_t count, std::size_t components,
                    std::vector<unsigned char>& bytes) {
    if (!attribute.is_mapping_identity() && attribute.indices_map_size() < count) return false;
    std::vector<T> element(components);
    bytes.resize(count * components * sizeof(T));
    for (std::size_t i = 0; i < count; ++i) {
        const draco::AttributeValueIndex value =
            attribute.mapped_index(draco::PointIndex(static_cast<std::uint32_t>(i)));
        if (value.value() >= attribute.size()) return false;
        if (!attribute.ConvertValue<T>(value, static_cast<std::int8_t>(components), element.data())) return false;
        std::memcpy(bytes.data() + i * components * sizeof(T), element.data(), components * sizeof(T));
    }
    return true;
}

bool convert_attribute(const draco::PointAttribute& attribute, int component_type, std::size_t count,
                       std::size_t components, std::vector<unsigned char>& bytes) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return convert_values<std::int8_t>(attribute, count, components, bytes);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return convert_values<std::uint8_t>(attribute, count, components, bytes);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return convert_values<std::int16_t>(attribute, count, components, bytes);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return convert_values<std::uint16_t>(attribute, count, components, bytes);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return convert_values<std::uint32_t>(attribute, count, components, bytes);
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return convert_values<float>(attribute, count, components, bytes);
        default: return false;
    }
}

// The accessor `index` of `owner`, checked to exist and to be small enough
// to be filled.
const tg::Accessor& checked_accessor(const tg::Model& model, int index, const std::string& owner,
                                     const Diagnostics& diagnostics) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
        diagnostics.fail(owner + " refers to accessor " + std::to_string(index) + ", which does not exist");
    }
    const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
    if (accessor.count > kMaxElementsWithoutView) {
        diagnostics.fail(owner + ": accessor " + std::to_string(index) + " count " + std::to_string(accessor.count) +
                         " is over the " + kExtension + " limit " + std::to_string(kMaxElementsWithoutView));
    }
    return accessor;
}

// The decoded mesh of `primitive`'s extension, read from its buffer view.
std::unique_ptr<draco::Mesh> decode_mesh(const tg::Model& model, int view_index, const std::string& owner,
                                         const Diagnostics& diagnostics) {
    if (view_index < 0 || static_cast<std::size_t>(view_index) >= model.bufferViews.size()) {
        diagnostics.fail(owner + ": " + kExtension + " buffer view " + std::to_string(view_index) +
                         " does not exist");
    }
    const tg::BufferView& view = model.bufferViews[static_cast<std::size_t>(view_index)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
        diagnostics.fail(owner + ": " + kExtension + " buffer view " + std::to_string(view_index) +
                         " refers to buffer " + std::to_string(view.buffer) + ", which does not exist");
    }
    const tg::Buffer& buffer = model.buffers[static_cast<std::size_t>(view.buffer)];
    if (!span_fits(view.byteOffset, 1, 1, view.byteLength, buffer.data.size())) {
        diagnostics.fail(owner + ": " + kExtension + " buffer view " + std::to_string(view_index) +
                         " reads past the end of buffer " + std::to_string(view.buffer));
    }
    draco::DecoderBuffer source;
    source.Init(reinterpret_cast<const char*>(buffer.data.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&source);
    if (!decoded.ok() || !decoded.value()) {
        diagnostics.fail(owner + ": " + kExtension + " data (" + std::to_string(view.byteLength) +
                         " bytes) cannot be decoded: " + Diagnostics::quoted(decoded.status().error_msg_string()));
    }
    return std::move(decoded).value();
}

// A copy of accessor `index` over new bytes; returns the copy's index.
int replaced_accessor(tg::Model& model, int index, const std::vector<unsigned char>& bytes, DecodedBuffer& out) {
    tg::Accessor accessor = model.accessors[static_cast<std::size_t>(index)];
    accessor.bufferView = out.add_view(model, bytes);
    accessor.byteOffset = 0;
    accessor.sparse = tg::Accessor{}.sparse;
    model.accessors.push_back(accessor);
    return static_cast<int>(model.accessors.size() - 1);
}

void decode_attributes(tg::Model& model, tg::Primitive& primitive, const draco::Mesh& mesh, const tg::Value& ids,
                       const std::string& owner, DecodedBuffer& out, const Diagnostics& diagnostics) {
    for (const std::string& name : ids.Keys()) {
        const auto target = primitive.attributes.find(name);
        if (target == primitive.attributes.end()) continue;  // not one the primitive uses
        const tg::Value& id = ids.Get(name);
        const double number = id.IsNumber() ? id.GetNumberAsDouble() : -1.0;
        const draco::PointAttribute* attribute =
            number >= 0.0 && number <= 4294967295.0 ? mesh.GetAttributeByUniqueId(static_cast<std::uint32_t>(number))
                                                    : nullptr;
        if (attribute == nullptr) {
            diagnostics.fail(owner + ": " + kExtension + " attribute " + Diagnostics::quoted(name) +
                             " has no attribute in the Draco mesh");
        }
        const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(target->second)];
        const ElementLayout layout = layout_of(accessor);
        if (layout.size == 0 || layout.columns != 1 || accessor.componentType == TINYGLTF_COMPONENT_TYPE_INT) {
            diagnostics.fail(owner + ": " + kExtension + " attribute " + Diagnostics::quoted(name) +
                             " has an accessor type Draco cannot fill");
        }
        if (accessor.count != mesh.num_points()) {
            diagnostics.fail(owner + ": " + kExtension + " attribute " + Diagnostics::quoted(name) + " accessor has " +
                             std::to_string(accessor.count) + " elements but the Draco mesh has " +
                             std::to_string(mesh.num_points()) + " points");
        }
        if (attribute->num_components() != layout.rows) {
            diagnostics.fail(owner + ": " + kExtension + " attribute " + Diagnostics::quoted(name) + " has " +
                             std::to_string(attribute->num_components()) + " components in the Draco mesh, " +
                             std::to_string(layout.rows) + " in its accessor");
        }
        std::vector<unsigned char> bytes;
        if (!convert_attribute(*attribute, accessor.componentType, accessor.count, layout.rows, bytes)) {
            diagnostics.fail(owner + ": " + kExtension + " attribute " + Diagnostics::quoted(name) +
                             " cannot be converted to its accessor's component type");
        }
        target->second = replaced_accessor(model, target->second, bytes, out);
    }
}

void decode_indices(tg::Model& model, tg::Primitive& primitive, const draco::Mesh& mesh, const std::string& owner,
                    DecodedBuffer& out, const Diagnostics& diagnostics) {
    const std::size_t count = std::size_t{mesh.num_faces()} * 3;
    int component_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    if (primitive.indices >= 0) {
        const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(primitive.indices)];
        if (accessor.count != count) {
            diagnostics.fail(owner + ": " + kExtension + " indices accessor has " + std::to_string(accessor.count) +
                             " elements but the Draco mesh has " + std::to_string(mesh.num_faces()) + " triangles");
        }
        component_type = accessor.componentType;
    }
    const std::size_t index_bytes = component_size(component_type);
    if (component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        diagnostics.fail(owner + ": " + kExtension + " indices accessor is not unsigned byte, short or int");
    }
    const std::uint64_t limit = index_bytes == 4 ? std::uint64_t{1} << 32 : std::uint64_t{1} << (8 * index_bytes);
    std::vector<unsigned char> bytes(count * index_bytes);
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
        const draco::Mesh::Face& face = mesh.face(f);
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t index = face[k].value();
            if (index >= mesh.num_points() || index >= limit) {
                diagnostics.fail(owner + ": " + kExtension + " index " + std::to_string(index) +
                                 " is not below the Draco mesh's " + std::to_string(mesh.num_points()) + " points");
            }
            const std::size_t at = (std::size_t{f.value()} * 3 + k) * index_bytes;
            if (index_bytes == 1) bytes[at] = static_cast<unsigned char>(index);
            if (index_bytes == 2) {
                const auto v = static_cast<std::uint16_t>(index);
                std::memcpy(&bytes[at], &v, 2);
            }
            if (index_bytes == 4) std::memcpy(&bytes[at], &index, 4);
        }
    }
    if (primitive.indices >= 0) {
        primitive.indices = replaced_accessor(model, primitive.indices, bytes, out);
        return;
    }
    tg::Accessor accessor;
    accessor.bufferView = out.add_view(model, bytes);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.type = TINYGLTF_TYPE_SCALAR;
    accessor.count = count;
    model.accessors.push_back(accessor);
    primitive.indices = static_cast<int>(model.accessors.size() - 1);
}

void decode_primitive(tg::Model& model, tg::Primitive& primitive, const tg::Value& extension,
                      const std::string& owner, DecodedBuffer& out, const Diagnostics& diagnostics) {
    if (!extension.IsObject() || !extension.Has("bufferView") || !extension.Get("bufferView").IsInt() ||
        !extension.Has("attributes") || !extension.Get("attributes").IsObject()) {
        diagnostics.fail(owner + ": " + kExtension + " needs an integer bufferView and an attributes object");
    }
    // The indices that compressed_json.cpp moved into the extension.
    if (extension.Has(kDracoIndicesKey)) {
        const tg::Value& indices = extension.Get(kDracoIndicesKey);
        if (!indices.IsInt()) diagnostics.fail(owner + " indices is not an accessor index");
        primitive.indices = indices.GetNumberAsInt();
    }
    // Every accessor to be filled exists and is small, before decoding.
    const tg::Value& ids = extension.Get("attributes");
    for (const std::string& name : ids.Keys()) {
        const auto target = primitive.attributes.find(name);
        if (target != primitive.attributes.end()) {
            checked_accessor(model, target->second, owner + " attribute " + Diagnostics::quoted(name), diagnostics);
        }
    }
    if (primitive.indices != -1) checked_accessor(model, primitive.indices, owner + " indices", diagnostics);

    const std::unique_ptr<draco::Mesh> mesh =
        decode_mesh(model, extension.Get("bufferView").GetNumberAsInt(), owner, diagnostics);
    // What this primitive's accessors will hold: at most 16 bytes per point
    // per attribute (VEC4 of 4-byte components), 12 per triangle.
    const std::size_t estimate = (ids.Keys().size() * std::size_t{mesh->num_points()} * 16) +
                                 std::size_t{mesh->num_faces()} * 12;
    if (!out.fits(estimate)) {
        diagnostics.fail(owner + ": " + kExtension + " meshes decode to more than " + std::to_string(out.limit) +
                         " bytes in all, 256 times the file's buffers");
    }
    decode_attributes(model, primitive, *mesh, ids, owner, out, diagnostics);
    decode_indices(model, primitive, *mesh, owner, out, diagnostics);
}

}  // namespace

void decode_draco_primitives(tg::Model& model, const Diagnostics& diagnostics) {
    DecodedBuffer out;
    out.index = model.buffers.size();
    for (const tg::Buffer& buffer : model.buffers) out.limit += buffer.data.size() * 256;
    out.limit += std::size_t{1} << 20;
    out.buffer.name = "KHR_draco_mesh_compression (decoded)";
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        auto& primitives = model.meshes[m].primitives;
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            tg::Primitive& primitive = primitives[p];
            const auto extension = primitive.extensions.find(kExtension);
            if (extension == primitive.extensions.end() || primitive.mode == TINYGLTF_MODE_POINTS) continue;
            const std::string owner = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            decode_primitive(model, primitive, extension->second, owner, out, diagnostics);
        }
    }
    if (out.used) model.buffers.push_back(std::move(out.buffer));
}

}  // namespace blurcull::frontend::gltf
