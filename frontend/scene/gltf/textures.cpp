#include "scene/gltf/textures.hpp"

#include <climits>
#include <cstdint>
#include <string>

#include "third_party/stb_codecs.hpp"

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
    const std::uint8_t* bytes = image.image.data();
    const std::size_t length = image.image.size();
    codecs::ImageHeader header;
    std::string error;
    if (!codecs::read_image_header(bytes, length, header, error)) {
        return unusable("cannot decode its image (" + error + "; PNG and JPEG are read)");
    }
    const int width = header.width, height = header.height;
    const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (texels > kMaxTextureTexels || texels_ + texels > kMaxSceneTexels) {
        return unusable("image of " + std::to_string(width) + "x" + std::to_string(height) +
                        " texels is over the texture budget (" + std::to_string(kMaxTextureTexels) +
                        " texels each, " + std::to_string(kMaxSceneTexels) + " in all)");
    }
    codecs::DecodedImage decoded;
    if (!codecs::decode_image(bytes, length, 4, decoded, error)) return unusable("cannot decode its image (" + error + ")");
    if (decoded.width != width || decoded.height != height) return unusable("image size differs from its header");
    Texture texture;
    texture.width = decoded.width;
    texture.height = decoded.height;
    texture.name = image.name.empty() ? image.uri : image.name;
    texture.texels.resize(texels);
    for (std::size_t i = 0; i < texels; ++i) {
        const std::uint8_t* p = decoded.bytes.data() + 4 * i;
        texture.texels[i] = std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
                            std::uint32_t{p[3]} << 24;
    }
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
