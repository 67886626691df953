// Cleanups that run at the end of every test executable's main (doctest_main.cpp),
// after the test run and before the statics are destroyed: for objects a test
// file shares through a static (e.g. frontend_test_helpers.hpp's GL renderer)
// that must not outlive main. A GL context's driver registers exit handlers
// while it initialises (NVIDIA's EGL in eglInitialize) that shut it down
// before such statics' destructors run, so a renderer destroyed there calls
// into a dead driver (SIGSEGV at exit).
#pragma once

#include <functional>

namespace blurcull::frontend::test {

// Runs `cleanup` at the end of main; the last registered runs first.
void at_end_of_main(std::function<void()> cleanup);

// Runs and forgets the registered cleanups (doctest_main.cpp calls it).
void run_end_of_main_cleanups();

}  // namespace blurcull::frontend::test
