// `blurcull render`: options, scene loading, backend dispatch, summary output.
#pragma once

#include "app/scene_setup.hpp"
#include "app/secondary_flags.hpp"
#include "render/common/render_types.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/gl/gl_backend.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace blurcull::frontend {

// The dof-secondary flags come from SecondaryFlags (shared with `blurcull view`).
struct RenderCommand : SceneFlags, SecondaryFlags {
    RenderCommand() : SceneFlags("forest", 16, "1024x768") {}

    std::string backend = "auto";
    std::string method = to_string(RenderSettings{}.method);
    // The stochastic renderers' sample pattern (BC_PATTERN_*, pattern_names.hpp).
    std::string sampler = sample_pattern_name(RenderSettings{}.sampler);
    std::string output;         // empty: <scene>.png, or <scene>_%04d.png for --frames, in the current folder
    std::string exr_type = "half";  // an .exr output's channels: half or float
    // A sequence (app/frame_sequence.hpp): "A:B[:STEP]"; empty: one frame.
    std::string frames;
    double fps = 24.0;
    double shutter_angle = 180.0;  // degrees of the frame interval the shutter is open, (0, 360]
    bool json = false;
    int threads = 0;
    int footprint = CpuOptions{}.footprint;
    // cpu, bbox and hull: time slices and lens parts per axis (CpuOptions::time_strata, lens_strata).
    int time_strata = CpuOptions{}.time_strata;
    int lens_strata = CpuOptions{}.lens_strata;
    std::string occlusion = CpuOptions{}.occlusion ? "on" : "off";  // cpu: CpuOptions::occlusion
    std::string precision = to_string(CpuOptions{}.precision);
    int gl_cell = GlOptions{}.cell_pixels;
    std::string gl_pipeline = to_string(GlOptions{}.pipeline);  // gl: fragment or compute (GlPipeline)
    std::string secondary = "bounce";  // embree: bounce or none (EmbreeSecondary)
    bool quiet = false;
    std::string layer_images = "gl";  // dof-secondary on gl: where the layers are built, gl or host

    // The backend-specific options, to tell whether they were given
    // (count() > 0) when the backend in use cannot honour them.
    CLI::Option* method_option = nullptr;
    CLI::Option* sampler_option = nullptr;
    CLI::Option* footprint_option = nullptr;
    CLI::Option* time_strata_option = nullptr;
    CLI::Option* lens_strata_option = nullptr;
    CLI::Option* occlusion_option = nullptr;
    CLI::Option* precision_option = nullptr;
    CLI::Option* gl_cell_option = nullptr;
    CLI::Option* gl_pipeline_option = nullptr;
    CLI::Option* secondary_option = nullptr;
    CLI::Option* layer_images_option = nullptr;  // --layer-images, gl only
    // The sequence's and the EXR's options, refused without --frames or an .exr output.
    CLI::Option* frames_option = nullptr;
    CLI::Option* fps_option = nullptr;
    CLI::Option* shutter_angle_option = nullptr;
    CLI::Option* exr_type_option = nullptr;

    // Declares the options on `app`, their checks and help read from the
    // registries of cull methods, render methods, precisions and backends.
    void add_options(CLI::App& app);

    // Renders as the options say and prints the summary; returns the exit
    // status. Throws std::exception with a one-line message naming the flag.
    int run() const;
};

// Prints every built-in scene, one a line: its name, then its one-line
// description (builtin_scene_catalogue). Returns the exit status.
int list_scenes();

}  // namespace blurcull::frontend
