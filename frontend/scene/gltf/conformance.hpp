// What a file must declare for blurcull to read it: glTF 2.x (asset.version
// and asset.minVersion) and no required extension blurcull does not
// implement. Extensions a file only uses, and blurcull does not read, are
// named in one warning each.
#pragma once

#include "scene/gltf/diagnostics.hpp"

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace blurcull::frontend::gltf {

// The extensions blurcull implements, in the order docs/scenes.md lists
// them; a file may list these in extensionsRequired.
const std::vector<std::string>& implemented_extensions();

// Fails when asset.version is not 2.x or asset.minVersion is above 2.0
// (naming the version), and when extensionsRequired names an extension
// outside implemented_extensions() (naming it). Warns once per extension in
// extensionsUsed that blurcull does not read.
void check_conformance(const tinygltf::Model& model, Diagnostics& diagnostics);

// Only the version and required-extension checks, for a file tinygltf could
// not parse: tinygltf reads `asset` and `extensionsRequired` before anything
// else, so a glTF 1.0 file is refused by its version rather than by the
// first thing of 1.0 that tinygltf trips over. Does nothing when the asset
// has no version (the parse error is then the better message).
void check_declared_version(const tinygltf::Model& model, const Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
