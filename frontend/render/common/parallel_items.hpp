// The thread pool the renderers share (the cpu backend, dof-secondary, the
// gl backends' host-side setup): work items handed out one at a time to the
// settings' threads, each thread with its own state.
#pragma once

#include "render/common/render_types.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace blurcull::frontend {

// The threads a CPU render runs on: settings.threads, or one per hardware
// thread when it is 0.
inline int render_threads(const RenderSettings& settings) {
    return settings.threads > 0 ? settings.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Runs items 0 .. items-1 on up to `threads` threads, the caller's among them,
// each taking the next item when it is free. Every thread makes its own state
// with make_state(), calls work(state, item) for each item it takes and, when
// none is left, done(state); done runs on several threads at once. If a thread
// cannot be started, the ones started finish and the error is rethrown.
template <class MakeState, class Work, class Done>
void run_parallel_items(int threads, int items, MakeState&& make_state, Work&& work, Done&& done) {
    std::atomic<int> next{0};
    auto worker = [&]() {
        auto state = make_state();
        for (int item = next.fetch_add(1); item < items; item = next.fetch_add(1)) work(state, item);
        done(state);
    };
    std::vector<std::thread> helpers;
    try {
        for (int i = 1; i < std::min(threads, items); ++i) helpers.emplace_back(worker);
    } catch (...) {
        next.store(items);
        for (std::thread& helper : helpers) helper.join();
        throw;
    }
    worker();
    for (std::thread& helper : helpers) helper.join();
}

// Runs body(begin, end) over the ranges of `run` items that cover
// [0, count), on up to `threads` threads: a loop whose items are independent
// (each writes only its own results), the same result on any number.
template <class Body>
void run_parallel_ranges(int threads, std::size_t count, std::size_t run, Body&& body) {
    const auto runs = static_cast<int>((count + run - 1) / run);
    run_parallel_items(
        threads, runs, [] { return 0; },
        [&](int&, int item) {
            const std::size_t begin = static_cast<std::size_t>(item) * run;
            body(begin, std::min(count, begin + run));
        },
        [](int&) {});
}

}  // namespace blurcull::frontend
