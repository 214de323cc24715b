// One triangle that covers the screen: vertices (-1, -1), (3, -1), (-1, 3) in clip space.
#version 450

void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
