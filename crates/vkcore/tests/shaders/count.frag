#version 450
layout(location = 0) out vec4 o_count;
void main() { o_count = vec4(1.0, 0.0, 0.0, 1.0); }
