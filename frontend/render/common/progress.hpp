// "name: N%" on stderr for a render that has run over a second (so short
// renders print nothing), ending with one "name: 100%" line. Thread-safe.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <utility>

namespace blurcull::frontend {

// The clock of every render's timings (RenderStats::ms_total, ms_per_phase).
using RenderClock = std::chrono::steady_clock;

// Milliseconds from `start` to now.
inline double ms_since(RenderClock::time_point start) {
    return std::chrono::duration<double, std::milli>(RenderClock::now() - start).count();
}

class Progress {
public:
    using Clock = std::chrono::steady_clock;

    // total = the number of advance() calls the render makes.
    Progress(bool enabled, Clock::time_point start, int total, std::string name = "cpu")
        : enabled_(enabled), start_(start), total_(total > 0 ? total : 1), name_(std::move(name)) {}

    void advance() {
        const int done = done_.fetch_add(1) + 1;
        if (!enabled_) return;
        if (std::chrono::duration<double, std::milli>(Clock::now() - start_).count() < 1000.0) return;
        const int percent = static_cast<int>(100LL * done / total_);
        std::lock_guard<std::mutex> lock(mutex_);
        if (percent != last_percent_) {
            std::fprintf(stderr, "\r%s: %3d%%", name_.c_str(), percent);
            std::fflush(stderr);
            last_percent_ = percent;
            shown_ = true;
        }
    }

    // Ends the line; prints 100% only if the last advance() did not already.
    void finish() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!shown_) return;
        if (last_percent_ != 100) std::fprintf(stderr, "\r%s: 100%%", name_.c_str());
        std::fprintf(stderr, "\n");
        shown_ = false;
    }

private:
    bool enabled_;
    Clock::time_point start_;
    int total_;
    std::string name_;
    std::atomic<int> done_{0};
    std::mutex mutex_;
    int last_percent_ = -1;
    bool shown_ = false;
};

}  // namespace blurcull::frontend
