#version 450
// One full-screen triangle per instance; the instance picks the layer.
layout(location = 0) flat out int v_instance;
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
    v_instance = gl_InstanceIndex;
}
