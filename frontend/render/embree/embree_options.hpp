// How the Embree reference traces its rays: the choices a benchmark compares
// (docs/reference-renderer.md, "Tracing"). The defaults are the fastest that
// give the image of record.
#pragma once

#include <string>

namespace blurcull::frontend {

// The shape in which primary rays go to Embree.
enum class EmbreeTracing {
    single,    // rtcIntersect1, one ray per call
    packet4,   // rtcIntersect4
    packet8,   // rtcIntersect8
    packet16,  // rtcIntersect16 (Embree splits it where the CPU lacks AVX-512)
    stream,    // rtcIntersect1M with RTC_INTERSECT_CONTEXT_FLAG_COHERENT
};

// The BVH builder's quality (RTC_BUILD_QUALITY_*).
enum class EmbreeBuildQuality { low, medium, high };

// What a primary ray that hits a mirror or a dielectric sees
// (docs/secondary-rays.md, "The Embree reference").
enum class EmbreeSecondary {
    bounce,  // one exact bounce of reflection / refraction (render/embree/secondary_rays.hpp)
    none,    // the primary-only image: the environment along the bounced pinhole ray, as the cpu and gl backends
};

struct EmbreeOptions {
    EmbreeTracing tracing = EmbreeTracing::packet16;
    EmbreeBuildQuality build_quality = EmbreeBuildQuality::medium;
    bool robust = true;  // RTC_SCENE_FLAG_ROBUST: watertight triangle tests
    // bounce by default; a scene without mirrors or dielectrics renders the
    // same either way.
    EmbreeSecondary secondary = EmbreeSecondary::bounce;
};

// "single", "packet4", "packet8", "packet16" or "stream".
const char* tracing_name(EmbreeTracing tracing);

// "low", "medium" or "high".
const char* build_quality_name(EmbreeBuildQuality quality);

// "bounce" or "none".
const char* secondary_name(EmbreeSecondary secondary);

// The inverse of secondary_name; throws std::invalid_argument for other names.
EmbreeSecondary parse_embree_secondary(const std::string& name);

// The inverse of tracing_name; throws std::invalid_argument for other names.
EmbreeTracing parse_embree_tracing(const std::string& name);

}  // namespace blurcull::frontend
