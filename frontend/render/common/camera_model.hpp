// The camera model every backend shares (the contract in docs/reference-renderer.md).
//
// Conventions, all in float:
//  * View space is right-handed, camera at the origin looking down -z. View
//    depth w = -z_view.
//  * Clip space (x, y, w): x = k_x x_view, y = k_y y_view, w = -z_view, with
//    k_y = 1 / tan(yfov / 2), k_x = k_y / aspect, aspect = width / height.
//  * NDC (X, Y) = (x / w, y / w), both in [-1, 1] on screen, +Y up.
//  * Pixel (px, py) covers X in [-1 + 2 px / W, -1 + 2 (px + 1) / W] and
//    Y in [1 - 2 (py + 1) / H, 1 - 2 py / H]: row 0 is the TOP row.
//    Raster coordinates (rx, ry) = (px + ox, py + oy) grow right and DOWN, so a
//    sample offset (ox, oy) in [0,1)^2 is measured from the pixel's top-left.
//  * Thin lens: lens position (u, v) in the unit disk, physical lens point
//    L = (u R, v R, 0) in view space (R = lens_radius), focus depth F. A point
//    with clip coordinates (x, y, w) seen through (u, v) lands at NDC
//    X = (x + u c_x(w)) / w, Y = (y + v c_y(w)) / w, with the signed circle of
//    confusion c_x(w) = a_x + b_x w, a_x = -k_x R, b_x = k_x R / F (same in y
//    with k_y). c(F) = 0: the focus plane is sharp.
//  * Motion: a vertex's VIEW-space position is linear in shutter time t in
//    [0, 1] between view_open * position_open and view_close * position_close,
//    so its clip coordinates are linear in t as well.
//  * Near plane: a surface point is visible only at view depth w >= znear.
#pragma once

#include "scene/scene.hpp"

#include <blurcull/kernel.hpp>
#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace blurcull::frontend {

// A view-space ray. direction.z == -1 always, so the ray parameter t IS the
// view depth of the point origin + t direction (origin.z == 0 on the lens).
struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    float t_near = 0.0f;  // = znear: the first parameter whose point lies at depth >= znear
};

struct CameraModel {
    int width = 1;
    int height = 1;
    float aspect = 1.0f;  // width / height
    float k_x = 1.0f;     // x_clip = k_x x_view
    float k_y = 1.0f;     // y_clip = k_y y_view
    float lens_radius = 0.0f;
    float focus_distance = 1.0f;
    float znear = 0.05f;
    // Circle of confusion c(w) = a + b w per axis.
    float a_x = 0.0f, b_x = 0.0f, a_y = 0.0f, b_y = 0.0f;
    glm::mat4 view_open{1.0f};   // world -> view at shutter open
    glm::mat4 view_close{1.0f};  // world -> view at shutter close

    CameraModel() = default;

    // Throws std::invalid_argument naming the offending camera field or size.
    CameraModel(const Camera& camera, int image_width, int image_height) {
        if (image_width < 1 || image_height < 1) {
            throw std::invalid_argument("camera: image size must be at least 1x1, got " + std::to_string(image_width) +
                                        "x" + std::to_string(image_height));
        }
        if (!(camera.yfov > 0.0f && camera.yfov < 3.14159f)) {
            throw std::invalid_argument("camera: yfov must be in (0, pi) radians, got " + std::to_string(camera.yfov));
        }
        if (!(camera.znear > 0.0f && std::isfinite(camera.znear))) {
            throw std::invalid_argument("camera: znear must be positive, got " + std::to_string(camera.znear));
        }
        if (!(camera.lens_radius >= 0.0f && std::isfinite(camera.lens_radius))) {
            throw std::invalid_argument("camera: lens_radius must be >= 0, got " + std::to_string(camera.lens_radius));
        }
        if (camera.lens_radius > 0.0f && !(camera.focus_distance > 0.0f && std::isfinite(camera.focus_distance))) {
            throw std::invalid_argument("camera: focus_distance must be positive with a lens, got " +
                                        std::to_string(camera.focus_distance));
        }
        for (int column = 0; column < 4; ++column) {
            for (int row = 0; row < 4; ++row) {
                if (!std::isfinite(camera.view_open[column][row]) || !std::isfinite(camera.view_close[column][row])) {
                    throw std::invalid_argument("camera: view matrix has a non-finite entry");
                }
            }
        }
        width = image_width;
        height = image_height;
        aspect = static_cast<float>(image_width) / static_cast<float>(image_height);
        k_y = 1.0f / std::tan(0.5f * camera.yfov);
        k_x = k_y / aspect;
        lens_radius = camera.lens_radius;
        focus_distance = camera.focus_distance;
        znear = camera.znear;
        // With no lens, b = 0 whatever F is (F may be unset then).
        const glm::vec2 coc_x = kernelf::camera_coc(k_x, lens_radius, focus_distance);
        const glm::vec2 coc_y = kernelf::camera_coc(k_y, lens_radius, focus_distance);
        a_x = coc_x.x;
        b_x = coc_x.y;
        a_y = coc_y.x;
        b_y = coc_y.y;
        view_open = camera.view_open;
        view_close = camera.view_close;
    }

