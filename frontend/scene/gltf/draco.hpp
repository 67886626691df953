// KHR_draco_mesh_compression: primitives whose attributes and indices are
// one Draco mesh in a buffer view, decoded with libdraco into plain
// accessors that the loader then reads as usual.
#pragma once

#include "scene/gltf/diagnostics.hpp"

#include <tiny_gltf.h>

namespace blurcull::frontend::gltf {

// Decodes the Draco mesh of every primitive with the extension (points
// primitives, which the loader skips, excepted) and points the primitive's
// attributes named in the extension, and its indices, at new accessors
// holding the decoded values in the original accessors' component types
// (the indices accessor read from where compressed_json.hpp moved it).
// Fails, naming the primitive and the extension, for data that does not
// decode, an attribute id the mesh lacks, or counts that differ from the
// accessors'.
void decode_draco_primitives(tinygltf::Model& model, const Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
