#include "render/common/surface_shading.hpp"

#include "render/common/moving_triangle.hpp"
#include "render/common/pixel_samples.hpp"
#include "render/common/shading.hpp"
#include "render/common/surface_shared.h"
#include "render/common/texture_sampling.hpp"

namespace blurcull::frontend {

namespace {

template <class V>
V interpolate(const std::vector<V>& values, const glm::uvec3& tri, glm::vec3 b) {
    constexpr int n = V::length();
    const auto padded = [&](unsigned vertex) {
        glm::vec4 a(0.0f);
        for (int c = 0; c < n; ++c) a[c] = values[vertex][c];
        return a;
    };
    const glm::vec4 mixed = surface::bc_interpolate(b, padded(tri.x), padded(tri.y), padded(tri.z));
    V out;
    for (int c = 0; c < n; ++c) out[c] = mixed[c];
    return out;
}

// The texture's texel at the hit's TEXCOORD_0 (0, 0 without texture coordinates).
glm::vec4 texture_at(const Scene& scene, const TextureRef& ref, const glm::uvec3& tri, glm::vec3 b) {
    const glm::vec2 uv = scene.texcoord.empty() ? glm::vec2(0.0f) : interpolate(scene.texcoord, tri, b);
    // glm::mat3 is column-major: row r is (m[0][r], m[1][r], m[2][r]).
    const glm::mat3& m = ref.transform;
    const Texture& texture = scene.textures[static_cast<std::size_t>(ref.texture)];
    return surface::bc_transformed_texture(texture, texture.width, texture.height, static_cast<int>(texture.wrap_s),
                                           static_cast<int>(texture.wrap_t), glm::vec3(m[0][0], m[1][0], m[2][0]),
                                           glm::vec3(m[0][1], m[1][1], m[2][1]), uv);
}

bool nonzero(const glm::vec3& v) { return v.x != 0.0f || v.y != 0.0f || v.z != 0.0f; }

// The interpolated shading normal, or the geometric one at shutter open.
glm::vec3 hit_normal(const Scene& scene, const glm::uvec3& tri, glm::vec3 b) {
    if (!scene.normal.empty() && nonzero(scene.normal[tri.x]) && nonzero(scene.normal[tri.y]) &&
        nonzero(scene.normal[tri.z])) {
        const glm::vec3 n = interpolate(scene.normal, tri, b);
        if (nonzero(n)) return n;
    }
    const glm::vec3 p0 = scene.position_open[tri.x];
    return glm::cross(scene.position_open[tri.y] - p0, scene.position_open[tri.z] - p0);
}

}  // namespace

bool shades_per_hit(const Scene& scene, std::size_t triangle) {
    const Material& material = scene.materials[scene.triangle_material[triangle]];
    if (lights_vary(scene) && material.kind == MaterialKind::diffuse && !material.unlit) return true;
    if (material.base_color_texture.texture >= 0 || material.emissive_texture.texture >= 0) return true;
    if (!scene.vertex_color.empty()) return true;
    if (scene.normal.empty()) return false;
    const glm::uvec3& tri = scene.triangles[triangle];
    return nonzero(scene.normal[tri.x]) && nonzero(scene.normal[tri.y]) && nonzero(scene.normal[tri.z]);
}

float hit_alpha(const Scene& scene, std::size_t triangle, glm::vec3 barycentric) {
    const Material& material = scene.materials[scene.triangle_material[triangle]];
    const glm::uvec3& tri = scene.triangles[triangle];
    const float vertex_alpha = scene.vertex_color.empty() ? 1.0f : interpolate(scene.vertex_color, tri, barycentric).w;
    const float texture_alpha = material.base_color_texture.texture < 0
                                    ? 1.0f
                                    : texture_at(scene, material.base_color_texture, tri, barycentric).w;
    return surface::bc_hit_alpha(material.base_alpha, vertex_alpha, texture_alpha);
}

glm::vec3 shade_hit(const Scene& scene, std::size_t triangle, glm::vec3 barycentric, glm::vec3 incident) {
    static_cast<void>(incident);  // two-sided diffuse: the same from every direction
    const Material& material = scene.materials[scene.triangle_material[triangle]];
    const glm::uvec3& tri = scene.triangles[triangle];
    glm::vec3 base = material.base_color;
    if (!scene.vertex_color.empty()) base *= glm::vec3(interpolate(scene.vertex_color, tri, barycentric));
    if (material.base_color_texture.texture >= 0)
        base *= glm::vec3(texture_at(scene, material.base_color_texture, tri, barycentric));
    glm::vec3 emissive = material.emissive;
    if (material.emissive_texture.texture >= 0)
        emissive *= glm::vec3(texture_at(scene, material.emissive_texture, tri, barycentric));
    // Point and spot lights see the hit where its normal is taken: at shutter open.
    const glm::vec3 p = scene.lights.empty() ? glm::vec3(0.0f) : interpolate(scene.position_open, tri, barycentric);
    return surface::bc_material_colour(material.unlit, base, scene_light(scene, p, hit_normal(scene, tri, barycentric)),
                                       emissive, shading_ambient);
}

SurfaceShader::SurfaceShader(const Scene& scene, const CameraModel& model, int threads)
    : scene_(scene), near_(static_cast<double>(model.znear)), flat_(shade_all(scene, threads)),
      per_hit_(scene.triangles.size(), 0), masked_(scene.triangles.size(), 0) {
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
        per_hit_[t] = shades_per_hit(scene, t) ? 1 : 0;
        masked_[t] = scene.materials[scene.triangle_material[t]].alpha_mode != AlphaMode::opaque ? 1 : 0;
        any_per_hit_ = any_per_hit_ || per_hit_[t] != 0;
        any_masked_ = any_masked_ || masked_[t] != 0;
    }
    if (!any_per_hit_ && !any_masked_) return;
    triangles_.resize(scene.triangles.size());
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) triangles_[t] = make_moving_triangle<double>(scene, model, t);
}

