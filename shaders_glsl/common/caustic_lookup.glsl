// Caustic irradiance at a receiver point from the caustic maps (needs CAUSTICS_BINDING,
// CAUSTIC_MAP_BINDING and RECEIVER_POSITIONS_BINDING). A caustic-map texel holds the power
// (W) of the photons splatted into it; the texel covers solid angle w from the light, i.e.
// area A = w d^2 / cos(theta) on the receiver (Wyman & Davis 2006, Eq. 5-8), so
// E = power cos(theta) / (w d^2). A point receives a texel's light only if it is the first
// diffuse surface the light sees there (the receiver-positions map), like a shadow map.
#ifndef CAUSTIC_LOOKUP_GLSL
#define CAUSTIC_LOOKUP_GLSL
#include "common/caustics.glsl"
layout(binding = CAUSTIC_MAP_BINDING) uniform sampler2DArray caustic_map;
layout(binding = RECEIVER_POSITIONS_BINDING) uniform sampler2DArray receiver_positions;

// Power of base-resolution texel `texel` of light `l`. With the multi-resolution map, Eq. 3 of
// Wyman 2008: C = sum_i C_i / 4^i, level i holding its splats in the corner (M/2^i)^2 of layer
// 4l + i. A coarse level is read as a mipmap level is, bilinearly at the base texel's centre
// (clamped to the level's corner): each level-i texel's power spreads over the base texels
// around it with tent weights that sum to 4^i, so the sum conserves power, and the coarse
// levels add no 2^i-texel blocks to the caustic.
vec3 caustic_level(ivec2 texel, int layer, uint i, float size) {
    float scale = float(1u << i);
    // The corner holds ceil(M / 2^i) texels a side: with M not a multiple of 2^i the last one
    // straddles the map's edge and still holds power.
    int last = int(ceil(size / scale)) - 1;
    vec2 u = (vec2(texel) + 0.5) / scale - 0.5;
    ivec2 t0 = ivec2(floor(u));
    vec2 f = u - vec2(t0);
    ivec2 a = clamp(t0, ivec2(0), ivec2(last));
    ivec2 b = clamp(t0 + 1, ivec2(0), ivec2(last));
    vec3 c00 = texelFetch(caustic_map, ivec3(a.x, a.y, layer), 0).rgb;
    vec3 c10 = texelFetch(caustic_map, ivec3(b.x, a.y, layer), 0).rgb;
    vec3 c01 = texelFetch(caustic_map, ivec3(a.x, b.y, layer), 0).rgb;
    vec3 c11 = texelFetch(caustic_map, ivec3(b.x, b.y, layer), 0).rgb;
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

vec3 caustic_power(ivec2 texel, uint l, float size) {
    if (caustics.splat.w != SPLAT_VARYING_MULTIRES) {
        return texelFetch(caustic_map, ivec3(texel, int(l)), 0).rgb;
    }
    vec3 c = texelFetch(caustic_map, ivec3(texel, int(l * MULTIRES_LEVELS)), 0).rgb;
    for (uint i = 1u; i < MULTIRES_LEVELS; ++i) {
        int layer = int(l * MULTIRES_LEVELS + i);
        c += caustic_level(texel, layer, i, size) / float(1u << (2u * i));
    }
    return c;
}

vec3 caustic_irradiance(vec3 p, vec3 n) {
    vec3 e = vec3(0.0);
    for (uint l = 0u; l < caustics.settings.x; ++l) {
        CausticLight cl = caustics.lights[l];
        vec2 ndc;
        if (!caustic_map_ndc(cl, p, ndc)) continue;
        if (any(greaterThan(abs(ndc), vec2(1.0)))) continue;
        ivec2 texel = ivec2(clamp((ndc * 0.5 + 0.5) * cl.caustic_plane.y, vec2(0.0), vec2(cl.caustic_plane.y - 1.0)));
        vec4 first = texelFetch(receiver_positions, ivec3(texel, int(l)), 0);
        vec3 to_light = cl.position.xyz - p;
        float d = length(to_light);
        if (first.w < 0.5 || distance(first.xyz, p) > 0.02 * d) continue;
        float cos_theta = max(dot(n, to_light / d), 0.0);
        vec2 centre = (vec2(texel) + 0.5) / cl.caustic_plane.y * 2.0 - 1.0;
        float w = texel_solid_angle(centre, cl.caustic_plane);
        e += caustic_power(texel, l, cl.caustic_plane.y) * cos_theta / (w * d * d);
    }
    return e;
}
#endif
