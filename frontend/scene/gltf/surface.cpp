#include "scene/gltf/surface.hpp"

#include "scene/gltf/accessors.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

constexpr float kTexcoordLimit = 65536.0f;

// The accessor's values when the primitive has attribute `key` with one of
// the allowed component counts (VEC2 = 2, ...) and one element per vertex;
// empty when it has none. components receives the count.
std::vector<double> attribute_values(const tg::Model& model, const tg::Primitive& primitive, const std::string& key,
                                     std::vector<int> allowed_types, std::size_t vertex_count, const std::string& name,
                                     int& components, const Diagnostics& diagnostics) {
    const auto found = primitive.attributes.find(key);
    if (found == primitive.attributes.end()) return {};
    const tg::Accessor& accessor = model.accessors[static_cast<std::size_t>(found->second)];
    if (std::find(allowed_types.begin(), allowed_types.end(), accessor.type) == allowed_types.end()) {
        diagnostics.fail(name + " " + key + " accessor " + std::to_string(found->second) + " has the wrong type");
    }
    if (accessor.count != vertex_count) {
        diagnostics.fail(name + " " + key + " has " + std::to_string(accessor.count) + " elements for " +
                         std::to_string(vertex_count) + " vertices");
    }
    components = accessor.type == TINYGLTF_TYPE_VEC2 ? 2 : (accessor.type == TINYGLTF_TYPE_VEC3 ? 3 : 4);
    return read_values(model, found->second, diagnostics);
}

// Brings `values` (one per vertex of the scene before this primitive, or
// empty) to first_vertex entries of `fill` when this primitive has the
// attribute, then appends this primitive's (or, without, fill when the
// scene has the attribute).
template <class V>
void append_attribute(std::vector<V>& values, const std::vector<V>& own, std::size_t first_vertex,
                      std::size_t vertex_count, V fill) {
    if (own.empty() && values.empty()) return;
    values.resize(first_vertex, fill);
    if (own.empty()) values.resize(first_vertex + vertex_count, fill);
    else values.insert(values.end(), own.begin(), own.end());
}

std::vector<glm::vec2> read_texcoords(const tg::Model& model, const tg::Primitive& primitive, std::size_t vertex_count,
                                      const std::string& name, Diagnostics& diagnostics) {
    int components = 0;
    const std::vector<double> raw =
        attribute_values(model, primitive, "TEXCOORD_0", {TINYGLTF_TYPE_VEC2}, vertex_count, name, components, diagnostics);
    std::vector<glm::vec2> uv(raw.size() / 2);
    for (std::size_t v = 0; v < uv.size(); ++v) {
        for (int k = 0; k < 2; ++k) {
            double c = raw[2 * v + static_cast<std::size_t>(k)];
            if (!std::isfinite(c)) {
                diagnostics.warn_once("nan texcoord " + name, name + " has non-finite texture coordinates; 0 is used");
                c = 0.0;
            } else if (std::fabs(c) > kTexcoordLimit) {
                diagnostics.warn_once("far texcoord " + name,
                                      name + " has texture coordinates beyond +-65536; they are clamped");
                c = std::clamp(c, -double(kTexcoordLimit), double(kTexcoordLimit));
            }
            uv[v][k] = static_cast<float>(c);
        }
    }
    return uv;
}

std::vector<glm::vec4> read_colours(const tg::Model& model, const tg::Primitive& primitive, std::size_t vertex_count,
                                    const std::string& name, Diagnostics& diagnostics) {
    int components = 0;
    const std::vector<double> raw = attribute_values(model, primitive, "COLOR_0", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4},
                                                     vertex_count, name, components, diagnostics);
    std::vector<glm::vec4> colours(raw.empty() ? 0 : vertex_count, glm::vec4(1.0f));
    for (std::size_t v = 0; v < colours.size(); ++v) {
        for (int k = 0; k < components; ++k) {
            const double c = raw[v * static_cast<std::size_t>(components) + static_cast<std::size_t>(k)];
            if (!std::isfinite(c)) {
                diagnostics.warn_once("nan colour " + name, name + " has non-finite vertex colours; 1 is used");
                continue;
            }
            colours[v][k] = static_cast<float>(std::clamp(c, 0.0, 1.0));
        }
    }
    return colours;
}

std::vector<glm::vec3> read_normals(const tg::Model& model, const tg::Primitive& primitive, const glm::mat4& world_open,
                                    bool skinned, std::size_t vertex_count, const std::string& name,
                                    Diagnostics& diagnostics) {
    int components = 0;
    const std::vector<double> raw =
        attribute_values(model, primitive, "NORMAL", {TINYGLTF_TYPE_VEC3}, vertex_count, name, components, diagnostics);
    if (raw.empty()) return {};
    if (skinned) {
        diagnostics.warn_once("skinned normals", "normals of skinned meshes are not skinned; they shade flat");
        return {};
    }
    const glm::mat3 to_world = glm::transpose(glm::inverse(glm::mat3(world_open)));
    std::vector<glm::vec3> normals(vertex_count);
    for (std::size_t v = 0; v < vertex_count; ++v) {
        const glm::vec3 n(static_cast<float>(raw[3 * v]), static_cast<float>(raw[3 * v + 1]),
                          static_cast<float>(raw[3 * v + 2]));
        const glm::vec3 world = to_world * n;
        if (!std::isfinite(world.x) || !std::isfinite(world.y) || !std::isfinite(world.z)) {
            diagnostics.warn_once("nan normal " + name, name + " has non-finite normals; those vertices shade flat");
            continue;  // stays (0, 0, 0): flat
        }
        normals[v] = world;
    }
    return normals;
}