glm::vec3 SurfaceShader::barycentrics(std::uint32_t triangle, glm::vec2 ndc, glm::vec2 lens, float time) const {
    double depth = 0.0;
    kerneld::vec3 b(0.0);
    kerneld::covers_hit(triangles_[triangle], kerneld::vec2(ndc), kerneld::vec2(lens), static_cast<double>(time), near_,
                        depth, b);
    if (!(b.x + b.y + b.z > 0.0)) return glm::vec3(1.0f / 3.0f);
    return glm::vec3(b);
}

bool SurfaceShader::sample_kept(std::uint32_t triangle, glm::vec2 ndc, glm::vec2 lens, float time) const {
    if (masked_[triangle] == 0) return true;
    const Material& material = scene_.materials[scene_.triangle_material[triangle]];
    return surface::bc_alpha_test(hit_alpha(scene_, triangle, barycentrics(triangle, ndc, lens, time)),
                                  material.alpha_cutoff, material.alpha_mode == AlphaMode::blend, triangle, ndc, time);
}

glm::vec3 SurfaceShader::sample_colour(std::uint32_t triangle, glm::vec2 ndc, glm::vec2 lens, float time) const {
    if (triangle == no_hit) return scene_.background;
    if (per_hit_[triangle] == 0) return flat_[triangle];
    const glm::vec3 b = barycentrics(triangle, ndc, lens, time);
    return shade_hit(scene_, triangle, b, glm::vec3(0.0f, 0.0f, -1.0f));
}

}  // namespace blurcull::frontend

namespace blurcull::frontend {

Image resolve_sample_ids(const SurfaceShader& shader, const CameraModel& model, const RenderSettings& settings,
                         const std::vector<std::uint32_t>& ids) {
    Image image(settings.width, settings.height);
    const auto spp = static_cast<std::uint32_t>(settings.spp);
    std::vector<kernelf::PixelSample> samples(spp);
    for (int py = 0; py < settings.height; ++py) {
        for (int px = 0; px < settings.width; ++px) {
            const patternsf::SamplerSetup pattern = patternsf::sampler_setup(
                settings.sampler, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py), spp, settings.seed);
            const std::size_t base = image.index(px, py) * spp;
            glm::vec3 sum(0.0f);
            pixel_samples(pattern, 0, spp, samples.data());
            for (std::uint32_t j = 0; j < spp; ++j) {
                const kernelf::PixelSample& s = samples[j];
                sum += shader.sample_colour(ids[base + j], model.sample_ndc(px, py, s.offset), s.lens, s.time);
            }
            image.at(px, py) = resolve_box(sum, settings.spp);
        }
    }
    return image;
}

}  // namespace blurcull::frontend
