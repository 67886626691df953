// EXT_meshopt_compression: buffer views whose bytes are meshoptimizer
// streams (vertex attributes, triangle indices or index sequences), decoded
// with meshoptimizer's decoders and filters into a buffer the loader then
// reads as if the file had stored them plainly.
#pragma once

#include "scene/gltf/diagnostics.hpp"

#include <tiny_gltf.h>

namespace blurcull::frontend::gltf {

// The data URI that compressed_json.hpp gives a fallback buffer without
// data (4 zero bytes).
extern const char* const kMeshoptPlaceholderUri;

// Decodes every buffer view with the extension into a new buffer and points
// the view at it. Fails, naming the view and the extension, for a stream
// that does not decode, a mode, stride or filter the extension does not
// allow, a size that does not match the view, or a view without the
// extension that reads a placeholder buffer.
void decode_meshopt_views(tinygltf::Model& model, const Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
