// What a light emits towards a direction: the spot light's cone and projected texture (Wyman &
// Nichols 2009's elephant under a textured spotlight, Fig. 12), one function for the eye's direct
// light (common/lighting.glsl) and every photon (shared/trace_surface.glsl), and the twin of
// `SpotProjector::emission` (crates/caustics/src/scene/spot_projector.rs), which the CPU
// reference samples the same way: the same axes, uv, and bilinear clamp-to-edge filtering of
// the resampled texture (the linear sampler), at its single mip level.
// Needs binding SPOT_BINDING (sampler2DArray: one layer per light, white where it has none).
#ifndef SPOT_TEXTURE_GLSL
#define SPOT_TEXTURE_GLSL
#include "common/frame.glsl"

layout(binding = SPOT_BINDING) uniform sampler2DArray spot_textures;

// The RGB factor on light l's intensity towards unit direction d (from the light): 1 for a
// point light; for a spot light 0 outside its cone and its texture's colour at
// uv = (d.u, d.v) / (d.axis) / 2 + 1/2 inside it (1 without a texture).
vec3 spot_emission(uint l, vec3 d) {
    Light light = frame.lights[l];
    if (light.position.w < 0.5) return vec3(1.0);
    float c = dot(d, light.spot.xyz);
    if (c < light.spot.w) return vec3(0.0);
    if (light.intensity.w < 0.5) return vec3(1.0);
    vec2 uv = vec2(dot(d, light.spot_u.xyz), dot(d, light.spot_v.xyz)) / c * 0.5 + 0.5;
    return textureLod(spot_textures, vec3(uv, float(l)), 0.0).rgb;
}
#endif
