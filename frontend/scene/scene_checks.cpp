#include "scene/scene_checks.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace blurcull::frontend {

namespace {

bool is_finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool is_finite(const glm::mat4& m) {
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            if (!std::isfinite(m[column][row])) return false;
        }
    }
    return true;
}

[[noreturn]] void fail(const Scene& scene, const std::string& problem) {
    throw SceneError("scene '" + scene.name + "': " + problem);
}

glm::vec3 eye_position(const glm::mat4& view) {
    return glm::vec3(glm::inverse(view)[3]);
}

// Kinds, indices of refraction and the environment (the optics of
// render/common/optics_shared.h need ior > 0 and finite).
void check_materials(const Scene& scene) {
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        if (material.kind != MaterialKind::diffuse && material.kind != MaterialKind::mirror &&
            material.kind != MaterialKind::dielectric) {
            fail(scene, "material " + std::to_string(m) + " has unknown kind " +
                            std::to_string(static_cast<int>(material.kind)));
        }
        if (!(material.ior > 0.0f) || !std::isfinite(material.ior)) {
            fail(scene, "material " + std::to_string(m) + " has index of refraction " + std::to_string(material.ior) +
                            " (must be positive and finite)");
        }
        if (!is_finite(material.base_color)) fail(scene, "material " + std::to_string(m) + " has a non-finite colour");
    }
    if (scene.environment != BC_ENVIRONMENT_NONE && scene.environment != BC_ENVIRONMENT_SKY) {
        fail(scene, "environment " + std::to_string(scene.environment) + " is unknown (0 background, 1 sky)");
    }
}

// Motion segments: one position per vertex at every interior time, finite,
// and no more interior times than the cap; camera views, if any, at the same times.
void check_interior_times(const Scene& scene) {
    if (scene.position_at.size() + 1 > static_cast<std::size_t>(max_motion_segments)) {
        fail(scene, std::to_string(scene.position_at.size() + 1) + " motion segments exceed the cap of " +
                        std::to_string(max_motion_segments));
    }
    for (std::size_t k = 0; k < scene.position_at.size(); ++k) {
        if (scene.position_at[k].size() != scene.position_open.size()) {
            fail(scene, "interior time " + std::to_string(k + 1) + " has " +
                            std::to_string(scene.position_at[k].size()) + " positions for " +
                            std::to_string(scene.position_open.size()) + " vertices");
        }
        for (const glm::vec3& p : scene.position_at[k]) {
            if (!is_finite(p)) fail(scene, "interior time " + std::to_string(k + 1) + " has a non-finite position");
        }
    }
    if (!scene.camera.view_at.empty() && scene.camera.view_at.size() != scene.position_at.size()) {
        fail(scene, std::to_string(scene.camera.view_at.size()) + " interior camera views for " +
                        std::to_string(scene.position_at.size()) + " interior times");
    }
    for (const glm::mat4& view : scene.camera.view_at) {
        if (!is_finite(view)) fail(scene, "an interior camera view matrix is not finite");
    }
}

// The optional per-vertex attributes, textures and materials' texture
// references of surface_shading.hpp: sizes and indices that the shading
// trusts, and finite values (the loader replaces non-finite ones).
void validate_surface_attributes(const Scene& scene) {
    const std::size_t vertex_count = scene.position_open.size();
    const auto check_size = [&](std::size_t size, const char* what) {
        if (size != 0 && size != vertex_count) {
            fail(scene, std::to_string(size) + " " + what + " for " + std::to_string(vertex_count) + " vertices");
        }
    };
    check_size(scene.texcoord.size(), "texture coordinates");
    check_size(scene.vertex_color.size(), "vertex colours");
    check_size(scene.normal.size(), "normals");
    for (const glm::vec2& uv : scene.texcoord) {
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) fail(scene, "a texture coordinate is not finite");
    }
    for (const glm::vec4& c : scene.vertex_color) {
        if (!is_finite(glm::vec3(c)) || !std::isfinite(c.w)) fail(scene, "a vertex colour is not finite");
    }
    for (const glm::vec3& n : scene.normal) {
        if (!is_finite(n)) fail(scene, "a normal is not finite");
    }
    for (std::size_t k = 0; k < scene.textures.size(); ++k) {
        const Texture& texture = scene.textures[k];
        if (texture.width < 1 || texture.height < 1 ||
            texture.texels.size() != static_cast<std::size_t>(texture.width) * static_cast<std::size_t>(texture.height)) {
            fail(scene, "texture " + std::to_string(k) + " has " + std::to_string(texture.texels.size()) +
                            " texels for " + std::to_string(texture.width) + "x" + std::to_string(texture.height));
        }
    }
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        for (const TextureRef* ref : {&material.base_color_texture, &material.emissive_texture}) {
            if (ref->texture >= static_cast<int>(scene.textures.size())) {
                fail(scene, "material " + std::to_string(m) + " uses texture " + std::to_string(ref->texture) +
                                " but there are only " + std::to_string(scene.textures.size()) + " textures");
            }
        }
        if (!is_finite(material.emissive) || !std::isfinite(material.base_alpha) ||
            !std::isfinite(material.alpha_cutoff)) {
            fail(scene, "material " + std::to_string(m) + " has a non-finite emissive, alpha or cutoff");
        }
    }
    if (!is_finite(scene.light_color)) fail(scene, "light colour is not finite");
    if (scene.lights.size() > max_punctual_lights) {
        fail(scene, std::to_string(scene.lights.size()) + " lights (at most " + std::to_string(max_punctual_lights) +
                        ")");
    }
    for (std::size_t k = 0; k < scene.lights.size(); ++k) {
        const PunctualLight& light = scene.lights[k];
        if (!is_finite(light.position) || !is_finite(light.direction) || !is_finite(light.colour) ||
            !std::isfinite(light.range) || !std::isfinite(light.cos_inner) || !std::isfinite(light.cos_outer) ||
            light.range < 0.0f) {
            fail(scene, "light " + std::to_string(k) + " has a non-finite field or a negative range");
        }
    }
}

}  // namespace

