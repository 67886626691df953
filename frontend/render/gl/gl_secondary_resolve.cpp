#include "render/gl/gl_secondary_resolve.hpp"

#include "render/gl/gl_render_targets.hpp"
#include "render/gl/gpu_layout_shared.h"
#include "render/gl/shader_stages.hpp"

#include <cstring>
#include <string>

namespace blurcull::frontend {
namespace {

// render_secondary_resolve.comp's steps and chunk.
enum Step : int { samples_step = 0, chunks_step = 1, scan_step = 2, rays_step = 3 };
constexpr std::size_t chunk = 256;

std::uint32_t bits_of(float x) {
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return bits;
}

}  // namespace

GlSecondaryResolve::GlSecondaryResolve(const gl::HeadlessContext& context)
    : context_((context.make_current(), &context)),
      gl_(&context.gl()),
      program_(std::make_unique<gl::Program>(
          context.gl(), std::vector<gl::ShaderStage>{gl::shader_stage(GL_COMPUTE_SHADER, "render_secondary_resolve.comp",
                                                                      gl::Prelude::resolve)})) {}

// The program's and buffers' glDelete* act on the current context: this one's.
GlSecondaryResolve::~GlSecondaryResolve() { context_->make_current_for_release(); }

std::optional<GlResolved> GlSecondaryResolve::resolve(const GlResolveInput& in,
                                                      const std::vector<std::uint32_t>& sample_ids) const {
    const std::size_t n = sample_ids.size();
    if (n != std::size_t(in.width) * std::size_t(in.height) * std::size_t(in.spp) || n == 0)
        throw gl::GlError("gl: the resolve got " + std::to_string(n) + " sample ids for a " + std::to_string(in.width) +
                          "x" + std::to_string(in.height) + " image of " + std::to_string(in.spp) + " spp");
    const std::size_t chunks = (n + chunk - 1) / chunk;
    const gl::Functions& f = *gl_;
    const auto block = static_cast<std::size_t>(static_cast<unsigned>(get_integer(f, GL_MAX_SHADER_STORAGE_BLOCK_SIZE)));
    // Rays of up to two a sample, and every index, in 32 bits; the keys' pixels in 28; the colours in a block.
    if (2 * n + 2 * chunks + 2 > 0xffffffffu || n / std::size_t(in.spp) >= (std::size_t{1} << 28) ||
        n * sizeof(glm::vec4) > block)
        return std::nullopt;
    std::vector<glm::vec4> vertices;
    vertices.reserve(4 * in.view_open.size());
    for (std::size_t v = 0; v < in.view_open.size(); ++v) {
        for (const glm::vec3& p : {in.view_open[v], in.view_close[v], in.world_open[v], in.world_close[v]})
            vertices.emplace_back(p, 0.0f);
    }
    std::vector<std::uint32_t> triangles;
    triangles.reserve(8 * in.triangles.size());
    for (std::size_t t = 0; t < in.triangles.size(); ++t) {
        const glm::vec3 c = in.colours[t];
        for (std::uint32_t word : {in.triangles[t].x, in.triangles[t].y, in.triangles[t].z, in.kinds[t], bits_of(c.x),
                                   bits_of(c.y), bits_of(c.z), bits_of(in.iors[t])})
            triangles.push_back(word);
    }
    double frame[32];
    std::memcpy(frame, &in.inverse_open[0][0], 16 * sizeof(double));
    std::memcpy(frame + 16, &in.inverse_close[0][0], 16 * sizeof(double));
    const std::vector<std::uint32_t> no_counts(n + 2 * chunks + 2, 0u);
    gl::reserve_storage(f, ids_, n * 4, sample_ids.data()).bind_base(BC_GL_RESOLVE_IDS_BINDING);
    gl::reserve_storage(f, vertices_, vertices.size() * sizeof(glm::vec4), vertices.data())
        .bind_base(BC_GL_RESOLVE_VERTICES_BINDING);
    gl::reserve_storage(f, triangles_, triangles.size() * 4, triangles.data()).bind_base(BC_GL_RESOLVE_TRIANGLES_BINDING);
    gl::reserve_storage(f, frame_, sizeof frame, frame).bind_base(BC_GL_RESOLVE_FRAME_BINDING);
    gl::reserve_storage(f, colours_, n * sizeof(glm::vec4)).bind_base(BC_GL_RESOLVE_COLOURS_BINDING);
    gl::reserve_storage(f, counts_, no_counts.size() * 4, no_counts.data()).bind_base(BC_GL_RESOLVE_COUNTS_BINDING);

    const GLuint id = program_->id();
    f.UseProgram(id);
    f.Uniform1ui(f.GetUniformLocation(id, "width"), static_cast<GLuint>(in.width));
    f.Uniform1ui(f.GetUniformLocation(id, "height"), static_cast<GLuint>(in.height));
    f.Uniform1ui(f.GetUniformLocation(id, "spp"), static_cast<GLuint>(in.spp));
    f.Uniform1i(f.GetUniformLocation(id, "sampler"), in.sampler);
    f.Uniform1ui(f.GetUniformLocation(id, "seed"), in.seed);
    f.Uniform1i(f.GetUniformLocation(id, "lens_parts"), in.lens_parts);
    f.Uniform1f(f.GetUniformLocation(id, "k_x"), in.k_x);
    f.Uniform1f(f.GetUniformLocation(id, "k_y"), in.k_y);
    f.Uniform1f(f.GetUniformLocation(id, "lens_radius"), in.lens_radius);
    f.Uniform1f(f.GetUniformLocation(id, "lens_slope"), in.lens_slope);
    f.Uniform3f(f.GetUniformLocation(id, "background"), in.background.x, in.background.y, in.background.z);
    const GLint step = f.GetUniformLocation(id, "step");
    auto run = [&](Step s, std::size_t items) {
        f.Uniform1i(step, s);
        gl::dispatch_in_rows(f, (items + 63) / 64);
        f.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    };
    run(samples_step, n);
    run(chunks_step, chunks);
    run(scan_step, 1);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    // The rays' count, for their buffers: the one wait before the rays.
    std::uint32_t totals[2] = {0, 0};
    counts_->read(totals, sizeof totals, (n + 2 * chunks) * 4);
    const std::size_t rays = totals[0];
    if (2 * rays * sizeof(glm::uvec4) > block) {
        f.UseProgram(0);
        return std::nullopt;
    }
    gl::reserve_storage(f, info_, rays * sizeof(glm::uvec4)).bind_base(BC_GL_RESOLVE_RAYS_BINDING);
    gl::reserve_storage(f, points_, 2 * rays * sizeof(glm::uvec4)).bind_base(BC_GL_CLUSTER_POINTS_BINDING);
    f.UseProgram(id);
    run(rays_step, chunks);
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    f.UseProgram(0);
    gl::check_gl(f, "dof-secondary: the resolve passes");

    GlResolved out;
    out.reflector_samples = totals[1];
    std::vector<glm::vec4> colours(n);
    colours_->read(colours.data(), n * sizeof(glm::vec4));
    out.sample_colour.reserve(n);
    for (const glm::vec4& c : colours) out.sample_colour.emplace_back(c);
    out.points.resize(2 * rays);
    out.info.resize(rays);
    if (rays > 0) {
        points_->read(out.points.data(), out.points.size() * sizeof(glm::uvec4));
        info_->read(out.info.data(), out.info.size() * sizeof(glm::uvec4));
    }
    return out;
}

const gl::Buffer& GlSecondaryResolve::points_buffer() const {
    if (!points_) throw gl::GlError("gl: no samples resolved yet, so no rays on the GPU");
    return *points_;
}

}  // namespace blurcull::frontend
