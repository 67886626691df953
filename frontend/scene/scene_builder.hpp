// What the built-in scenes and the glTF loader both do to a Scene under
// construction: check the options they share, append materials and meshes.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace blurcull::frontend {

// The problem with a blur scale (finite, >= 0) and an image aspect (finite,
// > 0), worded for a SceneError after the caller's prefix; "" when both are
// fine. Blur scale is checked first.
std::string blur_and_aspect_problem(float blur_scale, float aspect);

// Appends a material; returns its index.
std::uint32_t add_material(Scene& scene, const Material& material);

// Appends a mesh of one material: vertices with their positions at shutter
// open and close (same count), triangles indexing them from 0. The caller
// makes sure the scene's vertex count stays below 2^32.
void append_mesh(Scene& scene, const std::vector<glm::vec3>& open, const std::vector<glm::vec3>& close,
                 const std::vector<glm::uvec3>& triangles, std::uint32_t material);

}  // namespace blurcull::frontend
