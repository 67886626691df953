#include "scene/builtin_scenes.hpp"

#include "scene/builtin/scenes.hpp"
#include "scene/builtin/secondary_scenes.hpp"
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
    if (name == "forest-10m") return make_forest_10m(options.blur_scale, options.aspect);
    if (name == "mirror-sphere") return make_mirror_sphere(options.blur_scale, options.aspect);
    if (name == "water") return make_water(options.blur_scale, options.aspect);
    if (name == "curved-mirror") return make_curved_mirror(options.blur_scale, options.aspect);
    if (name == "mirror-motion") return make_mirror_motion(options.blur_scale, options.aspect);
    std::string known;
    for (const std::string& candidate : builtin_scene_names()) known += (known.empty() ? "" : ", ") + candidate;
    for (const std::string& candidate : secondary_scene_names()) known += ", " + candidate;
    for (const std::string& candidate : large_scene_names()) known += ", " + candidate;
    throw SceneError("unknown scene '" + name + "' (known: " + known + ")");
}

}  // namespace builtin

namespace {

// Every built-in scene once: the name lists and `blurcull scenes` read this
// table, so a scene added here is listed everywhere (build_scene above makes it).
enum class SceneKind { thesis, secondary, large };

struct SceneEntry {
    const char* name;
    SceneKind kind;  // which of the name lists holds it
    const char* description;
};

constexpr SceneEntry kScenes[] = {
    {"hand", SceneKind::thesis, "a hand before a wall; defocus only (the thesis's Hand; 15k triangles)"},
    {"car", SceneKind::thesis, "a car driving down a street; object motion only (the thesis's Car; 54k triangles)"},
    {"dragonfly", SceneKind::thesis, "a dragonfly on a plant stem; camera motion only (the thesis's Dragonfly; 85k triangles)"},
    {"forest", SceneKind::thesis,
     "a walk through 236 trees; camera motion and defocus (the thesis's FairyForest; 168k triangles); the default"},
    {"mirror-sphere", SceneKind::secondary,
     "a mirror sphere on a chessboard; defocus; reflections with --method dof-secondary (29k triangles)"},
    {"water", SceneKind::secondary,
     "a waved water surface over a pool floor; defocus; refraction with --method dof-secondary (36k triangles)"},
    {"curved-mirror", SceneKind::secondary,
     "a chessboard before flat and convex mirrors (JCST 2013 Fig. 6); defocus; with --method dof-secondary "
     "(12k triangles)"},
    {"mirror-motion", SceneKind::secondary,
     "objects crossing before a flat mirror and behind the camera; object motion and defocus; motion in the mirror "
     "with --method dof-secondary (8k triangles)"},
    {"forest-10m", SceneKind::large,
     "the forest's walk through 15,600 of its trees, out to 390 m; camera motion and defocus; a GPU scale test, "
     "several GB of memory (10000k triangles)"},
};

std::vector<std::string> scene_names(SceneKind kind) {
    std::vector<std::string> names;
    for (const SceneEntry& entry : kScenes)
        if (entry.kind == kind) names.emplace_back(entry.name);
    return names;
}

}  // namespace

std::vector<std::string> builtin_scene_names() { return scene_names(SceneKind::thesis); }

std::vector<std::string> secondary_scene_names() { return scene_names(SceneKind::secondary); }

std::vector<std::string> large_scene_names() { return scene_names(SceneKind::large); }

std::vector<BuiltinSceneInfo> builtin_scene_catalogue() {
    std::vector<BuiltinSceneInfo> catalogue;
    for (SceneKind kind : {SceneKind::thesis, SceneKind::secondary, SceneKind::large})
        for (const SceneEntry& entry : kScenes)
            if (entry.kind == kind) catalogue.push_back({entry.name, entry.description});
    return catalogue;
}

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
