// Tracing one photon from the light through a point of a specular surface of a given material:
// the code every photon of every technique is traced with. The photon buffer and the vertex
// photons take the material from their mesh's push constants (shared/trace.glsl); adaptive
// caustic maps from the light-space geometry buffers they create photons from by deferred
// shading (Wyman & Nichols 2009 Sec. 3.2, wyman_nichols2009/adaptive.glsl), so that dense and
// adaptive photons are the same computation.
// Needs bindings: 0 frame, 1 caustics, 2 light-space back faces, 3 receiver positions, 4 the
// spot lights' projected textures (common/spot_texture.glsl).
#ifndef TRACE_SURFACE_GLSL
#define TRACE_SURFACE_GLSL
#define CAUSTICS_BINDING 1
#define SPOT_BINDING 4
#include "common/caustics.glsl"
#include "common/spot_texture.glsl"
#include "common/materials.glsl"
#include "common/fresnel.glsl"
layout(binding = 2) uniform sampler2D light_back_faces;
layout(binding = 3) uniform sampler2DArray receiver_positions;

// Why a photon carries nothing (direction.w), so the photon-buffer dump explains losses.
#define PHOTON_LOST_TIR 1.0
#define PHOTON_LOST_NO_RECEIVER 2.0

struct Photon {
    vec4 position;   // xyz where it lands on the first diffuse surface; w = 1 if it lands
    vec4 direction;  // xyz incident direction at the receiver; w: 0, or why it was lost
    vec4 power;      // rgb W (also kept for lost photons, to account for them)
};

// A photon lost on its way (`why`: PHOTON_LOST_*), its power kept to account for it.
Photon lost_photon(vec3 power, float why) {
    return Photon(vec4(0.0), vec4(0.0, 0.0, 0.0, why), vec4(power, 0.0));
}

// A photon that landed at `hit`, arriving along `d`.
Photon landed_photon(vec3 hit, vec3 d, vec3 power) {
    return Photon(vec4(hit, 1.0), vec4(d, 0.0), vec4(power, 1.0));
}

vec2 project_ndc(mat4 m, vec3 p, out bool inside) {
    vec4 c = m * vec4(p, 1.0);
    vec2 ndc = c.xy / c.w;
    inside = c.w > 0.0 && all(lessThanEqual(abs(ndc), vec2(1.0)));
    return ndc;
}

vec4 receiver_at(uint l, vec3 p, out bool inside) {
    vec2 ndc;
    inside = caustic_map_ndc(caustics.lights[l], p, ndc) && all(lessThanEqual(abs(ndc), vec2(1.0)));
    return texture(receiver_positions, vec3(ndc * 0.5 + 0.5, float(l)));
}

#include "shah2007/ray_geo.glsl"
#include "wyman_davis2006/depth_search.glsl"

bool find_receiver(uint l, vec3 o, vec3 d, out vec3 hit) {
    if ((caustics.settings.w & CAUSTIC_WD_DEPTH_SEARCH) != 0u) return depth_search(l, o, d, hit);
    return ray_geo(l, o, d, hit);
}

// The material a photon meets at the specular surface.
struct SpecularMaterial {
    uint kind;       // MATERIAL_REFRACTIVE or MATERIAL_REFLECTIVE
    vec3 colour;     // transmission or specular colour
    float ior;       // the mean of the rgb index of refraction (refractive)
};

// Wyman 2005, Eq. 2: how far the refracted ray t1 (entering at cos_i through normal n1) runs
// to the exit point, d_V (along the light's ray) and d_N (along the normal) weighted by the
// ratio of the refraction angle to the incidence angle.
float wyman2005_distance(float cos_i, vec3 t1, vec3 n1, float d_v, float d_n) {
    float theta_i = acos(clamp(cos_i, -1.0, 1.0));
    float theta_t = acos(clamp(dot(-t1, n1), -1.0, 1.0));
    float ratio = theta_i > 1e-4 ? theta_t / theta_i : 1.0;
    return ratio * d_v + (1.0 - ratio) * d_n;
}

