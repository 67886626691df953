#include "scene/gltf/animation.hpp"

#include "scene/gltf/accessors.hpp"
#include "scene/gltf/validate.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace blurcull::frontend::gltf {

namespace {

namespace tg = tinygltf;

void check_channels(const tg::Model& model, std::size_t animation_index, const Diagnostics& diagnostics) {
    const tg::Animation& animation = model.animations[animation_index];
    const std::string name = "animation " + std::to_string(animation_index);
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
        const tg::AnimationChannel& channel = animation.channels[c];
        if (channel.sampler < 0 || static_cast<std::size_t>(channel.sampler) >= animation.samplers.size()) {
            diagnostics.fail(name + " channel " + std::to_string(c) + " refers to sampler " +
                             std::to_string(channel.sampler) + ", which does not exist");
        }
        if (channel.target_node >= 0 && static_cast<std::size_t>(channel.target_node) >= model.nodes.size()) {
            diagnostics.fail(name + " channel " + std::to_string(c) + " targets node " +
                             std::to_string(channel.target_node) + ", which does not exist");
        }
    }
}

// Keyframe times: finite and non-decreasing.
void check_times(const std::vector<float>& times, const std::string& name, const Diagnostics& diagnostics) {
    for (std::size_t k = 0; k < times.size(); ++k) {
        if (!std::isfinite(times[k])) diagnostics.fail(name + ": keyframe time " + std::to_string(k) + " is not finite");
        if (k > 0 && times[k] < times[k - 1]) {
            diagnostics.fail(name + ": keyframe times are not increasing (time " + std::to_string(k) + " = " +
                             std::to_string(times[k]) + " after " + std::to_string(times[k - 1]) + ")");
        }
    }
}

// The keyframe values (CUBICSPLINE's tangents dropped) and their component count.
void read_keyframe_values(const tg::Model& model, const tg::AnimationSampler& source, bool cubic,
                          const std::string& name, const Diagnostics& diagnostics, Sampler& sampler) {
    const tg::Accessor& input = model.accessors[static_cast<std::size_t>(source.input)];
    const tg::Accessor& output = model.accessors[static_cast<std::size_t>(source.output)];
    const std::size_t per_key = cubic ? 3 : 1;
    if (output.count % (input.count * per_key) != 0 || output.count == 0) {
        diagnostics.fail(name + " has " + std::to_string(output.count) + " output values for " +
                         std::to_string(input.count) + " keyframes");
    }
    // Morph weights have several values per keyframe; node channels one.
    const std::size_t elements_per_key = output.count / (input.count * per_key);
    const std::vector<double> raw = read_values(model, source.output, diagnostics);
    if (!finite_values(raw)) diagnostics.fail(name + " has a non-finite output value");
    sampler.components = raw.size() / output.count * elements_per_key;
    for (std::size_t k = 0; k < input.count; ++k) {
        // CUBICSPLINE stores (in-tangent, value, out-tangent) per key: keep the value.
        const std::size_t first = (k * per_key + (cubic ? 1 : 0)) * sampler.components;
        for (std::size_t c = 0; c < sampler.components; ++c) {
            sampler.values.push_back(static_cast<float>(raw[first + c]));
        }
    }
}

Sampler read_sampler(const tg::Model& model, std::size_t animation_index, std::size_t sampler_index,
                     const Diagnostics& diagnostics) {
    const tg::AnimationSampler& source = model.animations[animation_index].samplers[sampler_index];
    const std::string name =
        "animation " + std::to_string(animation_index) + " sampler " + std::to_string(sampler_index);
    check_accessor_index(model, source.input, name + " input", diagnostics);
    check_accessor_index(model, source.output, name + " output", diagnostics);
    Sampler sampler;
    const bool cubic = source.interpolation == "CUBICSPLINE";
    const tg::Accessor& input = model.accessors[static_cast<std::size_t>(source.input)];
    if (input.type != TINYGLTF_TYPE_SCALAR || input.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        diagnostics.fail(name + ": keyframe times are not float scalars");
    }
    if (input.count == 0) diagnostics.fail(name + " has no keyframes");
    if (source.interpolation == "STEP") {
        sampler.step = true;
    } else if (source.interpolation != "LINEAR" && !cubic) {
        diagnostics.fail(name + " has unknown interpolation '" + source.interpolation + "'");
    }
    for (double t : read_values(model, source.input, diagnostics)) sampler.times.push_back(static_cast<float>(t));
    check_times(sampler.times, name, diagnostics);
    read_keyframe_values(model, source, cubic, name, diagnostics, sampler);
    return sampler;
}

