// Primary rays through Embree 3 in the shape that traces them fastest: one
// ray per call, SIMD packets of 4, 8 or 16, or a coherent stream
// (docs/reference-renderer.md, "Tracing"). Every shape finds the same nearest
// hit for the same ray; the Embree backend picks one with EmbreeOptions.
#pragma once

#include "render/embree/embree_options.hpp"

#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace blurcull::frontend {

// One primary ray: origin, direction, segment start and shutter time; the
// segment ends at infinity.
struct PrimaryRay {
    float org_x, org_y, org_z, tnear;
    float dir_x, dir_y, dir_z, time;
};

// The primitive id that a ray which hits nothing gets from trace_primary_rays.
constexpr std::uint32_t no_primitive = RTC_INVALID_GEOMETRY_ID;

// The intersect context the tracer passes to Embree: Embree's own, then a
// pointer a geometry's filter function reads (the Embree backend's alpha
// mask: the row's samples). Each ray's id is its index in the trace call.
struct TraceContext {
    RTCIntersectContext embree;
    const void* user = nullptr;
};

// Traces rays[0 .. count) in `scene` (one geometry) in the given shape and
// writes each ray's nearest primitive id, or no_primitive, to prim_ids.
// Packets take consecutive rays, so rays of one pixel share a packet. Not
// thread-safe per object; one per thread (it keeps its scratch buffers).
class PrimaryRayTracer {
public:
    PrimaryRayTracer(RTCScene scene, EmbreeTracing tracing);

    // Traces `count` rays; prim_ids must hold count entries.
    void trace(const PrimaryRay* rays, std::size_t count, std::uint32_t* prim_ids);

    // What a filter function finds in TraceContext::user during trace().
    void set_filter_data(const void* user) { context_.user = user; }

private:
    template <class RayHitN, int N>
    void trace_packets(const PrimaryRay* rays, std::size_t count, std::uint32_t* prim_ids);
    void trace_single(const PrimaryRay* rays, std::size_t count, std::uint32_t* prim_ids);
    void trace_stream(const PrimaryRay* rays, std::size_t count, std::uint32_t* prim_ids);

    RTCScene scene_;
    EmbreeTracing tracing_;
    TraceContext context_;
    std::vector<RTCRayHit> stream_;  // the stream shape's ray/hit records
};

}  // namespace blurcull::frontend
