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
    // Queries on the current context (which must stay current for begin,
    // end, add_to and the destructor); without `gpu_clock` none, and only
    // the host's clock (for software GL, whose queries mean nothing). With
    // `wait` end() waits for the phase's GPU work (the phases do not
    // overlap, and the wall time includes the GPU's); without, each run of
    // a phase gets a query of its own, all read at add_to, so nothing waits
    // before then, and its wall time is the host's time to issue it.
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
    void collect(std::size_t phase);  // the phase's pending queries' times, waited for

    const gl::Functions* gl_;
    std::vector<std::string> names_;
    bool gpu_clock_;
    std::vector<std::vector<GLuint>> pending_;  // per phase, queries begun and not read
    std::vector<GLuint> spare_;                 // queries read, for the next begin
    std::vector<double> gpu_ms_, wall_ms_;
    bool wait_;
    RenderClock::time_point started_ = RenderClock::now();
};

}  // namespace blurcull::frontend
