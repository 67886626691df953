#include "render/gl/gl_phase_timers.hpp"

#include <utility>

namespace blurcull::frontend {

GlPhaseTimers::GlPhaseTimers(const gl::Functions& gl, std::vector<std::string> names, bool gpu_clock, bool wait)
    : gl_(&gl),
      names_(std::move(names)),
      gpu_clock_(gpu_clock),
      pending_(names_.size()),
      gpu_ms_(names_.size(), 0.0),
      wall_ms_(names_.size(), 0.0),
      wait_(wait) {}

GlPhaseTimers::~GlPhaseTimers() {
    for (std::vector<GLuint>& queries : pending_) spare_.insert(spare_.end(), queries.begin(), queries.end());
    if (!spare_.empty()) gl_->DeleteQueries(static_cast<GLsizei>(spare_.size()), spare_.data());
}

void GlPhaseTimers::collect(std::size_t phase) {
    for (GLuint query : pending_[phase]) {
        GLuint64 ns = 0;
        gl_->GetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
        gpu_ms_[phase] += static_cast<double>(ns) * 1e-6;
        spare_.push_back(query);
    }
    pending_[phase].clear();
}

void GlPhaseTimers::begin(std::size_t phase) {
    if (gpu_clock_) {
        if (spare_.empty()) {
            GLuint query = 0;
            gl_->GenQueries(1, &query);
            spare_.push_back(query);
        }
        pending_[phase].push_back(spare_.back());
        spare_.pop_back();
        gl_->BeginQuery(GL_TIME_ELAPSED, pending_[phase].back());
    }
    started_ = RenderClock::now();
}

void GlPhaseTimers::end(std::size_t phase) {
    if (gpu_clock_) {
        gl_->EndQuery(GL_TIME_ELAPSED);
        if (wait_) collect(phase);
    }
    wall_ms_[phase] += ms_since(started_);
}

void GlPhaseTimers::add_to(RenderStats& stats) {
    if (gpu_clock_) {
        for (std::size_t k = 0; k < names_.size(); ++k) collect(k);
        for (std::size_t k = 0; k < names_.size(); ++k)
            stats.ms_per_phase.emplace_back("gpu_" + names_[k], gpu_ms_[k]);
    }
    for (std::size_t k = 0; k < names_.size(); ++k) stats.ms_per_phase.emplace_back("wall_" + names_[k], wall_ms_[k]);
}

}  // namespace blurcull::frontend
