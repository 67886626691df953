// How many linear motion segments a rotation needs (--motion-segments auto).
#pragma once

#include "scene/scene.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace blurcull::frontend {

// The chord error `auto` allows, in pixels: 1/16, so a wheel turning 90
// degrees in the shutter is within Monte Carlo noise of true rotation at
// 16 spp (a quarter pixel left a ring 0.12 px inside the rim, 2.1 times
// the noise; docs/reference-renderer.md, "The motion model").
inline constexpr double motion_chord_tolerance_px = 1.0 / 16.0;

// The fewest equal segments K that keep a point at radius `radius_px` pixels
// from the axis, turning by `angle` radians over the shutter, within
// `tolerance_px` of its arc: over a segment it turns by a = angle / K and its
// chord deviates from the arc by at most the sagitta r (1 - cos(a / 2)), so
// K = ceil(angle / (2 acos(1 - tolerance / r))). 1 when r <= tolerance (the
// sagitta never exceeds r) or angle <= 0; the caller caps the result.
inline int motion_segments_for_turn(double angle, double radius_px, double tolerance_px) {
    if (!(angle > 0.0) || !(radius_px > tolerance_px) || !(tolerance_px > 0.0)) return 1;
    const double segment_angle = 2.0 * std::acos(1.0 - tolerance_px / radius_px);
    const double k = std::ceil(angle / segment_angle - 1e-9);  // an exact fit is not one more segment
    return k < 1.0 ? 1 : (k > 1e6 ? 1000000 : static_cast<int>(k));
}

// The value of --motion-segments: "K" (an integer from 1 to
// max_motion_segments) or "auto" (0); throws std::invalid_argument naming the flag.
inline int parse_motion_segments(const std::string& text) {
    if (text == "auto") return 0;
    const std::string bad = "--motion-segments: expected an integer from 1 to " + std::to_string(max_motion_segments) +
                            " or 'auto', got '" + text + "'";
    std::size_t used = 0;
    long k = 0;
    try {
        k = std::stol(text, &used);
    } catch (const std::logic_error&) {
        throw std::invalid_argument(bad);
    }
    if (used != text.size() || k < 1 || k > max_motion_segments) throw std::invalid_argument(bad);
    return static_cast<int>(k);
}

}  // namespace blurcull::frontend
