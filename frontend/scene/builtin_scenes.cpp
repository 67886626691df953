#include "scene/builtin_scenes.hpp"

#include "scene/builtin/scenes.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_checks.hpp"

namespace blurcull::frontend {

namespace builtin {

Scene build_scene(const std::string& name, const SceneOptions& options) {
    const std::string problem = blur_and_aspect_problem(options.blur_scale, options.aspect);
    if (!problem.empty()) throw SceneError("scene '" + name + "': " + problem);
    if (name == "hand") return make_hand(options.blur_scale, options.aspect);
    if (name == "car") return make_car(options.blur_scale, options.aspect);
    if (name == "dragonfly") return make_dragonfly(options.blur_scale, options.aspect);
    if (name == "forest") return make_forest(options.blur_scale, options.aspect);
    std::string known;
    for (const std::string& candidate : builtin_scene_names()) known += (known.empty() ? "" : ", ") + candidate;
    throw SceneError("unknown scene '" + name + "' (known: " + known + ")");
}

}  // namespace builtin

std::vector<std::string> builtin_scene_names() { return {"hand", "car", "dragonfly", "forest"}; }

Scene make_builtin_scene(const std::string& name, const SceneOptions& options) {
    Scene scene = builtin::build_scene(name, options);
    validate_scene(scene);
    scene.validated = true;
    return scene;
}

Scene make_mostly_static(const Scene& source, int moving_every) {
    if (moving_every < 1) throw SceneError("mostly static scene: moving_every must be >= 1");
    Scene scene = source;  // keeps source.validated: the result is valid when the source is
    scene.position_open.clear();
    scene.position_close.clear();
    scene.texcoord.clear();
    scene.vertex_color.clear();
    scene.normal.clear();
    scene.camera.lens_radius = 0.0f;
    scene.camera.view_close = scene.camera.view_open;
    // The world point the still camera sees where the moving one saw p at
    // close; none when the camera does not move (an inverse times the same
    // matrix would move every point by its rounding).
    const bool camera_moves = source.camera.view_open != source.camera.view_close;
    const glm::mat4 close_motion =
        camera_moves ? glm::inverse(source.camera.view_open) * source.camera.view_close : glm::mat4(1.0f);
    for (std::size_t t = 0; t < source.triangles.size(); ++t) {
        const bool moves = t % static_cast<std::size_t>(moving_every) == 0;
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t v = source.triangles[t][i];
            scene.position_open.push_back(source.position_open[v]);
            const glm::vec3 close = camera_moves ? glm::vec3(close_motion * glm::vec4(source.position_close[v], 1.0f))
                                                 : source.position_close[v];
            scene.position_close.push_back(moves ? close : source.position_open[v]);
            // The surface attributes follow their vertex.
            if (!source.texcoord.empty()) scene.texcoord.push_back(source.texcoord[v]);
            if (!source.vertex_color.empty()) scene.vertex_color.push_back(source.vertex_color[v]);
            if (!source.normal.empty()) scene.normal.push_back(source.normal[v]);
            scene.triangles[t][i] = static_cast<std::uint32_t>(3 * t + static_cast<std::size_t>(i));
        }
    }
    return scene;
}

}  // namespace blurcull::frontend
