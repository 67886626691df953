#include "render/embree/primary_rays.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace blurcull::frontend {
namespace {

void intersect_n(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit4* packet) {
    rtcIntersect4(valid, scene, context, packet);
}
void intersect_n(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit8* packet) {
    rtcIntersect8(valid, scene, context, packet);
}
void intersect_n(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit16* packet) {
    rtcIntersect16(valid, scene, context, packet);
}

void fill_ray(RTCRayHit& query, const PrimaryRay& ray, unsigned id) {
    query.ray.org_x = ray.org_x;
    query.ray.org_y = ray.org_y;
    query.ray.org_z = ray.org_z;
    query.ray.tnear = ray.tnear;
    query.ray.dir_x = ray.dir_x;
    query.ray.dir_y = ray.dir_y;
    query.ray.dir_z = ray.dir_z;
    query.ray.time = ray.time;
    query.ray.tfar = std::numeric_limits<float>::infinity();
    query.ray.mask = 0xFFFFFFFFu;
    query.ray.id = id;
    query.ray.flags = 0;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.primID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

std::uint32_t hit_primitive(unsigned geom_id, unsigned prim_id) {
    return geom_id == RTC_INVALID_GEOMETRY_ID ? no_primitive : prim_id;
}

}  // namespace

const char* tracing_name(EmbreeTracing tracing) {
    switch (tracing) {
        case EmbreeTracing::single: return "single";
        case EmbreeTracing::packet4: return "packet4";
        case EmbreeTracing::packet8: return "packet8";
        case EmbreeTracing::packet16: return "packet16";
        case EmbreeTracing::stream: return "stream";
    }
    return "unknown";
}

const char* build_quality_name(EmbreeBuildQuality quality) {
    switch (quality) {
        case EmbreeBuildQuality::low: return "low";
        case EmbreeBuildQuality::medium: return "medium";
        case EmbreeBuildQuality::high: return "high";
    }
    return "unknown";
}

EmbreeTracing parse_embree_tracing(const std::string& name) {
    for (EmbreeTracing tracing : {EmbreeTracing::single, EmbreeTracing::packet4, EmbreeTracing::packet8,
                                  EmbreeTracing::packet16, EmbreeTracing::stream}) {
        if (name == tracing_name(tracing)) return tracing;
    }
    throw std::invalid_argument("embree tracing: '" + name + "' is not single, packet4, packet8, packet16 or stream");
}

PrimaryRayTracer::PrimaryRayTracer(RTCScene scene, EmbreeTracing tracing) : scene_(scene), tracing_(tracing) {
    rtcInitIntersectContext(&context_.embree);
    // Primary rays of neighbouring samples are coherent; the flag lets the
    // stream shape gather them into packets (the other shapes ignore it).
    if (tracing_ == EmbreeTracing::stream) context_.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
}

void PrimaryRayTracer::trace(const PrimaryRay* rays, std::size_t count, std::uint32_t* prim_ids) {
    switch (tracing_) {
        case EmbreeTracing::single: trace_single(rays, count, prim_ids); return;
        case EmbreeTracing::packet4: trace_packets<RTCRayHit4, 4>(rays, count, prim_ids); return;
        case EmbreeTracing::packet8: trace_packets<RTCRayHit8, 8>(rays, count, prim_ids); return;
        case EmbreeTracing::packet16: trace_packets<RTCRayHit16, 16>(rays, count, prim_ids); return;
        case EmbreeTracing::stream: trace_stream(rays, count, prim_ids); return;
    }
}

void PrimaryRayTracer::trace_single(const PrimaryRay* rays, std::size_t count, std::uint32_t* prim_ids) {
    for (std::size_t i = 0; i < count; ++i) {
        RTCRayHit query;
        fill_ray(query, rays[i], static_cast<unsigned>(i));
        rtcIntersect1(scene_, &context_.embree, &query);
        prim_ids[i] = hit_primitive(query.hit.geomID, query.hit.primID);
    }
}

void PrimaryRayTracer::trace_stream(const PrimaryRay* rays, std::size_t count, std::uint32_t* prim_ids) {
    stream_.resize(count);
    for (std::size_t i = 0; i < count; ++i) fill_ray(stream_[i], rays[i], static_cast<unsigned>(i));
    constexpr std::size_t max_call = std::numeric_limits<unsigned>::max();
    for (std::size_t first = 0; first < count; first += max_call) {
        const auto m = static_cast<unsigned>(std::min(max_call, count - first));
        rtcIntersect1M(scene_, &context_.embree, stream_.data() + first, m, sizeof(RTCRayHit));
    }
    for (std::size_t i = 0; i < count; ++i) prim_ids[i] = hit_primitive(stream_[i].hit.geomID, stream_[i].hit.primID);
}

template <class RayHitN, int N>
void PrimaryRayTracer::trace_packets(const PrimaryRay* rays, std::size_t count, std::uint32_t* prim_ids) {
    alignas(64) RayHitN packet;
    alignas(64) int valid[N];
    for (std::size_t first = 0; first < count; first += N) {
        const int lanes = static_cast<int>(std::min<std::size_t>(N, count - first));
        for (int lane = 0; lane < N; ++lane) {
            // Unused lanes repeat the last ray, masked off.
            const PrimaryRay& ray = rays[first + static_cast<std::size_t>(std::min(lane, lanes - 1))];
            valid[lane] = lane < lanes ? -1 : 0;
            packet.ray.org_x[lane] = ray.org_x;
            packet.ray.org_y[lane] = ray.org_y;
            packet.ray.org_z[lane] = ray.org_z;
            packet.ray.tnear[lane] = ray.tnear;
            packet.ray.dir_x[lane] = ray.dir_x;
            packet.ray.dir_y[lane] = ray.dir_y;
            packet.ray.dir_z[lane] = ray.dir_z;
            packet.ray.time[lane] = ray.time;
            packet.ray.tfar[lane] = std::numeric_limits<float>::infinity();
            packet.ray.mask[lane] = 0xFFFFFFFFu;
            packet.ray.id[lane] = static_cast<unsigned>(first + static_cast<std::size_t>(std::min(lane, lanes - 1)));
            packet.ray.flags[lane] = 0;
            packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.primID[lane] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
        }
        intersect_n(valid, scene_, &context_.embree, &packet);
        for (int lane = 0; lane < lanes; ++lane) {
            prim_ids[first + static_cast<std::size_t>(lane)] = hit_primitive(packet.hit.geomID[lane], packet.hit.primID[lane]);
        }
    }
}

}  // namespace blurcull::frontend