    // View-space position of a vertex at one shutter end (0 = open, 1 = close).
    // The caller guarantees vertex < scene.position_open.size().
    glm::vec3 view_position(const Scene& scene, std::size_t vertex, int shutter_end) const {
        if (shutter_end == 0) return glm::vec3(view_open * glm::vec4(scene.position_open[vertex], 1.0f));
        return glm::vec3(view_close * glm::vec4(scene.position_close[vertex], 1.0f));
    }

    // View-space position at shutter time t in [0, 1] (linear between the ends).
    glm::vec3 view_position_at(const Scene& scene, std::size_t vertex, float t) const {
        return glm::mix(view_position(scene, vertex, 0), view_position(scene, vertex, 1), t);
    }

    glm::vec3 clip_xyw(glm::vec3 view) const { return glm::vec3(k_x * view.x, k_y * view.y, -view.z); }

    // Signed circle of confusion (c_x, c_y) at view depth w.
    glm::vec2 coc(float w) const { return glm::vec2(a_x + b_x * w, a_y + b_y * w); }

    // NDC where a clip-space point appears through lens position (u, v).
    glm::vec2 project(glm::vec3 clip, glm::vec2 lens_uv) const {
        glm::vec2 c = coc(clip.z);
        return glm::vec2((clip.x + lens_uv.x * c.x) / clip.z, (clip.y + lens_uv.y * c.y) / clip.z);
    }

    // R / F, 0 with no lens: the CoC slope b of a unit projection scale (lens_ray's).
    float lens_slope() const { return kernelf::camera_coc(1.0f, lens_radius, focus_distance).y; }

    // The ray from lens point (u R, v R, 0) through the in-focus point of the
    // pinhole ray at NDC `ndc`: every point on it projects, through (u, v), to `ndc`.
    Ray lens_ray(glm::vec2 ndc, glm::vec2 lens_uv) const {
        Ray ray;
        ray.origin = glm::vec3(lens_uv.x * lens_radius, lens_uv.y * lens_radius, 0.0f);
        // Pinhole point at depth F is (X F / k_x, Y F / k_y, -F); dividing
        // (that - origin) by F makes direction.z = -1.
        const float slope = lens_slope();
        ray.direction = glm::vec3(ndc.x / k_x - lens_uv.x * slope, ndc.y / k_y - lens_uv.y * slope, -1.0f);
        ray.t_near = znear;
        return ray;
    }

    // The image size in pixels, as the kernel's raster functions take it.
    glm::vec2 image_size() const { return glm::vec2(static_cast<float>(width), static_cast<float>(height)); }

    // Raster coordinates (x right, y down, in pixels) <-> NDC: kernelf::raster_to_ndc / ndc_to_raster.
    glm::vec2 raster_to_ndc(glm::vec2 raster) const { return kernelf::raster_to_ndc(raster, image_size()); }
    glm::vec2 ndc_to_raster(glm::vec2 ndc) const { return kernelf::ndc_to_raster(ndc, image_size()); }

    // NDC of a sample at `offset` in [0,1)^2 from the top-left corner of pixel (px, py):
    // kernelf::pixel_sample_ndc.
    glm::vec2 sample_ndc(int px, int py, glm::vec2 offset) const {
        return kernelf::pixel_sample_ndc(glm::ivec2(px, py), offset, image_size());
    }

    // NDC rectangle covered by pixel (px, py): (X_min, Y_min, X_max, Y_max), kernelf::pixel_rect_ndc.
    glm::vec4 pixel_ndc_bounds(int px, int py) const {
        return kernelf::pixel_rect_ndc(glm::ivec4(px, py, px, py), image_size());
    }
};

}  // namespace blurcull::frontend
