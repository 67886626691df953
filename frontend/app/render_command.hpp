// `blurcull render`: options, scene loading, backend dispatch, summary output.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace blurcull::frontend {

struct RenderCommand {
    std::string scene = "forest";
    std::string backend = "auto";
    std::string cull = "clip2";
    std::string method = "stochastic";
    int spp = 16;
    std::string size = "1024x768";
    double lens_radius = -1.0;  // < 0: the scene's own
    double fstop = -1.0;
    double focus = -1.0;
    std::string shutter;        // "OPEN,CLOSE"; empty: the scene's own
    double blur_scale = 1.0;
    std::uint32_t seed = 1;
    std::string output;         // empty: <scene>.png in the current folder
    bool json = false;
    int threads = 0;
    int footprint = 4;  // CpuOptions::footprint
    std::string precision = "double";  // CpuOptions::precision
    bool quiet = false;

    void add_options(CLI::App& app);
    int run() const;
};

int list_scenes();

}  // namespace blurcull::frontend
