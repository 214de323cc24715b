// Wyman & Davis 2006 Sec. 3.2 (Fig. 4) and Sec. 3.2.2 step 1: every photon of the photon buffer
// drawn as a one-pixel point into a view, where the fragment shader adds it to the view's
// photon buffer (power, count, incident direction). The view is the eye's (or the orthographic
// receiver view) or, with LIGHT_SPACE, light l's caustic map (the light-space gather).
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "wyman_davis2006/image_space.glsl"
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D photon_direction;
layout(binding = 4) uniform sampler2D photon_power;
layout(location = 0) flat out vec3 v_position;
layout(location = 1) flat out vec3 v_direction;
layout(location = 2) flat out vec3 v_power;

void main() {
    uint n = constants.photon_side;
    ivec2 texel = ivec2(gl_VertexIndex % n, gl_VertexIndex / n);
    vec4 pos = texelFetch(photon_position, texel, 0);
    gl_PointSize = 1.0;
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);     // culled unless it is a photon that landed
    v_position = pos.xyz;
    v_direction = texelFetch(photon_direction, texel, 0).xyz;
    v_power = texelFetch(photon_power, texel, 0).rgb;
    if (pos.w < 0.5) return;
#ifdef LIGHT_SPACE
    vec2 ndc;
    if (!caustic_map_ndc(caustics.lights[constants.light], pos.xyz, ndc)) return;
#else
    vec4 clip = constants.view_proj * vec4(pos.xyz, 1.0);
    if (clip.w <= 0.0) return;
    vec2 ndc = clip.xy / clip.w;
#endif
    gl_Position = vec4(ndc, 0.5, 1.0);
}
