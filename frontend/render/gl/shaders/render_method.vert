// The interleave, interval and accum methods (frontend/render/gl/gl_sampling_methods.cpp):
// per pass, one quad per listed triangle over the framebuffer cells that may
// hold its samples (tiles for interleave, pixels otherwise), from the
// rectangle the host computed for that pass (method_pass_box, the same boxes
// the CPU renderers test in).
layout(std430, binding = BC_GL_METHOD_BOXES_BINDING) readonly buffer Boxes { MethodBox boxes[]; };

uniform vec2 target_size;  // framebuffer width, height

flat out int g_box;

void main() {
    int b = gl_VertexID / 6, k = gl_VertexID % 6;
    g_box = b;
    ivec4 r = boxes[b].quad;
    bool right = k == 1 || k == 4 || k == 5;
    bool top = k == 2 || k == 3 || k == 5;
    float x = float(right ? r.z + 1 : r.x);
    float y = float(top ? r.y : r.w + 1);
    gl_Position = vec4(bc_raster_to_ndc(vec2(x, y), target_size), 0.5, 1.0);
}
