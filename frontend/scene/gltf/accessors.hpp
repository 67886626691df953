// glTF accessors: where the components of an element sit (component types,
// matrix column padding), byte-range arithmetic that cannot overflow, and
// decoding an accessor (normalised integers, sparse substitutions) into
// numbers. validate.hpp checks every accessor before any of it is read.
#pragma once

#include "scene/gltf/diagnostics.hpp"

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace blurcull::frontend::gltf {

// An accessor without a buffer view is all zeros (plus sparse values) and is
// bounded by no byte range: cap its element count so a huge count neither
// overflows count * components nor allocates without limit.
constexpr std::size_t kMaxElementsWithoutView = std::size_t{1} << 24;

// Bytes of one component (1, 2 or 4); 0 for an unknown component type.
std::size_t component_size(int component_type);

// Where the components of one accessor element sit. Matrix columns start
// on 4-byte boundaries (glTF's padding rule for 1- and 2-byte components).
struct ElementLayout {
    std::size_t component_bytes = 0;
    std::size_t rows = 0;
    std::size_t columns = 0;
    std::size_t column_stride = 0;
    std::size_t size = 0;  // bytes of one element
    std::size_t components() const { return rows * columns; }
    std::size_t offset_of(std::size_t component) const {
        return (component / rows) * column_stride + (component % rows) * component_bytes;
    }
};

// The layout of the accessor's elements; size 0 for an unknown component
// type or type.
ElementLayout layout_of(const tinygltf::Accessor& accessor);

// True when `count` elements of `element_size` bytes, `stride` apart,
// starting at `offset`, fit in `length` bytes (without overflowing).
bool span_fits(std::size_t offset, std::size_t count, std::size_t stride, std::size_t element_size,
               std::size_t length);

// True when every value is finite.
bool finite_values(const std::vector<double>& values);

// count * components values of a validated accessor, normalised integers
// mapped to [0, 1] / [-1, 1], sparse substitutions applied. Fails on a
// sparse index outside the accessor.
std::vector<double> read_values(const tinygltf::Model& model, int accessor_index,
                                const Diagnostics& diagnostics);

// The accessor's values as unsigned integers; fails when it holds floats or
// a negative value, naming it as `what`.
std::vector<std::uint32_t> read_integers(const tinygltf::Model& model, int accessor_index, const std::string& what,
                                         const Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
