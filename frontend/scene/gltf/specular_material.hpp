// Mirror and glass from glTF materials (docs/reference-renderer.md,
// "Materials and environment", glTF):
//  * KHR_materials_transmission with transmissionFactor > 0 makes a
//    dielectric (clear glass) whose index of refraction is
//    KHR_materials_ior's "ior" (1.5 when absent). The factor's size,
//    transmissionTexture and every other transmission/volume property are
//    ignored: the glass is clear.
//  * Otherwise pbrMetallicRoughness metallicFactor 1 with roughnessFactor 0
//    makes a perfect mirror (textures ignored); any other values stay diffuse.
//  * Out of range: a metallic, roughness or transmission factor outside
//    [0, 1] is clamped into it with a warning; a non-finite one, or an ior
//    that is not finite or below 1 (glTF's minimum; a vacuum is 1), fails
//    with one line naming the material. An ior without transmission is ignored.
//  * glTF carries no environment, so a loaded scene has none: a file with a
//    mirror or glass gets one warning that rays leaving the scene show the
//    background colour.
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/scene.hpp"

#include <tiny_gltf.h>

#include <string>

namespace blurcull::frontend::gltf {

// Sets material.kind (and ior) from `source` as above; `label` names the
// material in messages ("material 3").
void read_specular_kind(const tinygltf::Material& source, const std::string& label, Material& material,
                        Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
