// Motion segments for glTF (--motion-segments K): the scene sampled at the
// interior shutter times k / K (Scene::position_at, Camera::view_at), and the
// `auto` choice of K from the largest rotation during the shutter
// (docs/reference-renderer.md, "The motion model").
#pragma once

#include "scene/gltf/diagnostics.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/gltf/nodes.hpp"
#include "scene/scene.hpp"

#include <tiny_gltf.h>

#include <functional>
#include <vector>

namespace blurcull::frontend::gltf {

// Every node's world matrices at one animation time (both NodePoses ends
// the same), as the loader samples them.
using PosesAt = std::function<NodePoses(float time)>;

// Appends to scene.position_at the world positions at the animation times
// open + (close - open) k / K, k = 1 .. K - 1, by running the mesh step on
// the poses there (so skins, and whatever else that step reads from the
// poses, move as at the ends), and to scene.camera.view_at the camera's view
// there when the camera moves. Fails if a time gives another vertex count.
void add_interior_times(const tinygltf::Model& model, const std::vector<int>& rendered, const PosesAt& poses_at,
                        const GltfOptions& options, float open, float close, int segments, Scene& scene,
                        Diagnostics& diagnostics);

// The `auto` K for the scene built at the shutter ends (its camera set up):
// per rendered mesh node, the angle A its world rotation (or its skin's
// joints') turns over the shutter, summed over 32 steps, and the radius r in
// pixels (options.image_height, options.aspect) of its mesh's projected box
// at open and close (half the diagonal, at most the image's diagonal); K = max of motion_segments_for_turn(A, r,
// tolerance), clamped to max_motion_segments with a warning.
int auto_motion_segments(const tinygltf::Model& model, const std::vector<int>& rendered, const PosesAt& poses_at,
                         const GltfOptions& options, float open, float close, const Scene& scene,
                         Diagnostics& diagnostics);

}  // namespace blurcull::frontend::gltf
