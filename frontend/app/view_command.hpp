// `blurcull view`: the GL backend (or, where GL is software, the CPU backend
// refining progressively: view_progressive.hpp) rendering into a GLFW window,
// with an orbit camera and keys for the lens, focus, shutter, spp, cull method
// and render method (stochastic or dof-secondary; on the CPU backend
// stochastic only); STE and frame time on screen. --frames and --screenshot
// run it without a user.
#pragma once

#include "app/scene_setup.hpp"
#include "app/secondary_flags.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace blurcull::frontend {

// The keys and mouse buttons, as --help and the start-up message list them.
extern const char* const view_controls_help;

// The --secondary-* flags are render's (SecondaryFlags).
struct ViewCommand : SceneFlags, SecondaryFlags {
    // The hand (15k triangles) re-renders in seconds on llvmpipe; the forest
    // (168k) takes a minute a frame there.
    ViewCommand() : SceneFlags("hand", 4, "480x360") {}

    std::string backend = "auto";  // auto, gl or cpu (view_command.cpp, view_draws_with_cpu)
    int frames = 0;             // > 0: render this many frames, then exit
    std::string screenshot;     // PNG of the window after the last frame
    bool quiet = false;
    std::string method = "stochastic";  // the initial method: stochastic or dof-secondary (M toggles)
    // Whether --scene and --size were given: dof-secondary has its own defaults.
    const CLI::Option* scene_option = nullptr;
    const CLI::Option* size_option = nullptr;

    void add_options(CLI::App& app);
    int run() const;
};

}  // namespace blurcull::frontend
