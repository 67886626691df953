// dof-secondary's GL layers, the draw of passes 2 and 3 (gl_layer_images.cpp):
// vertex k of fan triangle f (gl_VertexID = 3 f + k) at its image point, the
// three image points handed flat to render_layers.frag, which computes the
// depth from them as the host's scan does.
layout(std430, binding = BC_GL_LAYER_PASS_BINDING) readonly buffer Pass { LayerPass pass; };
layout(std430, binding = BC_GL_LAYER_FANS_BINDING) readonly buffer Fans { LayerFan fans[]; };
flat out vec3 corner_a;
flat out vec3 corner_b;
flat out vec3 corner_c;
flat out ivec2 fan_info;  // scene triangle, own

void main() {
    LayerFan fan = fans[gl_VertexID / 3];
    corner_a = fan.a.xyz;
    corner_b = fan.b.xyz;
    corner_c = fan.c.xyz;
    fan_info = fan.info.xy;
    int k = gl_VertexID % 3;
    vec3 p = k == 0 ? fan.a.xyz : (k == 1 ? fan.b.xyz : fan.c.xyz);
    // Image coordinates [0, size] to NDC; window = image coordinates (y up).
    float to_ndc = 2.0 / float(pass.sizes.x);
    gl_Position = vec4(p.x * to_ndc - 1.0, p.y * to_ndc - 1.0, 0.0, 1.0);
}
