#version 450
layout(location = 0) flat in int g_layer;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(float(g_layer + 1), 0.5, 0.25, 1.0); }
