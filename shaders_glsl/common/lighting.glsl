// Direct light from point and spot lights: irradiance I cos(theta) / r^2 (inverse-square law)
// and shadow-map visibility. Needs bindings SHADOW_BINDING (sampler2DArray of distances) and
// SPOT_BINDING (sampler2DArray of projected textures, common/spot_texture.glsl).
#ifndef LIGHTING_GLSL
#define LIGHTING_GLSL
#include "common/frame.glsl"
#include "common/spot_texture.glsl"

layout(binding = SHADOW_BINDING) uniform sampler2DArray shadow_map;

// Irradiance at `p` with normal `n` from light `l`, ignoring occluders (E0's term), W/m^2.
vec3 unoccluded_irradiance(uint l, vec3 p, vec3 n) {
    Light light = frame.lights[l];
    vec3 to_light = light.position.xyz - p;
    float r2 = max(dot(to_light, to_light), 1e-12);
    vec3 w = to_light * inversesqrt(r2);
    float cos_theta = max(dot(n, w), 0.0);
    return light.intensity.rgb * spot_emission(l, -w) * cos_theta / r2;
}

// The cube face whose 90-degree frustum contains direction d (+X -X +Y -Y +Z -Z).
int cube_face(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x > 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y > 0.0 ? 2 : 3;
    return d.z > 0.0 ? 4 : 5;
}

// 1 where `p` sees light `l`, 0 in its shadow. The bias grows with the angle between the
// surface and the light, since one shadow-map texel spans more depth at grazing angles.
float shadow_visibility(uint l, vec3 p, vec3 n) {
    Light light = frame.lights[l];
    vec3 d = p - light.position.xyz;
    float r = length(d);
    int face = cube_face(d);
    vec4 clip = light.face_view_proj[face] * vec4(p, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    float stored = texture(shadow_map, vec3(uv, light.shadow.w + float(face))).r;
    float cos_t = clamp(abs(dot(n, d / max(r, 1e-6))), 0.05, 1.0);
    float tan_t = sqrt(1.0 - cos_t * cos_t) / cos_t;
    float bias = r * light.shadow.z * (1.5 + 1.5 * tan_t) + 1e-3;
    return r <= stored + bias ? 1.0 : 0.0;
}

// Irradiance reaching `p`, shadows included.
vec3 direct_irradiance(vec3 p, vec3 n) {
    vec3 e = vec3(0.0);
    for (uint l = 0u; l < frame.counts.x; ++l) {
        vec3 e0 = unoccluded_irradiance(l, p, n);
        if (any(greaterThan(e0, vec3(0.0)))) e += e0 * shadow_visibility(l, p, n);
    }
    return e;
}
#endif
