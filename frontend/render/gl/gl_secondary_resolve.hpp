// dof-secondary's primary resolve on the GPU: resolve_primary
// (render/secondary/secondary_rays.hpp) as compute passes
// (shaders/render_secondary_resolve.comp) on the same shared text (the
// kernel's sampler, resolve_shared.h's fp64 sample hit and spawned rays,
// optics_shared.h), so on a GL that rounds as IEEE does the same sample
// colours and rays, in the same order, bit for bit (the test asserts it).
// The rays stay on the GPU in GlClustering's point layout with their group
// keys; docs/secondary-rays.md, "The renderer".
#pragma once

#include "render/gl/gl_context.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace blurcull::frontend {

// What the resolve needs of the scene, the camera and the settings, in the
// host's own values (the caller computes them as the host resolve does).
struct GlResolveInput {
    int width = 1, height = 1, spp = 1, sampler = 0, lens_parts = 1;
    std::uint32_t seed = 0;
    float k_x = 1.0f, k_y = 1.0f, lens_radius = 0.0f, lens_slope = 0.0f;  // CameraModel's
    glm::vec3 background{0.0f};
    // Per vertex: view position at shutter open and close (CameraModel::view_position), world ones.
    std::vector<glm::vec3> view_open, view_close, world_open, world_close;
    // Per triangle: its vertices, material kind (MaterialKind), index of refraction and shade() colour.
    std::vector<glm::uvec3> triangles;
    std::vector<std::uint32_t> kinds;
    std::vector<float> iors;
    std::vector<glm::vec3> colours;
    glm::dmat4 inverse_open{1.0}, inverse_close{1.0};  // the views' inverses, in double
};

// The resolve's result as read back: per sample its direct colour; per ray,
// in the host's order, its position and direction with their key words
// (GlClustering's points: triangle, pixel << 4 | lens part), its sample,
// time and weight.
struct GlResolved {
    std::vector<glm::vec3> sample_colour;
    std::vector<glm::uvec4> points;  // 2 a ray: position bits + triangle, direction bits + pixel key
    std::vector<glm::uvec4> info;    // sample, time bits, weight bits, 0
    std::uint64_t reflector_samples = 0;
};

class GlSecondaryResolve {
public:
    // On `context` (kept alive by the caller; made current here and by the
    // destructor); compiles the pass. resolve() runs on the current context.
    // Throws gl::GlError with the compiler's log.
    explicit GlSecondaryResolve(const gl::HeadlessContext& context);
    ~GlSecondaryResolve();
    GlSecondaryResolve(const GlSecondaryResolve&) = delete;
    GlSecondaryResolve& operator=(const GlSecondaryResolve&) = delete;

    // resolve_primary of the winning triangles `sample_ids` (no_sample_hit
    // for none): four passes, two waits (the rays' count, then the colours
    // and rays read back). nullopt where the samples' colours (16 bytes a
    // sample) or the rays' points (32 bytes a ray) would pass the GL's
    // largest storage block, or an index 32 bits, or a pixel the keys' 28
    // bits: the caller resolves on the host then.
    // Throws gl::GlError when GL reports an error or the ids do not fit the input's size.
    std::optional<GlResolved> resolve(const GlResolveInput& input, const std::vector<std::uint32_t>& sample_ids) const;

    // The last resolve()'s rays on the GPU: 2 uvec4 a ray (GlResolved::points).
    // Throws gl::GlError before the first call.
    const gl::Buffer& points_buffer() const;

private:
    const gl::HeadlessContext* context_;
    const gl::Functions* gl_;
    std::unique_ptr<gl::Program> program_;
    mutable std::optional<gl::Buffer> ids_, vertices_, triangles_, frame_, colours_, counts_, info_, points_;
};

}  // namespace blurcull::frontend
