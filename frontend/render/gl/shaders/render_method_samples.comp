// The interval method, before each pass: every pixel's sample of stratum
// pass_index (interval_sample, NDC as CameraModel::sample_ndc rounds it), so
// the fragment shader, which runs once per triangle and pixel, only reads it.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = BC_GL_PASS_SAMPLES_BINDING) writeonly buffer PassSamples { vec4 pass_ndc_lens[]; };
layout(std430, binding = BC_GL_PASS_TIMES_BINDING) writeonly buffer PassTimes { float pass_time[]; };

uniform uint pass_index;

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= uint(image_size.x) || pixel.y >= uint(image_size.y)) return;
    uint p = pixel.y * uint(image_size.x) + pixel.x;
    PixelSample s = bc_interval_sample(pixel.x, pixel.y, pass_index, spp, seed);
    pass_ndc_lens[p] = vec4(sample_ndc(pixel.x, pixel.y, s.offset), s.lens);
    pass_time[p] = s.time;
}
