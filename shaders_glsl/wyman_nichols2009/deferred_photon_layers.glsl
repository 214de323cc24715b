// Photons through several refractors (Wyman & Nichols 2009 Sec. 3.1.1 applied to photons, Sec. 5
// and Fig. 13): each specular object has its own light-space geometry buffers (layer k: front 0,
// back 1), at bindings B + 3k (position), B + 1 + 3k (normal), B + 2 + 3k (material),
// k < REFRACTORS, B = LAYER_BINDING (8 in deferred_photons.frag; after the traversal's own
// bindings in the adaptive kernels). Deferred photons and adaptive caustic maps both call
// through_further_refractors on the photon their first surface traced.
// The photon leaves the first object it meets (traced by shared/trace.glsl from the buffers of
// all objects, exactly as the forward photon buffer traces it); then, as long as another object
// lies on its way to the receiver:
// 1. the next object is found in image space, as the receiver is (Wyman & Davis 2006's depth
//    search): the ray is marched through each other object's buffers, a point being inside the
//    object where its distance to the light lies between that object's front and back distances
//    at the point's light-space texel; the first crossing is refined by bisection;
// 2. it refracts there into the object (the front buffer's interpolated normal, the object's
//    index of refraction), leaves it by Wyman 2005's two-interface estimate through that object's
//    back faces (Eq. 2, and the back-face refinement of shared/trace_surface.glsl), with the
//    Fresnel transmittances and the object's colour;
// 3. it lands where the receiver search (find_receiver) puts it.
// Approximations, stated as the paper states its own ("the refraction angle is incorrect at
// interfaces beyond the 2nd"): the back faces, d_V and d_N an object's buffers hold are those
// seen along the light's rays, not along the photon's refracted direction; the first object's
// exit point is taken as the point of the photon's landing ray nearest its entry point (the
// ray itself, its direction and its power are the trace's); photons the first object loses
// (total internal reflection, no receiver) stay lost; at most REFRACTORS - 1 further objects
// are crossed, each object once after another. Further objects are refractors only: a mirror's
// geometry buffers hold no back faces (light_geometry.geom routes refractors' alone), so the
// march never finds one inside and the photon passes it (the first object may be a mirror).
#ifndef DEFERRED_PHOTON_LAYERS_GLSL
#define DEFERRED_PHOTON_LAYERS_GLSL
#ifndef REFRACTORS
#define REFRACTORS 1
#endif
#ifndef LAYER_BINDING
#define LAYER_BINDING 8
#endif
#if REFRACTORS > 1
#define LAYER_BINDINGS(k)                                                                   \
    layout(binding = LAYER_BINDING + 3 * k) uniform sampler2DArray layer##k##_position;   \
    layout(binding = LAYER_BINDING + 1 + 3 * k) uniform sampler2DArray layer##k##_normal; \
    layout(binding = LAYER_BINDING + 2 + 3 * k) uniform sampler2DArray layer##k##_material;
LAYER_BINDINGS(0)
LAYER_BINDINGS(1)
#if REFRACTORS > 2
LAYER_BINDINGS(2)
#endif
#if REFRACTORS > 3
LAYER_BINDINGS(3)
#endif

