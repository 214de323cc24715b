// Hierarchical traversal, transform-feedback path, stage 1: one point per entry of the
// previous level's list (a packed entry, hierarchy/entry.glsl, fetched from its xfb buffer).
#version 450
layout(location = 0) in uint a_entry;
layout(location = 0) flat out uint v_entry;

void main() {
    v_entry = a_entry;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
