#include "render/gl/gl_frame_common.hpp"

#include "render/common/moving_triangle.hpp"
#include "render/common/parallel_items.hpp"
#include "render/common/shading.hpp"

#include <blurcull/kernel.hpp>

#include <algorithm>

namespace blurcull::frontend {

void set_int(const gl::Functions& gl, const gl::Program& program, const char* name, int value) {
    gl.Uniform1i(gl.GetUniformLocation(program.id(), name), value);
}
void set_uint(const gl::Functions& gl, const gl::Program& program, const char* name, std::uint32_t value) {
    gl.Uniform1ui(gl.GetUniformLocation(program.id(), name), value);
}
void set_float(const gl::Functions& gl, const gl::Program& program, const char* name, float value) {
    gl.Uniform1f(gl.GetUniformLocation(program.id(), name), value);
}

void set_common(const gl::Functions& gl, const gl::Program& program, const CameraModel& model,
                const RenderSettings& settings, std::uint32_t pass_base) {
    gl.UseProgram(program.id());
    gl.Uniform2f(gl.GetUniformLocation(program.id(), "image_size"), static_cast<float>(settings.width),
                 static_cast<float>(settings.height));
    set_float(gl, program, "near_plane", model.znear);
    set_uint(gl, program, "spp", static_cast<std::uint32_t>(settings.spp));
    set_uint(gl, program, "seed", settings.seed);
    set_int(gl, program, "sampler", settings.sampler);  // the stages that draw samples; -1 elsewhere, ignored
    set_uint(gl, program, "pass_base", pass_base);
}

gl::Buffer storage_buffer(const gl::Functions& gl, std::size_t bytes) {
    return gl::Buffer(gl, GL_SHADER_STORAGE_BUFFER, bytes);
}

FrameTriangles frame_triangles(const Scene& scene, const CameraModel& model, bool force_full_path, int threads) {
    return frame_triangles(scene, model, force_full_path, 0, scene.triangles.size(), threads);
}

FrameTriangles frame_triangles(const Scene& scene, const CameraModel& model, bool force_full_path,
                               std::size_t first, std::size_t count, int threads) {
    FrameTriangles out;
    out.gpu.resize(std::max<std::size_t>(count, 1));
    out.classes.assign(std::max<std::size_t>(count, 1), BC_INVALID);
    // Each triangle on its own: runs of 16,384 on the threads, then the
    // lists in index order.
    run_parallel_ranges(threads, count, 16384, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const kernelf::MovingTriangle tri = make_moving_triangle<float>(scene, model, first + k);
            out.classes[k] = kernelf::classify(tri);
            out.gpu[k] = gpu::to_gpu(tri);
        }
    });
    for (std::size_t k = 0; k < count; ++k) {
        const auto i = static_cast<std::uint32_t>(first + k);
        if (out.classes[k] == 0 && !force_full_path) {
            out.static_list.push_back(i);
        } else if (out.classes[k] != BC_INVALID) {
            out.moving_list.push_back(i);
        }
    }
    out.static_count = out.static_list.size();
    out.moving_count = out.moving_list.size();
    if (out.static_list.empty()) out.static_list.push_back(0);
    if (out.moving_list.empty()) out.moving_list.push_back(0);
    return out;
}

std::vector<glm::vec4> frame_colours(const std::vector<glm::vec3>& flat, const Scene& scene) {
    std::vector<glm::vec4> colours;
    colours.reserve(flat.size() + 1);
    for (const glm::vec3& colour : flat) colours.emplace_back(colour, 1.0f);
    colours.emplace_back(scene.background, 1.0f);
    return colours;
}

Image image_from_sums(const gl::Buffer& sums_buffer, const RenderSettings& settings) {
    const std::size_t pixels = static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height);
    std::vector<glm::vec4> sums(pixels);
    sums_buffer.read(sums.data(), pixels * sizeof(glm::vec4));
    Image image(settings.width, settings.height);
    image.coverage.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        image.pixels[i] = resolve_box(glm::vec3(sums[i]), settings.spp);
        // .w counts the samples that hit (render_resolve.comp): exact in float up to 2^24.
        image.coverage[i] = resolve_coverage(static_cast<std::uint32_t>(sums[i].w), settings.spp);
    }
    return image;
}

}  // namespace blurcull::frontend