void validate_scene(const Scene& scene) {
    const std::size_t vertex_count = scene.position_open.size();
    if (scene.position_close.size() != vertex_count) {
        fail(scene, std::to_string(vertex_count) + " open positions but " +
                        std::to_string(scene.position_close.size()) + " close positions");
    }
    if (scene.triangle_material.size() != scene.triangles.size()) {
        fail(scene, std::to_string(scene.triangles.size()) + " triangles but " +
                        std::to_string(scene.triangle_material.size()) + " triangle materials");
    }
    for (std::size_t i = 0; i < vertex_count; ++i) {
        if (!is_finite(scene.position_open[i]) || !is_finite(scene.position_close[i])) {
            fail(scene, "vertex " + std::to_string(i) + " has a non-finite position");
        }
    }
    check_interior_times(scene);
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        const glm::uvec3& tri = scene.triangles[t];
        for (int corner = 0; corner < 3; ++corner) {
            if (tri[corner] >= vertex_count) {
                fail(scene, "triangle " + std::to_string(t) + " uses vertex " +
                                std::to_string(tri[corner]) + " but there are only " +
                                std::to_string(vertex_count) + " vertices");
            }
        }
        if (scene.triangle_material[t] >= scene.materials.size()) {
            fail(scene, "triangle " + std::to_string(t) + " uses material " +
                            std::to_string(scene.triangle_material[t]) + " but there are only " +
                            std::to_string(scene.materials.size()) + " materials");
        }
    }
    check_materials(scene);
    const Camera& camera = scene.camera;
    if (!is_finite(camera.view_open) || !is_finite(camera.view_close)) {
        fail(scene, "camera view matrix is not finite");
    }
    if (!(camera.yfov > 0.0f && camera.yfov < 3.14159265f)) {
        fail(scene, "camera yfov " + std::to_string(camera.yfov) + " is outside (0, pi)");
    }
    if (!(camera.znear > 0.0f) || !std::isfinite(camera.znear)) {
        fail(scene, "camera znear " + std::to_string(camera.znear) + " is not positive");
    }
    if (!(camera.lens_radius >= 0.0f) || !std::isfinite(camera.lens_radius)) {
        fail(scene, "camera lens radius " + std::to_string(camera.lens_radius) + " is negative");
    }
    if (!(camera.focus_distance > 0.0f) || !std::isfinite(camera.focus_distance)) {
        fail(scene, "camera focus distance " + std::to_string(camera.focus_distance) +
                        " is not positive");
    }
    if (!is_finite(scene.light_direction) || !is_finite(scene.background)) {
        fail(scene, "light direction or background colour is not finite");
    }
    validate_surface_attributes(scene);
}

void require_valid_scene(const Scene& scene) {
    if (!scene.validated) validate_scene(scene);
}

SceneStats describe(const Scene& scene) {
    SceneStats stats;
    stats.triangles = scene.triangles.size();
    stats.vertices = scene.position_open.size();
    const std::size_t paired = std::min(scene.position_open.size(), scene.position_close.size());
    if (paired > 0) {
        stats.bounds_min = glm::vec3(INFINITY);
        stats.bounds_max = glm::vec3(-INFINITY);
    }
    for (std::size_t i = 0; i < paired; ++i) {
        const glm::vec3& open = scene.position_open[i];
        const glm::vec3& close = scene.position_close[i];
        stats.bounds_min = glm::min(stats.bounds_min, glm::min(open, close));
        stats.bounds_max = glm::max(stats.bounds_max, glm::max(open, close));
        if (open != close) {
            stats.object_motion = true;
            stats.max_vertex_displacement =
                std::max(stats.max_vertex_displacement, glm::length(close - open));
        }
    }
    const Camera& camera = scene.camera;
    stats.camera_motion = camera.view_open != camera.view_close;
    if (stats.camera_motion) {
        stats.camera_displacement =
            glm::length(eye_position(camera.view_close) - eye_position(camera.view_open));
        // Relative rotation R = R_close R_open^T; its angle from atan2 of the
        // skew part and the trace, in double so small angles stay accurate.
        const glm::dmat3 relative = glm::dmat3(glm::mat3(camera.view_close)) *
                                    glm::transpose(glm::dmat3(glm::mat3(camera.view_open)));
        const glm::dvec3 skew(relative[1][2] - relative[2][1], relative[2][0] - relative[0][2],
                              relative[0][1] - relative[1][0]);
        const double trace = relative[0][0] + relative[1][1] + relative[2][2];
        stats.camera_rotation =
            static_cast<float>(std::atan2(0.5 * glm::length(skew), 0.5 * (trace - 1.0)));
    }
    stats.lens_radius = camera.lens_radius;
    stats.focus_distance = camera.focus_distance;
    return stats;
}

}  // namespace blurcull::frontend
