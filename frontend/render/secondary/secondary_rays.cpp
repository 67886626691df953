#include "render/secondary/secondary_rays.hpp"

#include "render/common/method_plan.hpp"
#include "render/common/shading.hpp"
#include "render/common/parallel_items.hpp"
#include "render/common/resolve_shared.h"

#include <blurcull/kernel.hpp>
#include <blurcull/patterns.hpp>

#include <algorithm>
#include <cmath>

namespace blurcull::frontend {
namespace {

using resolve::SampleHit;

// The sample's hit (resolve::bc_sample_hit) on triangle `triangle` through
// lens position `lens` and NDC point `ndc` at `time`: the view-space
// vertices as the camera model moves them, the world ones mixed over the
// shutter. `inverse_open` and `inverse_close`: the inverses of the model's
// views, in double (made once per frame by the caller).
SampleHit sample_hit(const Scene& scene, const CameraModel& model, const glm::dmat4& inverse_open,
                     const glm::dmat4& inverse_close, std::uint32_t triangle, glm::vec2 ndc, glm::vec2 lens,
                     float time) {
    const glm::uvec3& tri = scene.triangles[triangle];
    glm::dvec3 view[3], world[3];
    for (int k = 0; k < 3; ++k) {
        view[k] = glm::dvec3(model.view_position_at(scene, tri[k], time));
        world[k] = glm::dvec3(glm::mix(scene.position_open[tri[k]], scene.position_close[tri[k]], time));
    }
    const Ray ray = model.lens_ray(ndc, lens);
    const glm::dvec3 o(ray.origin);
    return resolve::bc_sample_hit(view[0], view[1], view[2], world[0], world[1], world[2], o,
                                  glm::dvec3(ray.direction),
                                  resolve::bc_lens_world(inverse_open, inverse_close, o, double(time)));
}

// The rays a reflector sample spawns (resolve::bc_spawn_rays: one for a
// mirror, up to two for a dielectric).
void spawn_rays(const Material& material, const SampleHit& hit, std::uint32_t sample, std::uint32_t part,
                std::uint32_t triangle, float time, std::vector<SecondaryRay>& rays) {
    const resolve::SpawnedRays spawned =
        resolve::bc_spawn_rays(material.kind == MaterialKind::mirror, material.ior, hit.incident, hit.normal);
    if (spawned.count > 0)
        rays.push_back({hit.point, spawned.direction0, glm::vec3(spawned.weight0), sample, part, triangle, time});
    if (spawned.count > 1)
        rays.push_back({hit.point, spawned.direction1, glm::vec3(spawned.weight1), sample, part, triangle, time});
}

}  // namespace

std::uint32_t lens_part_of(glm::vec2 lens, int parts) { return resolve::bc_lens_part(lens, parts); }

PrimaryResolve resolve_primary(const Scene& scene, const CameraModel& model, const RenderSettings& settings,
                               const std::vector<std::uint32_t>& sample_ids, int lens_parts) {
    const std::vector<glm::vec3> colours = shade_all(scene);
    const auto spp = static_cast<std::uint32_t>(settings.spp);
    PrimaryResolve out;
    out.sample_colour.assign(sample_ids.size(), glm::vec3(0.0f));
    // Rows in parallel: each writes its own samples' colours and its own
    // rays, which are joined in row order (the order of a serial loop).
    struct Row {
        std::vector<SecondaryRay> rays;
        std::uint64_t reflector_samples = 0;
    };
    std::vector<Row> rows(static_cast<std::size_t>(settings.height));
    const glm::dmat4 inverse_open = glm::inverse(glm::dmat4(model.view_open));
    const glm::dmat4 inverse_close = glm::inverse(glm::dmat4(model.view_close));
    auto resolve_row = [&](int py) {
        Row& row = rows[static_cast<std::size_t>(py)];
        for (int px = 0; px < settings.width; ++px) {
            const patternsf::SamplerSetup pattern = patternsf::sampler_setup(
                settings.sampler, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py), spp, settings.seed);
            for (std::uint32_t j = 0; j < spp; ++j) {
                const std::uint32_t k = (static_cast<std::uint32_t>(py * settings.width + px)) * spp + j;
                const std::uint32_t id = sample_ids[k];
                if (id == no_sample_hit) {
                    out.sample_colour[k] = scene.background;
                    continue;
                }
                const Material& material = scene.materials[scene.triangle_material[id]];
                if (material.kind == MaterialKind::diffuse) {
                    out.sample_colour[k] = colours[id];
                    continue;
                }
                ++row.reflector_samples;
                const kernelf::PixelSample s = patternsf::sampler_sample(pattern, j);
                const SampleHit hit = sample_hit(scene, model, inverse_open, inverse_close, id,
                                                  model.sample_ndc(px, py, s.offset), s.lens, s.time);
                // A degenerate hit (grazing to the rounding) sees the environment straight on.
                if (!hit.valid) continue;
                spawn_rays(material, hit, k, lens_part_of(s.lens, lens_parts), id, s.time, row.rays);
            }
        }
    };
    run_parallel_items(
        render_threads(settings), settings.height, [] { return 0; },
        [&](int&, int py) { resolve_row(py); }, [](int&) {});
    std::size_t ray_count = 0;
    for (const Row& row : rows) ray_count += row.rays.size();
    out.rays.reserve(ray_count);
    for (const Row& row : rows) {
        out.rays.insert(out.rays.end(), row.rays.begin(), row.rays.end());
        out.reflector_samples += row.reflector_samples;
    }
    return out;
}

glm::vec3 bounce_hit_radiance(const Scene& scene, const std::vector<glm::vec3>& colours, std::uint32_t triangle,
                              glm::vec3 direction, glm::vec3 normal) {
    const Material& material = scene.materials[scene.triangle_material[triangle]];
    if (material.kind == MaterialKind::diffuse || glm::dot(normal, normal) == 0.0f) return colours[triangle];
    return specular_environment_colour(scene, material, direction, normal);
}

Image resolve_samples(const std::vector<glm::vec3>& sample_colour, int width, int height, int spp) {
    Image image(width, height);
    const auto per_pixel = static_cast<std::size_t>(spp);
    for (int py = 0; py < height; ++py) {
        for (int px = 0; px < width; ++px) {
            const std::size_t first = (static_cast<std::size_t>(py) * width + px) * per_pixel;
            glm::vec3 sum(0.0f);
            for (std::size_t j = 0; j < per_pixel; ++j) sum += sample_colour[first + j];
            image.at(px, py) = resolve_box(sum, spp);
        }
    }
    return image;
}

}  // namespace blurcull::frontend
