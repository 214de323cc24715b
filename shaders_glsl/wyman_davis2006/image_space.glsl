// Wyman & Davis 2006 Sec. 3.2: what the eye-space points, the caustic quads and the gathers
// share: the push constants of every such pass, the view they draw into (the eye, an
// orthographic view straight down on the receiver plane, or light l's caustic map), and the
// lighting of photons (Eq. 3-4 and 9-11). Needs common/caustics.glsl (bindings 0-1).
#ifndef IMAGE_SPACE_GLSL
#define IMAGE_SPACE_GLSL

// Mirrored by `ImageSpaceConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform ImageSpaceConstants {
    mat4 view_proj;       // world to the view's clip space
    vec4 tolerance;       // a photon is on the pixel's surface within x * (distance to eye) + y (m)
    vec4 eye;             // xyz: the eye (the view's), w: 1 for an orthographic view
    uint light;
    uint lighting;        // 9, 10, 11 (points, gathers) or 3, 4 (quads)
    uint slot;            // the history layer this frame writes (temporal filter, Sec. 3.2.3)
    uint frames;          // history layers that hold a frame, 1..4, from history_base on
    uint radius;          // the gather's half-width: 3 (7x7), 0 for points
    uint min_photons;     // neighbourhoods with fewer photons are discarded (3, Sec. 3.2.2; 0: none)
    uint photon_side;     // N, the photon buffer's side
    uint history_base;    // the first history layer of this view (light space: light * layers)
} constants;

const float PI = 3.14159265358979;

#include "shared/pixel_area.glsl"

// The surface point of a view's pixel: world position (w = 1 where there is a surface) and
// normal. Light space has no normal image: it is the cross product of the differences to the
// neighbouring texels' world positions (the receiver positions map), turned towards `toward`.
vec3 normal_from_positions(sampler2D positions, ivec2 t, vec3 toward) {
    ivec2 size = textureSize(positions, 0);
    vec3 p = texelFetch(positions, t, 0).xyz;
    ivec2 tx = ivec2(min(t.x + 1, size.x - 1), t.y);
    ivec2 ty = ivec2(t.x, min(t.y + 1, size.y - 1));
    vec4 px = texelFetch(positions, tx == t ? ivec2(max(t.x - 1, 0), t.y) : tx, 0);
    vec4 py = texelFetch(positions, ty == t ? ivec2(t.x, max(t.y - 1, 0)) : ty, 0);
    vec3 dx = (px.xyz - p) * (tx == t ? -1.0 : 1.0);
    vec3 dy = (py.xyz - p) * (ty == t ? -1.0 : 1.0);
    vec3 n = cross(dx, dy);
    if (px.w < 0.5 || py.w < 0.5 || dot(n, n) == 0.0) return vec3(0.0, 1.0, 0.0);
    n = normalize(n);
    return dot(n, toward - p) < 0.0 ? -n : n;
}

// Whether a photon at `photon` belongs to the surface `surface` (w = 1 where there is one)
// a pixel sees: it must not be hidden from the view, or on another surface.
bool on_surface(vec4 surface, vec3 photon) {
    if (surface.w < 0.5) return false;
    float d = constants.eye.w > 0.5 ? 0.0 : distance(surface.xyz, constants.eye.xyz);
    return distance(surface.xyz, photon) <= constants.tolerance.x * d + constants.tolerance.y;
}

// The cosine of the light's direct direction at p with normal n, for light l.
float direct_cosine(uint l, vec3 p, vec3 n) {
    return dot(n, normalize(caustics.lights[l].position.xyz - p));
}

// L(V, N, L_photon) / L(V, N, L_direct) for a Lambertian surface: the factor Eq. 3, 9 and 10
// put on a photon's ratio E_photon / E_p (Eq. 4 and 11: 1). For a Lambertian receiver the flux
// of a photon adds Phi / A whatever its direction, which Eq. 4 and 11 give exactly; Eq. 3, 9
// and 10 re-light it with cos(photon) / cos(direct). Where the light grazes the surface
// (cos(direct) < 0.05) that ratio has no meaning and is taken as 1.
float photon_lighting(float cos_photon, float cos_direct) {
    if (cos_direct < 0.05) return 1.0;
    return max(cos_photon, 0.0) / cos_direct;
}
#endif
