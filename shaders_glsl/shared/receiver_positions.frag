// Shah et al. step 1: the receivers' world positions as the light sees them (the positions
// texture that rayGeo searches); w = 1 where a receiver was hit.
#version 450
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in float v_thickness;
layout(location = 0) out vec4 o_position;
void main() { o_position = vec4(v_world, 1.0); }