// KHR_texture_transform of a texture reference: translation * rotation * scale.
glm::mat3 texture_transform(const tg::ExtensionMap& extensions, Diagnostics& diagnostics) {
    const auto found = extensions.find("KHR_texture_transform");
    if (found == extensions.end() || !found->second.IsObject()) return glm::mat3(1.0f);
    const tg::Value& ext = found->second;
    const auto number = [&](const tg::Value& v, double fallback) {
        const double x = v.IsNumber() ? v.GetNumberAsDouble() : fallback;
        return std::isfinite(x) ? x : fallback;
    };
    const auto pair = [&](const char* key, double fallback, int k) {
        if (!ext.Has(key) || !ext.Get(key).IsArray() || ext.Get(key).ArrayLen() < 2) return fallback;
        return number(ext.Get(key).Get(k), fallback);
    };
    if (ext.Has("texCoord")) diagnostics.warn_once("transform texcoord", "KHR_texture_transform texCoord is ignored (TEXCOORD_0 is used)");
    const double rotation = ext.Has("rotation") ? number(ext.Get("rotation"), 0.0) : 0.0;
    const float c = static_cast<float>(std::cos(rotation)), s = static_cast<float>(std::sin(rotation));
    const glm::mat3 translate(1, 0, 0, 0, 1, 0, static_cast<float>(pair("offset", 0.0, 0)), static_cast<float>(pair("offset", 0.0, 1)), 1);
    const glm::mat3 rotate(c, s, 0, -s, c, 0, 0, 0, 1);  // column-major, as the spec's GLSL mat3(c, s, 0, -s, c, 0, 0, 0, 1)
    const glm::mat3 scale(static_cast<float>(pair("scale", 1.0, 0)), 0, 0, 0, static_cast<float>(pair("scale", 1.0, 1)), 0, 0, 0, 1);
    return translate * rotate * scale;
}

TextureRef texture_ref(int index, int tex_coord, const tg::ExtensionMap& extensions, TextureLoader& textures,
                       Diagnostics& diagnostics) {
    TextureRef ref;
    if (index < 0) return ref;
    if (tex_coord > 0) diagnostics.warn_once("texcoord set", "texture coordinate sets other than TEXCOORD_0 are read as TEXCOORD_0");
    ref.texture = textures.texture_for(index);
    ref.transform = texture_transform(extensions, diagnostics);
    return ref;
}

float finite_or(double value, float fallback) {
    return std::isfinite(value) ? static_cast<float>(value) : fallback;
}

}  // namespace

void append_surface_attributes(const tg::Model& model, const tg::Primitive& primitive, const glm::mat4& world_open,
                               bool skinned, std::size_t first_vertex, std::size_t vertex_count,
                               const std::string& name, Scene& scene, Diagnostics& diagnostics) {
    append_attribute(scene.texcoord, read_texcoords(model, primitive, vertex_count, name, diagnostics), first_vertex,
                     vertex_count, glm::vec2(0.0f));
    append_attribute(scene.vertex_color, read_colours(model, primitive, vertex_count, name, diagnostics), first_vertex,
                     vertex_count, glm::vec4(1.0f));
    append_attribute(scene.normal, read_normals(model, primitive, world_open, skinned, vertex_count, name, diagnostics),
                     first_vertex, vertex_count, glm::vec3(0.0f));
}

void read_surface_material(const tg::Material& source, TextureLoader& textures, Material& material,
                           Diagnostics& diagnostics) {
    const tg::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() >= 4) material.base_alpha = std::clamp(finite_or(pbr.baseColorFactor[3], 1.0f), 0.0f, 1.0f);
    material.base_color_texture = texture_ref(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                              pbr.baseColorTexture.extensions, textures, diagnostics);
    if (source.alphaMode == "MASK") {
        material.alpha_mode = AlphaMode::mask;
        material.alpha_cutoff = finite_or(source.alphaCutoff, 0.5f);
    } else if (source.alphaMode == "BLEND") {
        material.alpha_mode = AlphaMode::blend;
    }
    if (source.emissiveFactor.size() >= 3) {
        material.emissive = glm::max(glm::vec3(finite_or(source.emissiveFactor[0], 0.0f), finite_or(source.emissiveFactor[1], 0.0f),
                                               finite_or(source.emissiveFactor[2], 0.0f)),
                                     0.0f);
    }
    material.emissive_texture = texture_ref(source.emissiveTexture.index, source.emissiveTexture.texCoord,
                                            source.emissiveTexture.extensions, textures, diagnostics);
    // An emissive texture multiplies the factor, which defaults to 0 (glTF).
    const auto strength = source.extensions.find("KHR_materials_emissive_strength");
    if (strength != source.extensions.end() && strength->second.IsObject() &&
        strength->second.Has("emissiveStrength")) {
        const tg::Value& value = strength->second.Get("emissiveStrength");
        const double factor = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
        if (!(factor >= 0.0) || !std::isfinite(factor) || factor > 1e6) {
            diagnostics.warn_once("emissive strength", "KHR_materials_emissive_strength emissiveStrength is not a "
                                                       "number in [0, 1e6]; 1 is used");
        } else {
            material.emissive *= static_cast<float>(factor);
        }
    }
    // KHR_materials_unlit: an object, no properties.
    material.unlit = source.extensions.count("KHR_materials_unlit") > 0;
}

}  // namespace blurcull::frontend::gltf
