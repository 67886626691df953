// dof-secondary's primary resolve on the GPU (gl_secondary_resolve.cpp):
// resolve_primary (render/secondary/secondary_rays.cpp) over the winning
// triangle of every sample, on the same text: the kernel's sampler and
// pixel_sample_ndc, the camera's thin-lens ray, resolve_shared.h's sample
// hit (fp64) and spawned rays, optics_shared.h. A sample on a diffuse
// triangle gets its colour, a miss the background, a reflector sample
// black and its rays, written in sample order (the host's ray order: the
// clustering's k-means start depends on it) by a scan of the per-sample ray
// counts over chunks of BC_RESOLVE_CHUNK samples. Each step a dispatch:
// BC_RESOLVE_STEP_SAMPLES  per sample: its colour and how many rays;
// BC_RESOLVE_STEP_CHUNKS   per chunk: the sum of its counts;
// BC_RESOLVE_STEP_SCAN     one invocation: each chunk's first ray (an
//                          exclusive scan), the total after them;
// BC_RESOLVE_STEP_RAYS     per chunk: its samples' rays, from its first
//                          (the hit computed again: cheaper than keeping it).
// The rays go where the clustering reads them: position and direction in
// Points (their w the keys: triangle, pixel << 4 | lens part), sample, time
// and weight beside them.
layout(local_size_x = 64) in;
layout(std430, binding = BC_GL_RESOLVE_IDS_BINDING) readonly buffer SampleIds { uint sample_id[]; };
// Per vertex: view position at open, at close, world position at open, at close.
layout(std430, binding = BC_GL_RESOLVE_VERTICES_BINDING) readonly buffer Vertices { vec4 vertex[]; };
// Per triangle 8 words: its vertices, material kind, then colour (rgb) and index of refraction (float bits).
layout(std430, binding = BC_GL_RESOLVE_TRIANGLES_BINDING) readonly buffer Triangles { uint triangle_word[]; };
layout(std430, binding = BC_GL_RESOLVE_FRAME_BINDING) readonly buffer Frame { double frame[]; };  // two inverse views
layout(std430, binding = BC_GL_RESOLVE_COLOURS_BINDING) writeonly buffer Colours { vec4 colour_out[]; };
// Per sample its ray count; per chunk their sum, then its first ray; then the total and the reflector samples.
layout(std430, binding = BC_GL_RESOLVE_COUNTS_BINDING) buffer Counts { uint count_word[]; };
layout(std430, binding = BC_GL_RESOLVE_RAYS_BINDING) writeonly buffer RayInfo { uvec4 ray_info[]; };
layout(std430, binding = BC_GL_CLUSTER_POINTS_BINDING) writeonly buffer PointWords { uvec4 point_word[]; };

#define BC_RESOLVE_STEP_SAMPLES 0
#define BC_RESOLVE_STEP_CHUNKS 1
#define BC_RESOLVE_STEP_SCAN 2
#define BC_RESOLVE_STEP_RAYS 3
#define BC_RESOLVE_CHUNK 256u
#define BC_RESOLVE_NO_HIT 0xFFFFFFFFu
#define BC_RESOLVE_DIFFUSE 0u
#define BC_RESOLVE_MIRROR 1u

uniform int step;
uniform uint width;
uniform uint height;
uniform uint spp;
uniform int sampler;
uniform uint seed;
uniform int lens_parts;
uniform float k_x;
uniform float k_y;
uniform float lens_radius;
uniform float lens_slope;  // CameraModel::lens_slope()
uniform vec3 background;

uint item() { return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x; }
uint samples() { return width * height * spp; }
uint chunks() { return (samples() + BC_RESOLVE_CHUNK - 1u) / BC_RESOLVE_CHUNK; }

dmat4 frame_matrix(uint at) {
    return dmat4(frame[at], frame[at + 1u], frame[at + 2u], frame[at + 3u], frame[at + 4u], frame[at + 5u],
                 frame[at + 6u], frame[at + 7u], frame[at + 8u], frame[at + 9u], frame[at + 10u], frame[at + 11u],
                 frame[at + 12u], frame[at + 13u], frame[at + 14u], frame[at + 15u]);
}

// A reflector sample: its pattern sample, hit and the rays it spawns.
struct ReflectorSample {
    PixelSample s;
    SampleHit hit;
    SpawnedRays rays;
};

