#include "render/gl/gl_render_targets.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

namespace blurcull::frontend {
namespace {

constexpr std::uint32_t zero_counters[4] = {0, 0, 0, 0};  // tested, hit, and their carries

}  // namespace

int get_integer(const gl::Functions& gl, GLenum name) {
    GLint value = 0;
    gl.GetIntegerv(name, &value);
    return value;
}

void require_target_fits(const gl::Functions& gl, int target_width, int target_height, int width, int height) {
    const int max_size = std::min({get_integer(gl, GL_MAX_TEXTURE_SIZE), get_integer(gl, GL_MAX_FRAMEBUFFER_WIDTH),
                                   get_integer(gl, GL_MAX_FRAMEBUFFER_HEIGHT)});
    if (target_width > max_size || target_height > max_size) {
        throw gl::GlError("gl: image size " + std::to_string(width) + "x" + std::to_string(height) +
                          " exceeds the context's limit of " + std::to_string(max_size) + " pixels per side");
    }
}

IdDepthTarget::IdDepthTarget(const gl::Functions& gl, int width, int height, int samples, const char* what)
    : gl_(&gl),
      width_(width),
      height_(height),
      id_texture_(gl, samples > 0 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D, GL_R32UI, width, height, samples),
      depth_texture_(gl, id_texture_.target(), GL_DEPTH_COMPONENT32F, width, height, samples),
      framebuffer_(gl) {
    const GLenum target = id_texture_.target();
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target, id_texture_.id(), 0);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, target, depth_texture_.id(), 0);
    const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) throw gl::GlError(std::string("gl: ") + what + " is incomplete");
}

void IdDepthTarget::bind_with_depth_rule() const {
    gl_->BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl_->Viewport(0, 0, width_, height_);
    gl_->ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    gl_->Enable(GL_DEPTH_TEST);
    gl_->DepthFunc(GL_GREATER);
    gl_->Enable(GL_DEPTH_CLAMP);
}

SampleCounters::SampleCounters(const gl::Functions& gl)
    : gl_(&gl), buffer_(gl, GL_SHADER_STORAGE_BUFFER, sizeof zero_counters, zero_counters) {}

void SampleCounters::add_to(RenderStats& stats) {
    gl_->MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t counters[4] = {0, 0, 0, 0};
    buffer_.read(counters, sizeof counters);
    stats.samples_tested += counters[0] + (std::uint64_t{counters[2]} << 32);
    stats.samples_hit += counters[1] + (std::uint64_t{counters[3]} << 32);
    gl_->BindBuffer(GL_SHADER_STORAGE_BUFFER, buffer_.id());
    gl_->BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero_counters, zero_counters);
}

void SampleCounters::preset(const std::uint32_t (&words)[4]) { buffer_.write(words, sizeof words); }

}  // namespace blurcull::frontend
