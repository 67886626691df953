// `blurcull render`: options, scene loading, backend dispatch, summary output.
#pragma once

#include "app/scene_setup.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace blurcull::frontend {

struct RenderCommand : SceneFlags {
    RenderCommand() : SceneFlags("forest", 16, "1024x768") {}

    std::string backend = "auto";
    std::string method = "stochastic";
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
