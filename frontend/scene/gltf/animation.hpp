// glTF animation: decoding and checking every sampler (keyframe times,
// interpolation, output counts), evaluating one at a time, and applying an
// animation's translation / rotation / scale channels to node transforms.
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/nodes.hpp"

#include <tiny_gltf.h>

#include <cstddef>
#include <vector>

namespace blurcull::frontend::gltf {

struct Sampler {
    std::vector<float> times;
    std::vector<float> values;  // keyframe values only (cubic tangents dropped)
    std::size_t components = 0;
    bool step = false;
};

// samplers[a][s]: sampler s of animation a.
using AnimationSamplers = std::vector<std::vector<Sampler>>;

// Checks every animation's channels (sampler and node indices) and decodes
// its samplers, animation by animation. Fails on the first problem.
AnimationSamplers read_animations(const tinygltf::Model& model, const Diagnostics& diagnostics);

// The sampler's value at time t: clamped outside the keyframes; STEP holds
// the earlier key; LINEAR lerps (or slerps when `rotation` and 4 components).
std::vector<float> evaluate(const Sampler& sampler, float t, bool rotation);

// The last keyframe time of animation `animation_index` (seconds): where
// its clock ends. 0 for index -1, one the file does not have, or no keys.
float animation_end_time(const AnimationSamplers& samplers, int animation_index);

// Sets the animated parts of `transforms` to animation `animation_index` at
// time t. Nothing for index -1 or a file without animations; fails for an
// index the file does not have. Ignored channels warn once per kind.
void apply_animation(const tinygltf::Model& model, const AnimationSamplers& samplers, int animation_index, float t,
                     std::vector<NodeTransform>& transforms, Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
