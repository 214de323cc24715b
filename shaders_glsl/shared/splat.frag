#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "shared/splat_kernel.glsl"
layout(location = 0) flat in vec4 v_power;
layout(location = 1) flat in vec2 v_centre;
layout(location = 2) flat in float v_radius;
layout(location = 0) out vec4 o_power;   // rgb W, a: photon count

void main() {
    float w = splat_weight(v_centre, v_radius, gl_FragCoord.xy);
    if (w == 0.0) discard;
    o_power = v_power * w;
}
