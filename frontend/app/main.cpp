// The `blurcull` command: renders built-in or glTF scenes with motion blur and
// depth of field on the chosen backend, and reports what the culling cost.
#include "app/render_command.hpp"
#if BLURCULL_HAVE_VIEW
#include "app/view_command.hpp"
#endif

#include <blurcull/version.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

int main(int argc, char** argv) {
    using namespace blurcull::frontend;
    CLI::App app{"blurcull: motion blur and depth of field by stochastic rasterization with sample culling"};
    app.set_version_flag("--version", std::string("blurcull ") + blurcull::version_string());
    app.require_subcommand(0, 1);
    CLI::App* view_app = nullptr;
    // One line naming the flag and what it accepts, like every other error.
    app.failure_message([&view_app](const CLI::App*, const CLI::Error& error) {
        const char* command = view_app != nullptr && view_app->parsed() ? "view" : "render";
        return std::string("blurcull: error: ") + error.what() + " (see blurcull " + command + " --help)\n";
    });

    RenderCommand render;
    CLI::App* render_app = app.add_subcommand("render", "render a scene to a PNG (the default command)");
    render.add_options(*render_app);
    CLI::App* scenes_app = app.add_subcommand("scenes", "list the built-in scenes, a line on each");
#if BLURCULL_HAVE_VIEW
    ViewCommand view;
    view_app = app.add_subcommand("view", "render a scene interactively in a window (GLFW, OpenGL 4.5)");
    view.add_options(*view_app);
#else
    // Kept as a command so that asking for it says why it is missing.
    view_app = app.add_subcommand("view", "not in this build: needs GLFW (libglfw3-dev) and the GL backend");
    view_app->allow_extras();
#endif

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        // CLI11 names the flag and the accepted range. --help and --version
        // exit 0; usage errors exit 2.
        return app.exit(error) == 0 ? 0 : 2;
    }
    try {
        if (scenes_app->parsed()) return list_scenes();
#if BLURCULL_HAVE_VIEW
        if (view_app->parsed()) return view.run();
#else
        if (view_app->parsed()) {
            throw std::runtime_error("view: this blurcull was built without a window (GLFW from libglfw3-dev, or the "
                                     "GL backend, was not found when it was configured)");
        }
#endif
        return render.run();  // `blurcull` alone renders the default scene
    } catch (const std::exception& error) {
        std::fprintf(stderr, "blurcull: error: %s\n", error.what());
        return 1;
    }
}
