#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
layout(location = 0) flat in vec4 v_power;
layout(location = 1) flat in vec2 v_centre;
layout(location = 2) flat in float v_radius;
layout(location = 0) out vec4 o_power;   // rgb W, a: photon count

void main() {
    float w;
    if (v_radius < 0.0) {
        w = all(equal(floor(gl_FragCoord.xy), floor(v_centre))) ? 1.0 : 0.0;
    } else {
        float d = distance(gl_FragCoord.xy, v_centre);
        float r = v_radius;
        w = d > r ? 0.0 : (caustics.splat.y > 0.5 ? 1.0 : exp(-0.5 * d * d / (0.25 * r * r)));
    }
    if (w == 0.0) discard;
    o_power = v_power * w;
}
