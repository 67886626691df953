// Before each pass: the pass's four samples of every pixel (sampler_setup
// once per pixel, then sampler_sample, in the settings' sampler), so the fragment shaders, which run
// once per triangle and pixel, only read them. Also, with stride the group's
// size, the samples of a group of passes for render_static_group.frag.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = BC_GL_PASS_SAMPLES_BINDING) writeonly buffer PassSamples { vec4 pass_ndc_lens[]; };
layout(std430, binding = BC_GL_PASS_TIMES_BINDING) writeonly buffer PassTimes { float pass_time[]; };

uniform int sampler;  // BC_PATTERN_* (RenderSettings::sampler)
uniform uint stride;  // samples per pixel in the buffers: 4, or a group's size

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= uint(image_size.x) || pixel.y >= uint(image_size.y)) return;
    uint slot = (pixel.y * uint(image_size.x) + pixel.x) * stride;
    SamplerSetup setup = bc_sampler_setup(sampler, pixel.x, pixel.y, spp, seed);
    for (uint k = 0u; k < stride; ++k) {
        uint j = pass_base + k;
        if (j >= spp) break;
        vec4 ndc_lens;
        float time;
        pattern_sample(setup, pixel, j, ndc_lens, time);
        pass_ndc_lens[slot + k] = ndc_lens;
        pass_time[slot + k] = time;
    }
}
