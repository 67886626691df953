// `blurcull view`: the GL backend rendering into a GLFW window, with an orbit
// camera and keys for the lens, focus, shutter, spp and cull method; STE and
// frame time on screen. --frames and --screenshot run it without a user.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace blurcull::frontend {

// The keys and mouse buttons, as --help and the start-up message list them.
extern const char* const view_controls_help;

struct ViewCommand {
    // The hand (15k triangles) re-renders in seconds on llvmpipe; the forest
    // (168k) takes a minute a frame there.
    std::string scene = "hand";
    std::string cull = "clip2";
    int spp = 4;
    std::string size = "480x360";
    double lens_radius = -1.0;  // < 0: the scene's own
    double fstop = -1.0;
    double focus = -1.0;
    std::string shutter;        // "OPEN,CLOSE"; empty: the scene's own
    double blur_scale = 1.0;
    std::uint32_t seed = 1;
    int frames = 0;             // > 0: render this many frames, then exit
    std::string screenshot;     // PNG of the window after the last frame
    bool quiet = false;

    void add_options(CLI::App& app);
    int run() const;
};

}  // namespace blurcull::frontend
