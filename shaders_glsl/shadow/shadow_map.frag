// Stores the distance from the light to the nearest occluder.
#version 450
#include "common/frame.glsl"
#include "common/mesh_constants.glsl"
layout(location = 0) in vec3 v_world;
layout(location = 0) out float o_distance;

void main() {
    o_distance = length(v_world - frame.lights[mesh.light].position.xyz);
}
