// Reading a .gltf or .glb file into a tinygltf model: the GLB header is
// checked before tinygltf sees it, images are never decoded, and tinygltf's
// messages are joined onto one line.
#pragma once

#include "scene/gltf/diagnostics.hpp"

#include <tiny_gltf.h>

namespace blurcull::frontend::gltf {

// Parses diagnostics.path() (binary when it ends in .glb, any case). Fails
// when the file cannot be read or parsed; tinygltf's warnings become one
// warning. Compressed geometry (EXT_meshopt_compression buffer views,
// KHR_draco_mesh_compression primitives) comes back decoded into plain
// buffer views and accessors (meshopt.hpp, draco.hpp).
tinygltf::Model parse_file(Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
