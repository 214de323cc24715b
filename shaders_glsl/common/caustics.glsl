// Light-space frusta of the caustic techniques, mirrored by `CausticUniforms` in
// crates/caustics/src/techniques/uniforms.rs (std140, vec4/uvec4/mat4 members only).
#ifndef CAUSTICS_GLSL
#define CAUSTICS_GLSL
#include "common/frame.glsl"

#define CAUSTIC_FRESNEL 1u          // settings.w bit: Fresnel transmittance at both interfaces
#define CAUSTIC_WD_DEPTH_SEARCH 2u  // settings.w bit: Wyman & Davis depth search, else Shah rayGeo
#define CAUSTIC_BEAM_AREA 4u        // settings.w bit: varying splats by Eq. 1-2, else max distance
#define CAUSTIC_EYE_SPACE 8u        // settings.w bit: caustics rendered in the eye's view (Wyman & Davis 2006)
#define CAUSTIC_REFLECTION_PLANE 16u  // settings.w bit: mirrored photons land on one plane (Wyman & Davis 2006 Sec. 4)
#define CAUSTIC_ONE_REFRACTION 32u    // settings.w bit: refracted once, then straight on (the caustics mapping tutorial)
#define CAUSTIC_TUTORIAL_LOOKUP 64u   // settings.w bit: the caustics mapping tutorial's psDiffuse lookup
#define CAUSTIC_RECEIVER_FLUX 128u    // settings.w bit: the receiver map's caustic term from photon-trace's direct deposit
#define SPLAT_FIXED 0.0
#define SPLAT_VARYING_SINGLE 1.0
#define SPLAT_VARYING_MULTIRES 2.0
#define SPLAT_INTERPOLATED 3.0
// Levels of the multi-resolution caustic map (Wyman 2008 Sec. 3.3): splats that would need the
// 4th level or beyond are discarded.
#define MULTIRES_LEVELS 4u
// Largest splat diameter in any level (the paper's threshold).
#define MULTIRES_MAX_DIAMETER 5.0
// Interpolated splats (Wyman 2008 Fig. 7's third column): layer i of a light's map holds every
// splat at radius splat.x * 2^i, full resolution; the lookup reads the radius at which about
// INTERPOLATED_PHOTONS photons cover the texel (common/caustic_lookup.glsl).
#define INTERPOLATED_LEVELS 4u
#define INTERPOLATED_PHOTONS 8.0

struct CausticLight {
    mat4 photon_view_proj;    // the photon buffer's frustum (tight around the specular objects)
    mat4 caustic_view_proj;   // the caustic map's (and receiver positions') frustum
    vec4 photon_plane;        // x: tan(half fov), y: resolution N, z: solid angle of a central texel
    vec4 caustic_plane;       // x: tan(half fov), y: resolution M, z: solid angle of a central texel
    vec4 axis;                // xyz: both frusta's axis
    vec4 position;            // xyz: the light
};

layout(std140, binding = CAUSTICS_BINDING) uniform Caustics {
    uvec4 settings;   // x: lights with caustics (0 = none), y: photons per side, z: iterations, w: flags
    vec4 splat;       // x: splat radius (caustic-map texels), y: kernel (0 Gaussian, 1 box), z: back-face iterations,
                      // w: splat sizes (SPLAT_FIXED, SPLAT_VARYING_SINGLE, SPLAT_VARYING_MULTIRES, SPLAT_INTERPOLATED)
    vec4 background_plane;  // x: y of the plane mirrored photons land on (CAUSTIC_REFLECTION_PLANE)
    CausticLight lights[MAX_LIGHTS];
} caustics;

// Solid angle of the texel at normalised device coordinates `ndc` of a square perspective
// frustum: texel area on the image plane at unit distance, times cos^3 of the off-axis angle.
float texel_solid_angle(vec2 ndc, vec4 plane) {
    vec2 xy = ndc * plane.x;
    float s = 2.0 * plane.x / plane.y;
    return s * s / pow(1.0 + dot(xy, xy), 1.5);
}

// Where point `p` lands in light `cl`'s caustic map (and receiver positions), in normalised
// device coordinates; false behind the light, where `ndc` means nothing. The caustic-map
// lookup, a texel's solid angle (varying splat radii), Wyman & Davis 2006's light-space points
// and quads and the receiver search project by it.
bool caustic_map_ndc(CausticLight cl, vec3 p, out vec2 ndc) {
    vec4 clip = cl.caustic_view_proj * vec4(p, 1.0);
    ndc = clip.xy / clip.w;
    return clip.w > 0.0;
}

// Where point `p` lands in light `cl`'s caustic map, in texels (texel (i, j) spans [i, i + 1) x
// [j, j + 1)); false behind the light, where `t` means nothing. Splats, hierarchy texels,
// adaptive clusters and max-distance radii land by it.
bool caustic_map_texel(CausticLight cl, vec3 p, out vec2 t) {
    vec2 ndc;
    bool in_front = caustic_map_ndc(cl, p, ndc);
    t = (ndc * 0.5 + 0.5) * cl.caustic_plane.y;
    return in_front;
}

// The varying splat radius "based on the maximum distance between adjacent photons rather than
// area" (Wyman 2008 Sec. 3.3): the largest distance in caustic-map texels from a photon's
// `centre` to where its adjacent photons landed (neighbour k at `t[k]` where bit k of
// `landed` is set). Wyman 2008's photon buffer and Wyman & Nichols 2009's adaptive photons
// (Sec. 3.2.2) both use it.
float max_distance_radius(vec2 centre, vec2 t[4], uint landed) {
    float dmax = 0.0;
    for (int k = 0; k < 4; ++k) {
        if ((landed & (1u << uint(k))) != 0u) dmax = max(dmax, distance(t[k], centre));
    }
    return dmax;
}
#endif
