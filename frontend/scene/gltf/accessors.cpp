#include "scene/gltf/accessors.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

// Rows and columns of an accessor type (SCALAR 1x1, VEC3 3x1, MAT4 4x4).
bool type_shape(int type, std::size_t& rows, std::size_t& columns) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: rows = 1; columns = 1; return true;
        case TINYGLTF_TYPE_VEC2: rows = 2; columns = 1; return true;
        case TINYGLTF_TYPE_VEC3: rows = 3; columns = 1; return true;
        case TINYGLTF_TYPE_VEC4: rows = 4; columns = 1; return true;
        case TINYGLTF_TYPE_MAT2: rows = 2; columns = 2; return true;
        case TINYGLTF_TYPE_MAT3: rows = 3; columns = 3; return true;
        case TINYGLTF_TYPE_MAT4: rows = 4; columns = 4; return true;
        default: return false;
    }
}

template <typename Stored>
Stored load(const unsigned char* bytes) {
    Stored v;
    std::memcpy(&v, bytes, sizeof v);
    return v;
}

double decode_component(const unsigned char* bytes, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const auto v = load<std::int8_t>(bytes);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const auto v = load<std::uint8_t>(bytes);
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const auto v = load<std::int16_t>(bytes);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const auto v = load<std::uint16_t>(bytes);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_INT: return load<std::int32_t>(bytes);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<std::uint32_t>(bytes);
        default: return load<float>(bytes);
    }
}

const unsigned char* view_data(const tg::Model& model, int view_index, std::size_t offset) {
    const tg::BufferView& view = model.bufferViews[static_cast<std::size_t>(view_index)];
    return model.buffers[static_cast<std::size_t>(view.buffer)].data.data() + view.byteOffset + offset;
}

// Decodes one element at `element` into values[target * components ...].
void decode_element(const tg::Accessor& accessor, const ElementLayout& layout, const unsigned char* element,
                    std::size_t target, std::vector<double>& values) {
    const std::size_t components = layout.components();
    for (std::size_t c = 0; c < components; ++c) {
        values[target * components + c] =
            decode_component(element + layout.offset_of(c), accessor.componentType, accessor.normalized);
    }
}

void apply_sparse(const tg::Model& model, int accessor_index, const ElementLayout& layout,
                  const Diagnostics& diagnostics, std::vector<double>& values) {
    const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(accessor_index)];
    const auto& sparse = accessor.sparse;
    const unsigned char* indices =
        view_data(model, sparse.indices.bufferView, static_cast<std::size_t>(sparse.indices.byteOffset));
    const unsigned char* substitutes =
        view_data(model, sparse.values.bufferView, static_cast<std::size_t>(sparse.values.byteOffset));
    const std::size_t index_bytes = component_size(sparse.indices.componentType);
    for (std::size_t k = 0; k < static_cast<std::size_t>(sparse.count); ++k) {
        const double target = decode_component(indices + k * index_bytes, sparse.indices.componentType, false);
        if (!(target >= 0.0) || target >= static_cast<double>(accessor.count)) {
            diagnostics.fail("accessor " + std::to_string(accessor_index) + ": sparse index " +
                             std::to_string(target) + " is outside its " + std::to_string(accessor.count) +
                             " elements");
        }
        decode_element(accessor, layout, substitutes + k * layout.size, static_cast<std::size_t>(target), values);
    }
}

}  // namespace

std::size_t component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

ElementLayout layout_of(const tg::Accessor& accessor) {
    ElementLayout layout;
    layout.component_bytes = component_size(accessor.componentType);
    if (layout.component_bytes == 0 || !type_shape(accessor.type, layout.rows, layout.columns)) {
        return ElementLayout{};
    }
    layout.column_stride = layout.rows * layout.component_bytes;
    if (layout.columns > 1) layout.column_stride = (layout.column_stride + 3) / 4 * 4;
    layout.size = layout.columns == 1
                      ? layout.column_stride
                      : layout.column_stride * (layout.columns - 1) + layout.rows * layout.component_bytes;
    return layout;
}

bool span_fits(std::size_t offset, std::size_t count, std::size_t stride, std::size_t element_size,
               std::size_t length) {
    if (count == 0) return offset <= length;
    if (offset > length || element_size > length - offset) return false;
    return count - 1 <= (length - offset - element_size) / stride;
}

bool finite_values(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

std::vector<double> read_values(const tg::Model& model, int accessor_index, const Diagnostics& diagnostics) {
    const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(accessor_index)];
    const ElementLayout layout = layout_of(accessor);
    std::vector<double> values(accessor.count * layout.components(), 0.0);
    if (accessor.bufferView >= 0) {
        const tg::BufferView& view = model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
        const unsigned char* base = view_data(model, accessor.bufferView, accessor.byteOffset);
        const std::size_t stride = view.byteStride == 0 ? layout.size : view.byteStride;
        for (std::size_t i = 0; i < accessor.count; ++i) decode_element(accessor, layout, base + i * stride, i, values);
    }
    if (accessor.sparse.isSparse) apply_sparse(model, accessor_index, layout, diagnostics, values);
    return values;
}

std::vector<std::uint32_t> read_integers(const tg::Model& model, int accessor_index, const std::string& what,
                                         const Diagnostics& diagnostics) {
    const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(accessor_index)];
    if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        diagnostics.fail(what + " accessor " + std::to_string(accessor_index) + " holds floats, not integers");
    }
    const std::vector<double> values = read_values(model, accessor_index, diagnostics);
    std::vector<std::uint32_t> integers(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i] < 0.0) {
            diagnostics.fail(what + " accessor " + std::to_string(accessor_index) + " holds a negative value " +
                             std::to_string(values[i]));
        }
        integers[i] = static_cast<std::uint32_t>(values[i]);
    }
    return integers;
}

}  // namespace blurcull::frontend::gltf
