// Wyman & Nichols 2009 Sec. 3.1, step 4: "render a full screen quad" (a triangle covering the
// screen, wyman_nichols2009/full_screen.vert), once per pixel (wyman_nichols2009/deferred_refraction.glsl).
#version 450
#include "wyman_nichols2009/deferred_refraction.glsl"
layout(location = 0) out vec4 o_radiance;

void main() {
    o_radiance = vec4(deferred_radiance(ivec2(gl_FragCoord.xy)), 1.0);
}
