#include "scene/gltf/textures.hpp"

#include <climits>
#include <cstdint>
#include <string>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#include <stb_image.h>
#pragma GCC diagnostic pop

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

TextureWrap wrap_of(int gl_wrap) {
    if (gl_wrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::clamp;
    if (gl_wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::mirror;
    return TextureWrap::repeat;
}

}  // namespace

int TextureLoader::texture_for(int gltf_texture) {
    const auto found = loaded_.find(gltf_texture);
    if (found != loaded_.end()) return found->second;
    const int index = decode(gltf_texture);
    loaded_.emplace(gltf_texture, index);
    return index;
}

int TextureLoader::decode(int gltf_texture) {
    const std::string name = "texture " + std::to_string(gltf_texture);
    const auto unusable = [&](const std::string& why) {
        diagnostics_.warn_once("texture " + std::to_string(gltf_texture),
                               name + ": " + why + "; the material's factor is used instead");
        return -1;
    };
    if (gltf_texture < 0 || static_cast<std::size_t>(gltf_texture) >= model_.textures.size()) {
        return unusable("no such texture");
    }
    const tg::Texture& source = model_.textures[static_cast<std::size_t>(gltf_texture)];
    if (source.source < 0 || static_cast<std::size_t>(source.source) >= model_.images.size()) {
        return unusable("has no image blurcull can read (no source, or only an extension's)");
    }
    // parse.cpp keeps each image's encoded bytes; empty ones (a missing or
    // empty file) it has already warned of, once per image.
    const tg::Image& image = model_.images[static_cast<std::size_t>(source.source)];
    if (image.image.empty()) return -1;
    if (image.image.size() > static_cast<std::size_t>(INT_MAX)) return unusable("image is larger than 2 GiB");
    const auto* bytes = image.image.data();
    const int length = static_cast<int>(image.image.size());
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, length, &width, &height, &channels)) {
        return unusable(std::string("cannot decode its image (") + stbi_failure_reason() + "; PNG and JPEG are read)");
    }
    const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (texels > kMaxTextureTexels || texels_ + texels > kMaxSceneTexels) {
        return unusable("image of " + std::to_string(width) + "x" + std::to_string(height) +
                        " texels is over the texture budget (" + std::to_string(kMaxTextureTexels) +
                        " texels each, " + std::to_string(kMaxSceneTexels) + " in all)");
    }
    stbi_uc* pixels = stbi_load_from_memory(bytes, length, &width, &height, &channels, 4);
    if (pixels == nullptr) return unusable(std::string("cannot decode its image (") + stbi_failure_reason() + ")");
    Texture texture;
    texture.width = width;
    texture.height = height;
    texture.name = image.name.empty() ? image.uri : image.name;
    texture.texels.resize(texels);
    for (std::size_t i = 0; i < texels; ++i) {
        const stbi_uc* p = pixels + 4 * i;
        texture.texels[i] = std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
                            std::uint32_t{p[3]} << 24;
    }
    stbi_image_free(pixels);
    if (source.sampler >= 0 && static_cast<std::size_t>(source.sampler) < model_.samplers.size()) {
        const tg::Sampler& sampler = model_.samplers[static_cast<std::size_t>(source.sampler)];
        texture.wrap_s = wrap_of(sampler.wrapS);
        texture.wrap_t = wrap_of(sampler.wrapT);
    }
    texels_ += texels;
    scene_.textures.push_back(std::move(texture));
    return static_cast<int>(scene_.textures.size() - 1);
}

}  // namespace blurcull::frontend::gltf