// True for a translation, rotation or scale channel on a TRS node; false
// for weights (morph.hpp reads those) and, with a warning once per kind,
// for the channels blurcull ignores.
bool channel_applies(const tg::AnimationChannel& channel, const NodeTransform& transform, Diagnostics& diagnostics) {
    const std::string& path = channel.target_path;
    if (path == "weights") return false;  // morph weights: morph.hpp
    if (path != "translation" && path != "rotation" && path != "scale") {
        diagnostics.warn_once("path " + path, "animation path '" + path + "' is ignored");
        return false;
    }
    if (transform.uses_matrix) {
        diagnostics.warn_once("matrix", "animation of a node given by a matrix is ignored (glTF requires TRS there)");
        return false;
    }
    return true;
}

}  // namespace

AnimationSamplers read_animations(const tg::Model& model, const Diagnostics& diagnostics) {
    AnimationSamplers samplers(model.animations.size());
    for (std::size_t a = 0; a < model.animations.size(); ++a) {
        check_channels(model, a, diagnostics);
        for (std::size_t s = 0; s < model.animations[a].samplers.size(); ++s) {
            samplers[a].push_back(read_sampler(model, a, s, diagnostics));
        }
    }
    return samplers;
}

std::vector<float> evaluate(const Sampler& sampler, float t, bool rotation) {
    const std::size_t n = sampler.times.size();
    const std::size_t c = sampler.components;
    auto key = [&](std::size_t k) {
        return std::vector<float>(sampler.values.begin() + static_cast<std::ptrdiff_t>(k * c),
                                  sampler.values.begin() + static_cast<std::ptrdiff_t>((k + 1) * c));
    };
    if (t <= sampler.times.front()) return key(0);
    if (t >= sampler.times.back()) return key(n - 1);
    const std::size_t upper = static_cast<std::size_t>(
        std::upper_bound(sampler.times.begin(), sampler.times.end(), t) - sampler.times.begin());
    const std::size_t lower = upper - 1;
    if (sampler.step) return key(lower);
    const float span = sampler.times[upper] - sampler.times[lower];
    const float f = span > 0.0f ? (t - sampler.times[lower]) / span : 0.0f;
    std::vector<float> a = key(lower);
    const std::vector<float> b = key(upper);
    if (rotation && c == 4) {
        const glm::quat qa = glm::normalize(glm::quat(a[3], a[0], a[1], a[2]));
        const glm::quat qb = glm::normalize(glm::quat(b[3], b[0], b[1], b[2]));
        const glm::quat q = glm::slerp(qa, qb, f);
        return {q.x, q.y, q.z, q.w};
    }
    for (std::size_t i = 0; i < c; ++i) a[i] += (b[i] - a[i]) * f;
    return a;
}

float animation_end_time(const AnimationSamplers& samplers, int animation_index) {
    if (animation_index < 0 || static_cast<std::size_t>(animation_index) >= samplers.size()) return 0.0f;
    float end = 0.0f;
    for (const Sampler& sampler : samplers[static_cast<std::size_t>(animation_index)]) {
        if (!sampler.times.empty()) end = std::max(end, sampler.times.back());
    }
    return end;
}

void apply_animation(const tg::Model& model, const AnimationSamplers& samplers, int animation_index, float t,
                     std::vector<NodeTransform>& transforms, Diagnostics& diagnostics) {
    if (animation_index < 0 || model.animations.empty()) return;
    const auto index = static_cast<std::size_t>(animation_index);
    if (index >= model.animations.size()) {
        diagnostics.fail("animation " + std::to_string(animation_index) + " does not exist (the file has " +
                         std::to_string(model.animations.size()) + ")");
    }
    for (const tg::AnimationChannel& channel : model.animations[index].channels) {
        if (channel.target_node < 0) continue;  // e.g. targets an extension's object
        NodeTransform& transform = transforms[static_cast<std::size_t>(channel.target_node)];
        if (!channel_applies(channel, transform, diagnostics)) continue;
        const std::string& path = channel.target_path;
        const Sampler& sampler = samplers[index][static_cast<std::size_t>(channel.sampler)];
        const std::size_t expected = path == "rotation" ? 4 : 3;
        if (sampler.components != expected) {
            diagnostics.fail("animation " + std::to_string(index) + " channel for '" + path + "' has " +
                             std::to_string(sampler.components) + " components per key, expected " +
                             std::to_string(expected));
        }
        const std::vector<float> v = evaluate(sampler, t, path == "rotation");
        if (path == "translation") transform.translation = glm::vec3(v[0], v[1], v[2]);
        if (path == "scale") transform.scale = glm::vec3(v[0], v[1], v[2]);
        if (path == "rotation") transform.rotation = glm::quat(v[3], v[0], v[1], v[2]);
    }
}

}  // namespace blurcull::frontend::gltf
