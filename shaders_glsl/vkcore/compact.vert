// Stream compaction, transform-feedback path, stage 1: one point per element, fetched as a
// vertex attribute from the input buffer (or from the previous compaction's xfb buffer).
#version 450
layout(location = 0) in uvec4 a_value;
layout(location = 0) flat out uvec4 v_value;

void main() {
    v_value = a_value;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
