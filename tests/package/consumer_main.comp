// A user's compute shader: compiled after the installed blurcull_kernel.glsl
// (blurcull_KERNEL_GLSL from find_package), it calls the kernel's public GLSL
// functions, which all start with bc_.
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Samples { vec4 lens_and_time[]; };

void main() {
    uint px = gl_GlobalInvocationID.x;
    PixelSample s = bc_pixel_sample(px, 0u, 0u, 16u, 1u);
    lens_and_time[px] = vec4(s.lens, s.time, bc_epsilon());
}
