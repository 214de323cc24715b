// Wyman & Nichols 2009 Sec. 3.1, step 4: the deferred render pass, once per pixel: where the
// refractor's nearest front face is visible (in front of the background), refract through it
// from the geometry buffers (eye/image_space_refraction.glsl, the same computation as the
// forward path's fragment shader); elsewhere copy the background. Sec. 3.1.1: with several
// refractors, one such pass per refractor, back to front, each reading the previous pass's
// result as its "background".
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
#include "common/frame.glsl"
#include "common/mesh_constants.glsl"
layout(binding = 1) uniform sampler2D background_radiance;  // the background, or the previous layer's result
layout(binding = 2) uniform sampler2D background_position;  // the diffuse surfaces: world position, w = hit
layout(binding = 3) uniform sampler2D background_normal;    // w: the diffuse surfaces' window depth
layout(binding = 4) uniform sampler2D front_faces;          // outward normal, distance (0: none)
layout(binding = 5) uniform sampler2D back_faces;           // outward normal, distance
layout(binding = 6) uniform sampler2D front_depth;          // window depth, Wyman 2005 d_N
layout(binding = 7, rgba32f) uniform writeonly image2D result;
#include "eye/image_space_refraction.glsl"

// The world point at distance `dist` from the eye on the ray through pixel p's centre.
vec3 on_eye_ray(ivec2 p, float dist) {
    vec2 ndc = (vec2(p) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
    vec4 w = frame.inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(w.xyz / w.w - frame.eye.xyz);
    return frame.eye.xyz + dist * dir;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(result)))) return;
    vec4 front = texelFetch(front_faces, p, 0);
    vec2 depth = texelFetch(front_depth, p, 0).xy;
    bool background_hit = texelFetch(background_position, p, 0).w > 0.5;
    float background_depth = background_hit ? texelFetch(background_normal, p, 0).w : 1.0;
    // The forward path's depth test (less or equal) of the front faces against the background.
    bool visible = front.w > 0.0 && depth.x <= background_depth;
    vec3 colour = visible ? specular_radiance(on_eye_ray(p, front.w), front.xyz, depth.y)
                          : texelFetch(background_radiance, p, 0).rgb;
    imageStore(result, p, vec4(colour, 1.0));
}
