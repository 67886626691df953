// Start of each pass when static triangles were drawn per group
// (render_static_group.frag): one invocation per sample writes the static
// winner's id and its depth key (the largest, kept in group_depths), so the
// moving triangles are then drawn on top with the GREATER depth test, as
// after a per-pass static draw.
GROUP_SAMPLE_BUFFERS
layout(std430, binding = BC_GL_GROUP_IDS_BINDING) readonly buffer GroupIds { uint group_ids[]; };
layout(std430, binding = BC_GL_GROUP_DEPTHS_BINDING) readonly buffer GroupDepths { uint group_depths[]; };

uniform uint group_base;  // the group's first sample
layout(location = 0) out uint out_id;

void main() {
    uint j = pass_base + uint(gl_SampleID);
    if (j >= spp) discard;
    uvec2 pixel = fragment_cell(gl_FragCoord.xy, image_size);
    uint slot = (pixel.y * uint(image_size.x) + pixel.x) * group_samples + (j - group_base);
    uint id = group_ids[slot];
    if (id == 0xffffffffu) discard;
    gl_FragDepth = uintBitsToFloat(group_depths[slot]);
    gl_SampleMask[0] = 1 << gl_SampleID;
    out_id = id;
}