ReflectorSample reflector_sample(uint k, uint id, uint kind) {
    uint pixel = k / spp, j = k % spp;
    uint px = pixel % width, py = pixel / width;
    ReflectorSample r;
    r.s = bc_sampler_sample(bc_sampler_setup(sampler, px, py, spp, seed), j);
    vec2 ndc = bc_pixel_sample_ndc(ivec2(px, py), r.s.offset, vec2(float(width), float(height)));
    precise float dx = ndc.x / k_x - r.s.lens.x * lens_slope;
    precise float dy = ndc.y / k_y - r.s.lens.y * lens_slope;
    precise float ox = r.s.lens.x * lens_radius;
    precise float oy = r.s.lens.y * lens_radius;
    dvec3 o = dvec3(vec3(ox, oy, 0.0));
    uint at = 8u * id;
    dvec3 v[3], w[3];
    for (uint c = 0u; c < 3u; ++c) {
        uint vertex_at = 4u * triangle_word[at + c];
        v[c] = dvec3(bc_optics_mix(vertex[vertex_at].xyz, vertex[vertex_at + 1u].xyz, r.s.time));
        w[c] = dvec3(bc_optics_mix(vertex[vertex_at + 2u].xyz, vertex[vertex_at + 3u].xyz, r.s.time));
    }
    dvec3 lens_world = bc_lens_world(frame_matrix(0u), frame_matrix(16u), o, double(r.s.time));
    r.hit = bc_sample_hit(v[0], v[1], v[2], w[0], w[1], w[2], o, dvec3(vec3(dx, dy, -1.0)), lens_world);
    r.rays = bc_spawn_rays(kind == BC_RESOLVE_MIRROR, uintBitsToFloat(triangle_word[at + 7u]), r.hit.incident,
                           r.hit.normal);
    if (!r.hit.valid) r.rays.count = 0;  // a degenerate hit sees the environment straight on: no ray
    return r;
}

void write_ray(uint ray, uint k, uint id, ReflectorSample r, vec3 direction, float weight) {
    uint pixel = k / spp;
    point_word[2u * ray] = uvec4(floatBitsToUint(r.hit.point), id);
    point_word[2u * ray + 1u] =
        uvec4(floatBitsToUint(direction), (pixel << BC_GROUP_PART_BITS) | bc_lens_part(r.s.lens, lens_parts));
    ray_info[ray] = uvec4(k, floatBitsToUint(r.s.time), floatBitsToUint(weight), 0u);
}

void main() {
    uint i = item();
    uint n = samples();
    if (step == BC_RESOLVE_STEP_SAMPLES) {
        if (i >= n) return;
        uint id = sample_id[i];
        uint count = 0u;
        vec3 colour = vec3(0.0);
        if (id == BC_RESOLVE_NO_HIT) {
            colour = background;
        } else {
            uint kind = triangle_word[8u * id + 3u];
            if (kind == BC_RESOLVE_DIFFUSE) {
                colour = uintBitsToFloat(uvec3(triangle_word[8u * id + 4u], triangle_word[8u * id + 5u],
                                               triangle_word[8u * id + 6u]));
            } else {
                atomicAdd(count_word[n + 2u * chunks() + 1u], 1u);  // a reflector sample
                count = uint(reflector_sample(i, id, kind).rays.count);
            }
        }
        colour_out[i] = vec4(colour, 0.0);
        count_word[i] = count;
        return;
    }
    uint chunk_count = chunks();
    if (step == BC_RESOLVE_STEP_CHUNKS) {
        if (i >= chunk_count) return;
        uint sum = 0u;
        for (uint k = i * BC_RESOLVE_CHUNK; k < min(n, (i + 1u) * BC_RESOLVE_CHUNK); ++k) sum += count_word[k];
        count_word[n + i] = sum;
        return;
    }
    if (step == BC_RESOLVE_STEP_SCAN) {
        if (i != 0u) return;
        uint total = 0u;
        for (uint c = 0u; c < chunk_count; ++c) {
            count_word[n + chunk_count + c] = total;
            total += count_word[n + c];
        }
        count_word[n + 2u * chunk_count] = total;
        return;
    }
    if (i >= chunk_count) return;
    uint ray = count_word[n + chunk_count + i];
    for (uint k = i * BC_RESOLVE_CHUNK; k < min(n, (i + 1u) * BC_RESOLVE_CHUNK); ++k) {
        if (count_word[k] == 0u) continue;
        uint id = sample_id[k];
        ReflectorSample r = reflector_sample(k, id, triangle_word[8u * id + 3u]);
        if (r.rays.count > 0) write_ray(ray++, k, id, r, r.rays.direction0, r.rays.weight0);
        if (r.rays.count > 1) write_ray(ray++, k, id, r, r.rays.direction1, r.rays.weight1);
    }
}
