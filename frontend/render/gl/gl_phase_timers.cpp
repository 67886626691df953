#include "render/gl/gl_phase_timers.hpp"

#include <utility>

namespace blurcull::frontend {

GlPhaseTimers::GlPhaseTimers(const gl::Functions& gl, std::vector<std::string> names, bool gpu_clock, bool wait)
    : gl_(&gl),
      names_(std::move(names)),
      ids_(gpu_clock ? names_.size() : 0, 0),
      gpu_ms_(names_.size(), 0.0),
      wall_ms_(names_.size(), 0.0),
      pending_(names_.size(), 0),
      wait_(wait) {
    if (!ids_.empty()) gl.GenQueries(static_cast<GLsizei>(ids_.size()), ids_.data());
}

GlPhaseTimers::~GlPhaseTimers() {
    if (!ids_.empty()) gl_->DeleteQueries(static_cast<GLsizei>(ids_.size()), ids_.data());
}

void GlPhaseTimers::collect(std::size_t phase) {
    if (!pending_[phase]) return;
    GLuint64 ns = 0;
    gl_->GetQueryObjectui64v(ids_[phase], GL_QUERY_RESULT, &ns);
    gpu_ms_[phase] += static_cast<double>(ns) * 1e-6;
    pending_[phase] = 0;
}

void GlPhaseTimers::begin(std::size_t phase) {
    if (!ids_.empty()) {
        collect(phase);  // the query object is reused
        gl_->BeginQuery(GL_TIME_ELAPSED, ids_[phase]);
    }
    started_ = RenderClock::now();
}

void GlPhaseTimers::end(std::size_t phase) {
    if (!ids_.empty()) {
        gl_->EndQuery(GL_TIME_ELAPSED);
        pending_[phase] = 1;
        if (wait_) collect(phase);
    }
    wall_ms_[phase] += ms_since(started_);
}

void GlPhaseTimers::add_to(RenderStats& stats) {
    for (std::size_t k = 0; k < ids_.size(); ++k) collect(k);
    for (std::size_t k = 0; k < ids_.size(); ++k) stats.ms_per_phase.emplace_back("gpu_" + names_[k], gpu_ms_[k]);
    for (std::size_t k = 0; k < names_.size(); ++k) stats.ms_per_phase.emplace_back("wall_" + names_[k], wall_ms_[k]);
}

}  // namespace blurcull::frontend
