// Shah et al.'s caustics mapping, the iterative image-space ray/receiver intersection (the
// tutorial's rayGeo with num_iter steps). Included by shared/trace.glsl after receiver_at().
#ifndef RAY_GEO_GLSL
#define RAY_GEO_GLSL
// Shah et al.'s rayGeo: iterative image-space estimate of where o + t d meets the receivers,
// starting from t = 1 as the tutorial does.
bool ray_geo(uint l, vec3 o, vec3 d, out vec3 hit) {
    float t = 1.0;
    bool inside;
    vec4 r = vec4(0.0);
    for (uint i = 0u; i < max(caustics.settings.z, 1u); ++i) {
        r = receiver_at(l, o + t * d, inside);
        if (!inside || r.w < 0.5) return false;
        t = distance(r.xyz, o);
    }
    hit = o + t * d;
    return true;
}
#endif
