// After each pass: add the pass's samples (in sample order) to each pixel's
// running sum of colours, as the CPU backend sums them, and in .w the count
// of samples that hit a triangle (the coverage); optionally keep every
// sample's triangle id. The compute pipeline (ids_in_buffer = 1) has every
// sample's id in SampleIds already: one dispatch sums all spp of them, in
// the same order.
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = BC_GL_PASS_IDS_UNIT) uniform usampler2DMS pass_ids;
layout(std430, binding = BC_GL_COLOURS_BINDING) readonly buffer Colours { vec4 colours[]; };  // background last
layout(std430, binding = BC_GL_SUMS_BINDING) buffer Sums { vec4 sums[]; };
layout(std430, binding = BC_GL_SAMPLE_IDS_BINDING) buffer SampleIds { uint sample_ids[]; };

uniform uint background;  // index of the background colour in colours
uniform int keep_ids;
uniform int ids_in_buffer;  // 1: read the ids from SampleIds, all spp samples (pass_base 0)

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    uint width = uint(image_size.x), height = uint(image_size.y);
    if (pixel.x >= width || pixel.y >= height) return;
    uint index = pixel.y * width + pixel.x;
    vec3 sum = pass_base == 0u ? vec3(0.0) : sums[index].xyz;
    float covered = pass_base == 0u ? 0.0 : sums[index].w;
    uint samples_here = ids_in_buffer != 0 ? spp : 4u;
    for (uint k = 0u; k < samples_here; ++k) {
        uint j = pass_base + k;
        if (j >= spp) break;
        uint id = ids_in_buffer != 0 ? sample_ids[index * spp + j]
                                     : texelFetch(pass_ids, ivec2(pixel.x, height - 1u - pixel.y), int(k)).r;
        precise vec3 next = sum + colours[id == 0xffffffffu ? background : id].xyz;
        sum = next;
        if (id != 0xffffffffu) covered += 1.0;
        if (keep_ids != 0 && ids_in_buffer == 0) sample_ids[index * spp + j] = id;
    }
    sums[index] = vec4(sum, covered);
}
