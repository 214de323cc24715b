// Wyman 2005 two-sided image-space refraction, and the reflection lookup, for a refractive or
// reflective surface point seen from the eye. Shared by the forward path (eye/front_faces.frag,
// in the front faces' fragment shader) and Wyman & Nichols 2009's deferred pass
// (wyman_nichols2009/deferred_refraction.comp, once per pixel from the geometry buffers).
//
// Refractive: refract at the front face, estimate the distance to the back face from d_V
// (front-to-back distance along the view ray, from the back-face buffer) and d_N (per-vertex
// thickness along the inward normal), weighted by the ratio of refraction to incidence angles;
// refract again with the back-face normal found by projecting that point; then look the
// exiting ray up in the background image with an iterative image-space search (as Shah et al.
// intersect refracted rays with receivers). Fresnel (exact dielectric) splits light between
// the refracted and reflected lookups. Reflective: one reflection lookup, tinted by the
// specular colour.
//
// The includer declares, before including this: common/frame.glsl, common/mesh_constants.glsl
// (the surface's material) and the samplers `background_radiance`, `background_position` (the
// diffuse surfaces' world positions, w = 1 where hit) and `back_faces` (outward normal and
// distance from the eye of the nearest back face).
#ifndef IMAGE_SPACE_REFRACTION_GLSL
#define IMAGE_SPACE_REFRACTION_GLSL

#define SEARCH_ITERATIONS 8
#include "common/fresnel.glsl"

vec2 project_uv(vec3 p, out bool inside) {
    vec4 c = frame.view_proj * vec4(p, 1.0);
    vec2 uv = c.xy / c.w * 0.5 + 0.5;
    inside = c.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
    return uv;
}

// Radiance arriving along the ray o + t d from the diffuse background.
vec3 background_lookup(vec3 o, vec3 d) {
    bool inside;
    vec2 uv = project_uv(o + d, inside);
    float t = 1.0;
    vec4 hit = textureLod(background_position, uv, 0.0);
    if (inside && hit.w > 0.5) t = distance(hit.xyz, o);
    for (int i = 0; i < SEARCH_ITERATIONS; ++i) {
        uv = project_uv(o + t * d, inside);
        if (!inside) return frame.background.rgb;
        hit = textureLod(background_position, uv, 0.0);
        if (hit.w < 0.5) return frame.background.rgb;
        t = distance(hit.xyz, o);
    }
    // The search converges to the surface the ray meets where the background image can see it;
    // where it cannot (hidden or behind the camera), the last estimate is the best there is.
    return textureLod(background_radiance, uv, 0.0).rgb;
}

// Radiance through the refractor for one IOR, entering at p1 (normal n1 facing the eye, d_n
// the thickness there); also returns the front-face Fresnel term.
vec3 refract_through(vec3 p1, vec3 v, vec3 n1, float ior, float d_n, out float f1) {
    float cos_i = dot(-v, n1);
    f1 = dielectric_fresnel(cos_i, 1.0 / ior);
    vec3 t1 = refract(v, n1, 1.0 / ior);
    bool inside;
    vec2 uv = project_uv(p1, inside);
    vec4 back = textureLod(back_faces, uv, 0.0);
    float d_v = max(back.w - distance(p1, frame.eye.xyz), 0.0);
    float theta_i = acos(clamp(cos_i, -1.0, 1.0));
    float theta_t = acos(clamp(dot(-t1, n1), -1.0, 1.0));
    float ratio = theta_i > 1e-4 ? theta_t / theta_i : 1.0;
    float d = ratio * d_v + (1.0 - ratio) * d_n;   // Wyman 2005, Eq. 2
    vec3 p2 = p1 + d * t1;
    vec2 uv2 = project_uv(p2, inside);
    vec3 n2 = textureLod(back_faces, uv2, 0.0).xyz;
    if (dot(n2, n2) < 0.5) n2 = -n1;               // missed the back-face buffer: assume a slab
    n2 = normalize(n2);
    vec3 t2 = refract(t1, -n2, ior);
    float f2 = 1.0;
    if (dot(t2, t2) < 0.5) {
        t2 = reflect(t1, -n2);                     // total internal reflection: keep going inside, once
    } else {
        f2 = 1.0 - dielectric_fresnel(dot(-t1, -n2), ior);
    }
    return f2 * background_lookup(p2, normalize(t2));
}

// Radiance leaving the surface point p of `mesh` towards the eye: p on the eye ray, `normal`
// its interpolated (outward) normal, d_n its Wyman 2005 thickness.
vec3 specular_radiance(vec3 p, vec3 normal, float d_n) {
    vec3 n = normalize(normal);
    vec3 v = normalize(p - frame.eye.xyz);
    if (dot(n, v) > 0.0) n = -n;
    vec3 colour;
    if (mesh.material == MATERIAL_REFLECTIVE) {
        colour = mesh.colour.rgb * background_lookup(p, reflect(v, n));
    } else {
        vec3 reflected = background_lookup(p, reflect(v, n));
        vec3 through;
        float f1;
        if (mesh.ior.r == mesh.ior.g && mesh.ior.g == mesh.ior.b) {
            through = refract_through(p, v, n, mesh.ior.r, d_n, f1);
            colour = (1.0 - f1) * through * mesh.colour.rgb + f1 * reflected;
        } else {
            // Dispersion: one path per channel.
            float fr, fg, fb;
            vec3 r = refract_through(p, v, n, mesh.ior.r, d_n, fr);
            vec3 g = refract_through(p, v, n, mesh.ior.g, d_n, fg);
            vec3 b = refract_through(p, v, n, mesh.ior.b, d_n, fb);
            vec3 f = vec3(fr, fg, fb);
            colour = (1.0 - f) * vec3(r.r, g.g, b.b) * mesh.colour.rgb + f * reflected;
        }
    }
    return colour;
}

#endif
