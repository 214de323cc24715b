// Wyman 2005 image-space refraction, first pass: the refractor's back faces (front faces
// culled), nearest one per pixel: outward normal and distance from the eye.
#version 450
#include "common/frame.glsl"
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in float v_thickness;
layout(location = 0) out vec4 o_back;   // xyz outward normal of the back face, w distance to the eye

void main() {
    o_back = vec4(normalize(v_normal), distance(v_world, frame.eye.xyz));
}
