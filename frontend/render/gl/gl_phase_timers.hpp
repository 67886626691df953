// GPU time per phase of a GL pass: a GL_TIME_ELAPSED query per named phase,
// each summed over the times the phase ran, beside the host's clock over the
// same calls. The compute pipeline times setup, binning, raster and resolve
// with it; dof-secondary's GPU-resident bounce its layers and traces.
// docs/gl-backend.md, "The compute pipeline".
#pragma once

#include "render/common/progress.hpp"
#include "render/common/render_types.hpp"
#include "render/gl/gl_context.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace blurcull::frontend {

class GlPhaseTimers {
public:
    // One query per name, on the current context (which must stay current
    // for begin, end and the destructor); without `gpu_clock` none, and
    // only the host's clock (for software GL, whose queries mean nothing).
    // With `wait` end() waits for the phase's GPU work (the phases do not
    // overlap, and the wall time includes the GPU's); without, a phase's
    // query result is collected at its next begin() or at add_to, and its
    // wall time is the host's time to issue it.
    GlPhaseTimers(const gl::Functions& gl, std::vector<std::string> names, bool gpu_clock = true, bool wait = true);
    GlPhaseTimers(const GlPhaseTimers&) = delete;
    GlPhaseTimers& operator=(const GlPhaseTimers&) = delete;
    ~GlPhaseTimers();

    // Phases do not nest: end(k) before the next begin.
    void begin(std::size_t phase);
    // Ends the phase's query (adding its time, waiting for it, with `wait`)
    // and adds the host's clock from begin to then.
    void end(std::size_t phase);

    // ms_per_phase gets gpu_<name> (GL_TIME_ELAPSED: the GPU's own clock;
    // llvmpipe's timer queries do not time compute dispatches and read ~0,
    // and give draws nonsense) with the GPU clock, then wall_<name> (the
    // host's clock over the phase's calls and its wait) for every phase.
    void add_to(RenderStats& stats);

private:
    void collect(std::size_t phase);  // a pending query's time, waited for

    const gl::Functions* gl_;
    std::vector<std::string> names_;
    std::vector<GLuint> ids_;
    std::vector<double> gpu_ms_, wall_ms_;
    std::vector<char> pending_;  // a query ended but not read
    bool wait_;
    RenderClock::time_point started_ = RenderClock::now();
};

}  // namespace blurcull::frontend