// The second interface: t1 leaves the refractor (index ior, entered at cos_i through n1) through
// the back face of normal n2 (none there: -n1). False on total internal reflection, `power`
// untouched; else t2, and `power` times both interfaces' Fresnel transmittance (when on) and
// the material's colour.
bool exit_refractor(vec3 t1, vec3 n1, vec3 n2, float cos_i, float ior, vec3 colour, inout vec3 power, out vec3 t2) {
    n2 = dot(n2, n2) < 0.5 ? -n1 : normalize(n2);
    t2 = refract(t1, -n2, ior);
    if (dot(t2, t2) < 0.5) return false;
    if ((caustics.settings.w & CAUSTIC_FRESNEL) != 0u) {
        power *= (1.0 - dielectric_fresnel(cos_i, 1.0 / ior)) * (1.0 - dielectric_fresnel(dot(-t1, -n2), ior));
    }
    power *= colour;
    t2 = normalize(t2);
    return true;
}

// Photon through the surface point p1 (normal n1, thickness d_n) of material `m` with solid
// angle `omega`.
Photon trace_photon_through(uint l, vec3 p1, vec3 n1, float d_n, float omega, SpecularMaterial m) {
    CausticLight cl = caustics.lights[l];
    vec3 v = normalize(p1 - cl.position.xyz);
    if (dot(n1, v) > 0.0) n1 = -n1;
    // A spot light's cone and projected texture shape the photons as they shape the direct
    // light (and the CPU reference's photons): the power is weighted by the texture's colour in
    // the photon's direction, zero outside the cone.
    vec3 power = frame.lights[l].intensity.rgb * spot_emission(l, v) * omega;
    vec3 o, d;
    if (m.kind == MATERIAL_REFLECTIVE) {
        o = p1;
        d = reflect(v, n1);
        power *= m.colour;
    } else {
        float ior = m.ior;
        float cos_i = dot(-v, n1);
        vec3 t1 = refract(v, n1, 1.0 / ior);
        bool inside;
        if ((caustics.settings.w & CAUSTIC_ONE_REFRACTION) != 0u) {
            // The caustics mapping tutorial's path (`refractions = one`): refracted where the
            // light meets the object, then straight on through it, the receivers searched from
            // there (its psIntersectPts); only that interface's Fresnel transmittance.
            if ((caustics.settings.w & CAUSTIC_FRESNEL) != 0u) power *= 1.0 - dielectric_fresnel(cos_i, 1.0 / ior);
            power *= m.colour;
            o = p1;
            d = normalize(t1);
        } else {
            vec2 ndc = project_ndc(cl.photon_view_proj, p1, inside);
            vec4 back = texture(light_back_faces, ndc * 0.5 + 0.5);
            float d_v = max(back.w - distance(p1, cl.position.xyz), 0.0);
            vec3 p2 = p1 + wyman2005_distance(cos_i, t1, n1, d_v, d_n) * t1;
            // Beyond the paper (caustics.back_face_iterations > 0): refine the exit point against
            // the back faces the light sees, rayGeo's iteration applied to the back-face distances.
            // Wyman's d estimate alone falls short near the silhouette, where the chord is long but
            // d_V is ~0, and the wrong back-face normal then reports total internal reflection.
            for (uint k = 0u; k < uint(caustics.splat.z); ++k) {
                vec3 dir_l = normalize(p2 - cl.position.xyz);
                vec2 nk = project_ndc(cl.photon_view_proj, p2, inside);
                vec4 bk = texture(light_back_faces, nk * 0.5 + 0.5);
                if (bk.w <= 0.0) break;
                p2 = p1 + distance(p1, cl.position.xyz + dir_l * bk.w) * t1;
            }
            vec2 ndc2 = project_ndc(cl.photon_view_proj, p2, inside);
            vec3 n2 = texture(light_back_faces, ndc2 * 0.5 + 0.5).xyz;
            if (!exit_refractor(t1, n1, n2, cos_i, ior, m.colour, power, d)) {   // total internal reflection: lost
                return lost_photon(power, PHOTON_LOST_TIR);
            }
            o = p2;
        }
    }
    vec3 hit;
    bool found;
    if (m.kind == MATERIAL_REFLECTIVE && (caustics.settings.w & CAUSTIC_REFLECTION_PLANE) != 0u) {
        // Wyman & Davis 2006 Sec. 4: "we reflect about the surface normal and perform a ray-plane
        // intersection with a single background plane".
        float t = (caustics.background_plane.x - o.y) / d.y;
        found = d.y != 0.0 && t > 0.0;
        hit = o + t * d;
    } else {
        found = find_receiver(l, o, d, hit);
    }
    return found ? landed_photon(hit, d, power) : lost_photon(power, PHOTON_LOST_NO_RECEIVER);
}
#endif
