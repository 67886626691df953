// The textures the materials use: each glTF texture's image decoded with
// stb_image (PNG, JPEG) into a Scene texture on first use, with its sampler's
// wrap modes, under a memory budget. A texture that cannot be used (image
// truncated, of an unsupported format, or too large) warns once and the
// material keeps its factor (docs/reference-renderer.md, "Shading"); an
// image that could not be read at all (missing, empty) parse.cpp warns of.
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/scene.hpp"

#include <tiny_gltf.h>

#include <cstddef>
#include <map>

namespace blurcull::frontend::gltf {

// One texture's and all textures' decoded size limits, in texels (4 bytes
// each): 8192 x 8192 per texture, 1 GiB in all.
constexpr std::size_t kMaxTextureTexels = std::size_t{8192} * 8192;
constexpr std::size_t kMaxSceneTexels = std::size_t{1} << 28;

class TextureLoader {
public:
    TextureLoader(const tinygltf::Model& model, Scene& scene, Diagnostics& diagnostics)
        : model_(model), scene_(scene), diagnostics_(diagnostics) {}

    // The Scene::textures index of glTF texture `gltf_texture`, decoded on
    // first use; -1 after a warning when it cannot be used.
    int texture_for(int gltf_texture);

private:
    int decode(int gltf_texture);

    const tinygltf::Model& model_;
    Scene& scene_;
    Diagnostics& diagnostics_;
    std::map<int, int> loaded_;
    std::size_t texels_ = 0;
};

}  // namespace blurcull::frontend::gltf
