// Wyman & Nichols 2009 Sec. 3.1: the refractor's geometry buffers, "normals and depth for
// both front and back refractor surfaces" (the layer is the geometry shader's choice). The
// nearest face of each kind wins the depth test of its own layer.
#version 450
#include "common/frame.glsl"
layout(location = 0) in vec3 g_world;
layout(location = 1) in vec3 g_normal;
layout(location = 2) in float g_thickness;
layout(location = 0) out vec4 o_surface;   // xyz outward normal, w distance to the eye (> 0: a face)
layout(location = 1) out vec2 o_depth;     // x window depth (tested against the background's), y Wyman 2005 d_N

void main() {
    o_surface = vec4(normalize(g_normal), distance(g_world, frame.eye.xyz));
    o_depth = vec2(gl_FragCoord.z, g_thickness);
}
