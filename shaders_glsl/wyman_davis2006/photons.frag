// One photon added to the pixel it lands in (Sec. 3.2.2 step 1): rgb its power (W; with Eq. 9
// already re-lit from its own direction), a: one photon; and its incident direction, weighted
// by its power, with the cosine of the light's direct direction (for Eq. 10). A photon the
// pixel's surface does not hold (hidden from the eye, or on another surface) adds nothing.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "wyman_davis2006/image_space.glsl"
layout(binding = 5) uniform sampler2D view_position;   // xyz world, w = 1 on a surface
#ifndef LIGHT_SPACE
layout(binding = 6) uniform sampler2D view_normal;
#endif
layout(location = 0) flat in vec3 v_position;
layout(location = 1) flat in vec3 v_direction;
layout(location = 2) flat in vec3 v_power;
layout(location = 0) out vec4 o_photons;      // rgb power (W), a: photons
layout(location = 1) out vec4 o_direction;    // xyz: sum of m * (-direction), w: sum of m * cos(direct); m = mean power

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    vec4 surface = texelFetch(view_position, t, 0);
    vec3 light = caustics.lights[constants.light].position.xyz;
#ifdef LIGHT_SPACE
    // Photons land on the first diffuse surface the light sees: the texel's receiver.
    if (surface.w < 0.5) discard;
    vec3 n = normal_from_positions(view_position, t, light);
#else
    if (!on_surface(surface, v_position)) discard;
    vec3 n = texelFetch(view_normal, t, 0).xyz;
#endif
    float cos_direct = direct_cosine(constants.light, surface.xyz, n);
    float cos_photon = dot(n, -v_direction);
    vec3 power = v_power;
    if (constants.lighting == 9u) power *= photon_lighting(cos_photon, cos_direct);   // Eq. 9
    float m = (power.r + power.g + power.b) / 3.0;
    o_photons = vec4(power, 1.0);
    o_direction = vec4(-v_direction * m, cos_direct * m);
}
