// Wyman & Davis 2006 Sec. 3.1: where a refracted photon meets the diffuse receivers, found in the
// light's render of the first diffuse surface. Included by shared/trace.glsl after receiver_at().
#ifndef DEPTH_SEARCH_GLSL
#define DEPTH_SEARCH_GLSL
// Wyman & Davis 2006 variant: march the ray through the light's render of the first diffuse
// surface (distances from the light) and refine the crossing by bisection.
bool depth_search(uint l, vec3 o, vec3 d, out vec3 hit) {
    vec3 light = caustics.lights[l].position.xyz;
    bool inside;
    float t0 = 0.0, t1 = 0.0, step = 0.02 * max(distance(o, light), 1e-3);
    bool found = false;
    for (int i = 0; i < 256 && !found; ++i) {
        t1 = t0 + step;
        vec3 p = o + t1 * d;
        vec4 r = receiver_at(l, p, inside);
        if (!inside) return false;
        if (r.w > 0.5 && distance(p, light) >= distance(r.xyz, light)) found = true; else t0 = t1;
        step *= 1.05;
    }
    if (!found) return false;
    for (uint i = 0u; i < max(caustics.settings.z, 1u) + 8u; ++i) {
        float tm = 0.5 * (t0 + t1);
        vec3 p = o + tm * d;
        vec4 r = receiver_at(l, p, inside);
        if (r.w > 0.5 && distance(p, light) >= distance(r.xyz, light)) t1 = tm; else t0 = tm;
    }
    hit = o + t1 * d;
    return true;
}
#endif
