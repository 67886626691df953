// A scene as every backend sees it: triangles whose vertices have a world
// position at shutter open and at shutter close (linear motion in between), a
// thin-lens camera whose view may also differ between the two, flat materials.
//
// Validity is checked once, where a scene is made: make_builtin_scene,
// load_gltf_scene and load_scene return scenes that passed validate_scene
// (scene_checks.hpp) and say so in Scene::validated; make_mostly_static keeps
// a valid scene valid. The backends call require_valid_scene, which trusts a
// scene so marked and checks any other (one built by hand).
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

// Scene::environment's values (plain macros: render/common/optics_shared.h,
// which GLSL shares, names them too).
#define BC_ENVIRONMENT_NONE 0  // rays that leave the scene get the background colour
#define BC_ENVIRONMENT_SKY 1   // the procedural sky of render/common/optics_shared.h

namespace blurcull::frontend {

// How light leaves a surface. Diffuse is the flat shading of shading.hpp; a
// mirror reflects perfectly, a dielectric reflects and refracts with Fresnel
// weights (render/common/optics_shared.h). Backends without secondary rays
// shade a mirror or dielectric with the environment seen along the bounced
// direction (docs/reference-renderer.md, "Materials and environment").
enum class MaterialKind : std::uint8_t { diffuse, mirror, dielectric };

// How a texture coordinate outside [0, 1] is folded back (glTF sampler wrapS/wrapT).
enum class TextureWrap : std::uint8_t { repeat, clamp, mirror };

// A decoded texture: texels RGBA8 as stored in the file (colour channels
// sRGB-encoded, alpha linear), packed R | G << 8 | B << 16 | A << 24, row 0
// first (texture coordinate v = 0 is the top of the image, glTF's convention).
struct Texture {
    int width = 0;
    int height = 0;
    std::vector<std::uint32_t> texels;  // width * height
    TextureWrap wrap_s = TextureWrap::repeat;
    TextureWrap wrap_t = TextureWrap::repeat;
    std::string name;
};

// A material's use of a texture: Scene::textures[texture] (-1: none) at
// texture coordinates transform * (u, v, 1) (KHR_texture_transform; identity without it).
struct TextureRef {
    int texture = -1;
    glm::mat3 transform{1.0f};
};

// glTF alphaMode. BLEND is stochastic transparency: a covered sample stays
// covered with probability alpha (surface_shared.h, bc_blend_kept), then the
// depth rule applies as for opaque surfaces.
enum class AlphaMode : std::uint8_t { opaque, mask, blend };

struct Material {
    glm::vec3 base_color{0.8f, 0.8f, 0.8f};
    std::string name;
    MaterialKind kind = MaterialKind::diffuse;
    float ior = 1.5f;  // index of refraction of a dielectric (> 0); air is 1
    // The surface attributes of render/common/surface_shading.hpp (the
    // contract in docs/reference-renderer.md, "Shading"); the defaults shade
    // as the flat colour of shading.hpp.
    float base_alpha = 1.0f;            // baseColorFactor's alpha
    TextureRef base_color_texture{};    // times base_color (and base_alpha)
    AlphaMode alpha_mode = AlphaMode::opaque;
    float alpha_cutoff = 0.5f;          // mask: a sample is covered only where alpha >= cutoff
    glm::vec3 emissive{0.0f};           // added to the shaded colour (x KHR_materials_emissive_strength)
    TextureRef emissive_texture{};      // times emissive
    bool unlit = false;                 // KHR_materials_unlit: the base colour, neither lit nor emissive
};

// A light besides the scene's directional one (Scene::light_direction,
// light_color): KHR_lights_punctual's point and spot lights and further
// directional lights, in world space at shutter open (render/common/
// surface_shared.h, bc_punctual_light: the falloffs).
enum class LightType : std::uint8_t { directional, point, spot };  // BC_LIGHT_*

struct PunctualLight {
    LightType type = LightType::point;
    glm::vec3 position{0.0f};     // point, spot
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // spot: where it shines; directional: towards the light
    glm::vec3 colour{1.0f};       // colour x intensity (>= 0)
    float range = 0.0f;           // > 0: the distance where the light ends; 0: unlimited
    float cos_inner = 1.0f;       // spot: cos innerConeAngle
    float cos_outer = 0.70710678f;// spot: cos outerConeAngle (default pi / 4)
};

// The most lights Scene::lights holds; the loader keeps the first ones, warned.
inline constexpr std::size_t max_punctual_lights = 16;

// Right-handed view space, camera at the origin looking down -z (OpenGL).
// view depth w = -z_view. Projection: x_clip = (k_y / aspect) x_view,
// y_clip = k_y y_view, w_clip = -z_view, with k_y = 1 / tan(yfov / 2).
struct Camera {
    glm::mat4 view_open{1.0f};   // world -> view at shutter open
    glm::mat4 view_close{1.0f};  // world -> view at shutter close
    // Motion segments (Scene::position_at): world -> view at the interior
    // times k / K, k = 1 .. K - 1; empty: interpolated between the ends.
    std::vector<glm::mat4> view_at;
    float yfov = 0.8f;           // radians, full vertical field of view
    float znear = 0.05f;         // near plane (view depth)
    float lens_radius = 0.0f;    // thin-lens aperture radius, world units
    float focus_distance = 10.0f;// view depth that is in focus
};

// The most motion segments a scene may carry (--motion-segments K <= this;
// `auto` clamps to it with a warning): each segment is one more copy of the
// vertices and, on the CPU, of the moving triangles' setup.
inline constexpr int max_motion_segments = 64;

struct Scene {
    std::string name;
    // Per vertex; the two arrays have the same length.
    std::vector<glm::vec3> position_open;
    std::vector<glm::vec3> position_close;
    // Motion segments (--motion-segments K > 1; docs/reference-renderer.md,
    // "The motion model"): the world positions at the interior shutter times
    // k / K, k = 1 .. K - 1, position_at[k - 1] per vertex like position_open.
    // Empty (K = 1, every built-in scene): linear motion from open to close.
    std::vector<std::vector<glm::vec3>> position_at;
    // position_at's K was chosen by --motion-segments auto (the default), not
    // asked for: a renderer that carries one linear motion per triangle may
    // then drop the interior times with a warning (drop_motion_segments)
    // instead of refusing the scene.
    bool motion_segments_auto = false;
    // Optional per-vertex surface attributes: each empty, or one per vertex.
    // texcoord: TEXCOORD_0; vertex_color: COLOR_0 (linear RGBA; (1, 1, 1, 1)
    // where a mesh has none); normal: world-space shading normal at shutter
    // open ((0, 0, 0) where a mesh has none: such triangles shade flat).
    std::vector<glm::vec2> texcoord;
    std::vector<glm::vec4> vertex_color;
    std::vector<glm::vec3> normal;
    std::vector<Texture> textures;
    // Per triangle.
    std::vector<glm::uvec3> triangles;
    std::vector<std::uint32_t> triangle_material;
    std::vector<Material> materials;

    Camera camera;
    glm::vec3 light_direction{0.3f, 0.8f, 0.5f};  // towards the light, world space
    glm::vec3 light_color{1.0f, 1.0f, 1.0f};      // scales the diffuse term (KHR_lights_punctual colour x intensity)
    // glTF's other lights (at most max_punctual_lights); the built-in scenes have none.
    std::vector<PunctualLight> lights;
    glm::vec3 background{0.02f, 0.02f, 0.03f};
    // What a ray that leaves the scene sees: BC_ENVIRONMENT_NONE (the
    // background colour) or BC_ENVIRONMENT_SKY (render/common/optics_shared.h).
    int environment = 0;
    // Where the scene's animation clock ends (scene/load_scene.hpp,
    // frame_shutter_interval): for glTF the last keyframe time, in seconds,
    // of the animation used (0 without one); a built-in scene's linear
    // motion never ends (infinity).
    double animation_end = std::numeric_limits<double>::infinity();

    // True when the maker that returned this scene validated it, so the
    // backends need not check it again. Code that edits such a scene in a
    // way that could break validity (new vertices, triangles, materials, or
    // values from outside) clears it, and the backend checks it once more.
    bool validated = false;
};

}  // namespace blurcull::frontend
