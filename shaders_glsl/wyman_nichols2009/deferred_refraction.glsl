// Wyman & Nichols 2009 Sec. 3.1, step 4: the deferred render pass, once per pixel: where the
// refractor's nearest front face is visible (in front of the background), refract through it
// from the geometry buffers (eye/image_space_refraction.glsl, the same computation as the
// forward path's fragment shader); elsewhere copy the background. Sec. 3.1.1: with several
// refractors, one such pass per refractor, back to front, each reading the previous pass's
// result as its "background".
#ifndef DEFERRED_REFRACTION_GLSL
#define DEFERRED_REFRACTION_GLSL
#include "common/frame.glsl"
#include "common/mesh_constants.glsl"
layout(binding = 1) uniform sampler2D background_radiance;  // the background, or the previous layer's result
layout(binding = 2) uniform sampler2D background_position;  // the diffuse surfaces: world position, w = hit
layout(binding = 3) uniform sampler2D background_normal;    // w: the diffuse surfaces' window depth
layout(binding = 4) uniform sampler2D front_faces;          // outward normal, distance (0: none)
layout(binding = 5) uniform sampler2D back_faces;           // outward normal, distance
layout(binding = 6) uniform sampler2D front_depth;          // window depth, Wyman 2005 d_N
#include "eye/image_space_refraction.glsl"

// The world point at distance `dist` from the eye on the ray through pixel p's centre.
vec3 on_eye_ray(ivec2 p, float dist) {
    vec2 ndc = (vec2(p) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
    vec4 w = frame.inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(w.xyz / w.w - frame.eye.xyz);
    return frame.eye.xyz + dist * dir;
}

// The deferred pass's colour at pixel p.
vec3 deferred_radiance(ivec2 p) {
    vec4 front = texelFetch(front_faces, p, 0);
    // No refractor here: copy the background (reading no more than the forward composite does).
    if (front.w <= 0.0) return texelFetch(background_radiance, p, 0).rgb;
    vec2 depth = texelFetch(front_depth, p, 0).xy;
    bool background_hit = texelFetch(background_position, p, 0).w > 0.5;
    float background_depth = background_hit ? texelFetch(background_normal, p, 0).w : 1.0;
    // The forward path's depth test (less or equal) of the front faces against the background.
    if (depth.x > background_depth) return texelFetch(background_radiance, p, 0).rgb;
    return specular_radiance(on_eye_ray(p, front.w), front.xyz, depth.y);
}

#endif
