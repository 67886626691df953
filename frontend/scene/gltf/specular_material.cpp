#include "scene/gltf/specular_material.hpp"

#include <algorithm>
#include <cmath>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

// A factor in [0, 1]: clamped with a warning outside, a failure when not finite.
double unit_factor(double value, const std::string& what, Diagnostics& diagnostics) {
    if (!std::isfinite(value)) diagnostics.fail(what + " is not finite");
    if (value < 0.0 || value > 1.0) {
        diagnostics.warn_once("range " + what, what + " " + std::to_string(value) + " is outside [0, 1]; clamped");
        return std::clamp(value, 0.0, 1.0);
    }
    return value;
}

// The number `key` of extension `extension`, or `fallback` when either is
// absent. A present value that is not a number fails.
double extension_number(const tg::Material& source, const char* extension, const char* key, double fallback,
                        const std::string& label, const Diagnostics& diagnostics) {
    const auto found = source.extensions.find(extension);
    if (found == source.extensions.end() || !found->second.IsObject() || !found->second.Has(key)) return fallback;
    const tg::Value& value = found->second.Get(key);
    if (!value.IsNumber()) diagnostics.fail(label + " " + extension + " " + key + " is not a number");
    return value.GetNumberAsDouble();
}

}  // namespace

void read_specular_kind(const tg::Material& source, const std::string& label, Material& material,
                        Diagnostics& diagnostics) {
    const double transmission =
        unit_factor(extension_number(source, "KHR_materials_transmission", "transmissionFactor", 0.0, label,
                                     diagnostics),
                    label + " KHR_materials_transmission transmissionFactor", diagnostics);
    const double metallic =
        unit_factor(source.pbrMetallicRoughness.metallicFactor, label + " metallicFactor", diagnostics);
    const double roughness =
        unit_factor(source.pbrMetallicRoughness.roughnessFactor, label + " roughnessFactor", diagnostics);
    if (transmission > 0.0) {
        const double ior = extension_number(source, "KHR_materials_ior", "ior", 1.5, label, diagnostics);
        if (!std::isfinite(ior) || ior < 1.0 || ior > 1e6) {
            diagnostics.fail(label + " KHR_materials_ior ior " + std::to_string(ior) + " is not in [1, 1e6]");
        }
        material.kind = MaterialKind::dielectric;
        material.ior = static_cast<float>(ior);
    } else if (metallic == 1.0 && roughness == 0.0) {
        material.kind = MaterialKind::mirror;
    } else {
        return;
    }
    diagnostics.warn_once("no environment", label + " is a " +
                                                std::string(material.kind == MaterialKind::mirror ? "mirror" : "glass") +
                                                "; glTF has no environment, so rays that leave the scene show the "
                                                "background colour");
}

}  // namespace blurcull::frontend::gltf