// What: 0 position, 1 normal, 2 material; face: 0 front, 1 back.
#define LAYER_FETCH(k)                                                                  \
    if (layer == k) {                                                                   \
        if (what == 0) return texelFetch(layer##k##_position, ivec3(t, face), 0);       \
        if (what == 1) return texelFetch(layer##k##_normal, ivec3(t, face), 0);         \
        return texelFetch(layer##k##_material, ivec3(t, face), 0);                      \
    }
vec4 layer_texel(int layer, int what, ivec2 t, int face) {
    LAYER_FETCH(0)
    LAYER_FETCH(1)
#if REFRACTORS > 2
    LAYER_FETCH(2)
#endif
#if REFRACTORS > 3
    LAYER_FETCH(3)
#endif
    return vec4(0.0);
}

// The light-space texel of point p (photon frustum), and whether it is inside the buffers
// (all of one side: the photon buffer's, or the adaptive geometry buffers').
bool layer_texel_of(uint l, vec3 p, out ivec2 t) {
    bool inside;
    vec2 ndc = project_ndc(caustics.lights[l].photon_view_proj, p, inside);
    int g = textureSize(layer0_position, 0).x;
    t = clamp(ivec2(floor((ndc * 0.5 + 0.5) * float(g))), ivec2(0), ivec2(g - 1));
    return inside;
}

// Whether p is inside object `layer` as its buffers see it from light l (step 1).
bool inside_layer(uint l, int layer, vec3 p) {
    ivec2 t;
    if (!layer_texel_of(l, p, t)) return false;
    vec4 front = layer_texel(layer, 0, t, 0);
    vec4 back = layer_texel(layer, 0, t, 1);
    if (layer_texel(layer, 1, t, 0).w < 0.5 || back.w <= 0.0) return false;
    vec3 light = caustics.lights[l].position.xyz;
    float d = distance(p, light);
    return d >= distance(front.xyz, light) && d <= back.w;
}

// The first crossing into object `layer` on o + s d, 0 < s < s_max (step 1), or -1.
#define LAYER_MARCH_STEPS 96
float enter_layer(uint l, int layer, vec3 o, vec3 d, float s_max) {
    float s0 = 0.0;
    float step = s_max / float(LAYER_MARCH_STEPS);
    for (int i = 1; i <= LAYER_MARCH_STEPS; ++i) {
        float s1 = step * float(i);
        if (inside_layer(l, layer, o + s1 * d)) {
            for (int k = 0; k < 12; ++k) {
                float sm = 0.5 * (s0 + s1);
                if (inside_layer(l, layer, o + sm * d)) s1 = sm; else s0 = sm;
            }
            return s1;
        }
        s0 = s1;
    }
    return -1.0;
}

// Step 2 and 3 for a photon of power `power` entering object `layer` at e along d.
Photon through_layer(uint l, int layer, vec3 e, vec3 d, vec3 power) {
    vec3 light = caustics.lights[l].position.xyz;
    ivec2 t;
    layer_texel_of(l, e, t);
    vec4 front = layer_texel(layer, 0, t, 0);
    vec4 m = layer_texel(layer, 2, t, 0);
    vec3 n1 = normalize(layer_texel(layer, 1, t, 0).xyz);
    if (dot(n1, d) > 0.0) n1 = -n1;
    float ior = m.a;
    float cos_i = dot(-d, n1);
    vec3 t1 = refract(d, n1, 1.0 / ior);
    float d_v = max(layer_texel(layer, 0, t, 1).w - distance(e, light), 0.0);
    vec3 p2 = e + wyman2005_distance(cos_i, t1, n1, d_v, front.w) * t1;
    for (uint k = 0u; k < uint(caustics.splat.z); ++k) {        // as shared/trace_surface.glsl
        ivec2 tk;
        layer_texel_of(l, p2, tk);
        float bk = layer_texel(layer, 0, tk, 1).w;
        if (bk <= 0.0) break;
        p2 = e + distance(e, light + normalize(p2 - light) * bk) * t1;
    }
    ivec2 t2i;
    layer_texel_of(l, p2, t2i);
    vec3 dir;
    if (!exit_refractor(t1, n1, layer_texel(layer, 1, t2i, 1).xyz, cos_i, ior, m.rgb, power, dir)) {
        return lost_photon(power, PHOTON_LOST_TIR);
    }
    vec3 hit;
    if (!find_receiver(l, p2, dir, hit)) return lost_photon(power, PHOTON_LOST_NO_RECEIVER);
    return landed_photon(hit, dir, power);
}

// The photon `ph` that left object `object` (entered at p1) through the other objects on its way
// to the receiver.
Photon through_further_refractors(uint l, Photon ph, vec3 p1, uint object) {
    vec3 entry = p1;
    for (int hop = 1; hop < REFRACTORS && ph.position.w > 0.5; ++hop) {
        vec3 d = ph.direction.xyz;
        vec3 hit = ph.position.xyz;
        vec3 o = hit + d * dot(entry - hit, d);   // on the landing ray, inside the object just left
        float nearest = distance(o, hit);
        int next = -1;
        ivec2 t_entry;
        layer_texel_of(l, entry, t_entry);
        for (int k = 0; k < REFRACTORS; ++k) {
            // A layer holds one object: skip the one the photon just left (its own layer
            // covers its entry point's texel).
            if (uint(layer_texel(k, 1, t_entry, 0).w) == object + 1u) continue;
            float s = enter_layer(l, k, o, d, nearest);
            if (s <= 0.0) continue;
            ivec2 te;
            layer_texel_of(l, o + s * d, te);
            if (uint(layer_texel(k, 1, te, 0).w) == object + 1u) continue;
            nearest = s;
            next = k;
        }
        if (next < 0) break;
        entry = o + nearest * d;
        ivec2 te;
        layer_texel_of(l, entry, te);
        object = uint(layer_texel(next, 1, te, 0).w) - 1u;
        ph = through_layer(l, next, entry, d, ph.power.rgb);
    }
    return ph;
}
#endif
#endif
