// The refractor's back faces from the light (Wyman 2005, first pass, light's view): outward
// normal and distance from the light.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "common/mesh_constants.glsl"
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in float v_thickness;
layout(location = 0) out vec4 o_back;
void main() { o_back = vec4(normalize(v_normal), distance(v_world, caustics.lights[mesh.light].position.xyz)); }
