#version 450
// Writes the pushed value, for the statistics test (a graphics pass that pushes constants).
layout(location = 0) flat in int v_instance;
layout(location = 0) out vec4 o_color;
layout(push_constant) uniform ValueConstants { float value; } constants;
void main() { o_color = vec4(constants.value, float(v_instance), 0.0, 1.0); }
