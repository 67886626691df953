// What tinygltf 2.7 refuses in files with compressed geometry, rewritten in
// the file's JSON before tinygltf reads it:
// - an EXT_meshopt_compression fallback buffer without data (no uri; in a
//   GLB not the BIN chunk) gets a 4-byte placeholder (kMeshoptPlaceholderUri),
//   which meshopt.cpp recognises;
// - a KHR_draco_mesh_compression primitive's indices accessor has no buffer
//   view (its values are in the Draco mesh), which tinygltf rejects for
//   indices: the primitive's "indices" moves into the extension object as
//   kDracoIndicesKey, where draco.cpp reads it.
#pragma once

#include <vector>

namespace blurcull::frontend::gltf {

// The extension object's key that holds the primitive's moved indices.
extern const char* const kDracoIndicesKey;

// `bytes` (a whole .gltf, or a GLB whose header parse.cpp has checked, its
// chunks rebuilt) with the rewrites above; unchanged when the JSON names
// neither extension or cannot be parsed (tinygltf then says why).
std::vector<unsigned char> with_compression_rewrites(std::vector<unsigned char> bytes, bool binary);

}  // namespace blurcull::frontend::gltf
