// Wyman & Davis 2006 Sec. 3.2.2 step 2: the image-space gather. For every pixel of the view (the
// eye's, the orthographic receiver view, or with LIGHT_SPACE light l's caustic map), the photons
// of the 7x7 neighbourhood (radius 3; radius 0 is the eye-space points of Fig. 4, each pixel its
// own photons) weighted by a Gaussian, each neighbour's ratio E_photons / E_q lit once
// (Eq. 10 with its photons' average incident direction; Eq. 9 re-lit each photon when it was
// drawn; Eq. 11 not at all). Neighbourhoods hit by fewer than `min_photons` photons are
// discarded. With the temporal filter (Sec. 3.2.3) a pixel's photons are the mean of the last
// `frames` frames' (the current one's directions only). Every light is gathered from its own
// photon layers (history_base = light * layers), so light adds up.
//
// Eye space: the area A_q of each neighbour comes from the world positions of the pixels next to
// it (not Eq. 5); Eq. 6 gives its solid angle from the light, w_q = A_q cos_q / d^2, Eq. 8 the
// light's energy E_q = I w_q, Eq. 7 a photon's E = I w_photon = Phi, so the ratio is
// Phi / (I A_q cos_q / d^2); lit with L = I cos_avg / d^2 (Eq. 10) the irradiance it adds is
// Phi cos_avg / (A_q cos_q): I and d cancel, which is what is computed (rgb W/m^2).
// Light space: w_q is the texel's solid angle (Eq. 8 unnecessary); the gathered ratio is stored
// as the power it stands for at texel t, ratio * I * w_t, so that the caustic-map lookup
// (common/caustic_lookup.glsl) turns it into irradiance as it does a splat's power.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "wyman_davis2006/image_space.glsl"
#include "shared/splat_kernel.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 2) uniform sampler2DArray photons;     // rgb power (W), a: photons; history layers
layout(binding = 3) uniform sampler2D directions;       // xyz: sum m * (-d), w: sum m * cos(direct)
layout(binding = 4) uniform sampler2D view_position;
#ifndef LIGHT_SPACE
layout(binding = 5) uniform sampler2D view_normal;
#endif
#ifdef LIGHT_SPACE
layout(binding = 6, rgba32f) uniform writeonly image2DArray gathered;   // light l's own layer
#else
layout(binding = 6, rgba32f) uniform image2DArray gathered;   // shared by the lights: they add
#endif

// The pixel's photons, averaged over the history frames (pairwise for four frames, so that four
// equal frames give exactly one).
vec4 photons_of(ivec2 q) {
    int base = int(constants.history_base);
    if (constants.frames == 4u) {
        vec4 a = texelFetch(photons, ivec3(q, base), 0) + texelFetch(photons, ivec3(q, base + 1), 0);
        vec4 b = texelFetch(photons, ivec3(q, base + 2), 0) + texelFetch(photons, ivec3(q, base + 3), 0);
        return (a + b) * 0.25;
    }
    vec4 s = vec4(0.0);
    for (uint k = 0u; k < constants.frames; ++k) s += texelFetch(photons, ivec3(q, base + int(k)), 0);
    return s / float(max(constants.frames, 1u));
}


void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(view_position, 0);
    if (any(greaterThanEqual(t, size))) return;
    int r = int(constants.radius);
    uint l = constants.light;
    vec3 light = caustics.lights[l].position.xyz;
#ifdef LIGHT_SPACE
    float m = caustics.lights[l].caustic_plane.y;
    float w_t = texel_solid_angle((vec2(t) + 0.5) / m * 2.0 - 1.0, caustics.lights[l].caustic_plane);
#endif
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    float count = 0.0;
    for (int y = -r; y <= r; ++y) {
        for (int x = -r; x <= r; ++x) {
            // The Gaussian of the splats (sigma = r / 2, nothing beyond r), over the whole window.
            float w = r == 0 ? 1.0 : splat_kernel(length(vec2(x, y)), float(r));
            weights += w;
            ivec2 q = t + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            vec4 ph = photons_of(q);
            count += ph.a;
            if (ph.a == 0.0 || w == 0.0) continue;
            vec4 surface = texelFetch(view_position, q, 0);
            if (surface.w < 0.5) continue;
#ifdef LIGHT_SPACE
            vec3 n = normal_from_positions(view_position, q, light);
#else
            vec3 n = texelFetch(view_normal, q, 0).xyz;
#endif
            float f = 1.0;
            if (constants.lighting == 10u) {
                // Eq. 10: one lighting computation with the pixel's average incident direction.
                vec4 d = texelFetch(directions, q, 0);
                vec4 now = texelFetch(photons, ivec3(q, int(constants.slot)), 0);
                float mass = (now.r + now.g + now.b) / 3.0;
                if (mass > 0.0 && dot(d.xyz, d.xyz) > 0.0) f = photon_lighting(dot(n, normalize(d.xyz)), d.w / mass);
            }
#ifdef LIGHT_SPACE
            float w_q = texel_solid_angle((vec2(q) + 0.5) / m * 2.0 - 1.0, caustics.lights[l].caustic_plane);
            sum += w * ph.rgb * (w_t / w_q) * f;
#else
            float area = pixel_area(view_position, q, surface.xyz);
            if (area > 0.0) sum += w * ph.rgb / area * f;
#endif
        }
    }
    // Step 2 (5): too few photons in the neighbourhood: noise, discarded.
    vec3 result = count < float(constants.min_photons) ? vec3(0.0) : sum / weights;
#ifndef LIGHT_SPACE
    // Each light is gathered from its own photons (the three-photon rule and Eq. 10's average
    // direction are per light); the lights after the first add to the view's caustic.
    if (constants.light > 0u) {
        vec4 before = imageLoad(gathered, ivec3(t, 0));
        result += before.rgb;
        count += before.a;
    }
#endif
    imageStore(gathered, ivec3(t, 0), vec4(result, count));
}
