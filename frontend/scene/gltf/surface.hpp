// The surface part of glTF meshes and materials (docs/reference-renderer.md,
// "Shading"): per-vertex TEXCOORD_0, COLOR_0 and NORMAL appended beside the
// positions, and a material's base colour alpha, alpha mode, emission and
// textures (with KHR_texture_transform).
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/textures.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include <cstddef>
#include <string>

namespace blurcull::frontend::gltf {

// Appends the attributes of the primitive whose vertex_count vertices were
// just appended at first_vertex: the primitive's own, or the defaults
// (texcoord (0, 0), colour (1, 1, 1, 1), normal (0, 0, 0): flat) where it has
// none and the scene has them; earlier vertices get the defaults when this
// is the first primitive with an attribute. Normals are put in the world at
// shutter open by the inverse transpose of `world_open` (skinned primitives:
// none, flat). Non-finite values fall back to the default with a warning;
// texture coordinates beyond +-65536 are clamped with a warning; an attribute
// of the wrong type or count fails.
void append_surface_attributes(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                               const glm::mat4& world_open, bool skinned, std::size_t first_vertex,
                               std::size_t vertex_count, const std::string& name, Scene& scene,
                               Diagnostics& diagnostics);

// Fills material's surface fields (base_alpha, alpha_mode, alpha_cutoff,
// emissive, base_color_texture, emissive_texture) from the glTF material.
void read_surface_material(const tinygltf::Material& source, TextureLoader& textures, Material& material,
                           Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
