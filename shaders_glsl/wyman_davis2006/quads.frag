// A caustic quad's light where it covers a pixel (Sec. 3.2.1): the caustic term of Eq. 3,
// R L(V, N, L_photon), with L = I cos / d^2 for the Lambertian receivers (the light's intensity
// and what the specular surfaces let through are in v_intensity), or of Eq. 4 with the light's
// direct direction. Blended additively: overlapping beams add.
// Eye space: irradiance (W/m^2) at the surface the pixel sees, if the quad lies on it.
// Light space (LIGHT_SPACE): the power (W) the quad puts into the caustic-map texel, R I w_t
// (times Eq. 3's cos(photon) / cos(direct)), which the caustic-map lookup turns into irradiance.
// QUAD_POINTS (a polygon under a pixel, see quads.vert): its whole power I w_B lands in the
// pixel: in light space as it is, in eye space over the pixel's area on its surface (from the
// world positions of the neighbouring pixels, as the gather's). QUAD_LINES (a sliver): the
// same, with the power shared by the line's fragments (quads.vert divides it).
// Alpha counts the quads' fragments: 1 for every fragment rasterized, whether it lands on the
// pixel's surface or not, so that the target's alpha is the caustic polygons' depth complexity
// (Fig. 6: the fill rate they consume); a fragment off the surface adds no light.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "wyman_davis2006/image_space.glsl"
#ifdef LIGHT_SPACE
layout(binding = 7) uniform sampler2D receiver_positions;   // light l's first diffuse surfaces
#else
layout(binding = 5) uniform sampler2D view_position;
layout(binding = 6) uniform sampler2D view_normal;
#endif
layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_direction;
layout(location = 2) flat in vec3 v_intensity;
layout(location = 0) out vec4 o_caustic;

void main() {
    CausticLight cl = caustics.lights[constants.light];
    vec3 d_photon = normalize(v_direction);
#ifdef LIGHT_SPACE
    vec3 p = v_position;
    // Eq. 3's N: the surface the light sees in this texel, from the receiver positions (as the
    // light-space gather's), not the polygon's own normal, which points anywhere once the
    // polygon folds into a sliver at a caustic.
    vec3 n = normal_from_positions(receiver_positions, ivec2(gl_FragCoord.xy), cl.position.xyz);
#else
    ivec2 t = ivec2(gl_FragCoord.xy);
    vec4 surface = texelFetch(view_position, t, 0);
    if (!on_surface(surface, v_position)) {
        o_caustic = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 p = surface.xyz;
    vec3 n = texelFetch(view_normal, t, 0).xyz;
#endif
    vec3 to_light = cl.position.xyz - p;
    float d2 = dot(to_light, to_light);
    float cos_direct = dot(n, to_light * inversesqrt(d2));
    float f = constants.lighting == 3u ? photon_lighting(dot(n, -d_photon), cos_direct) : 1.0;
#if defined(QUAD_POINTS) || defined(QUAD_LINES)
#ifdef LIGHT_SPACE
    o_caustic = vec4(v_intensity * f, 1.0);
#else
    float area = pixel_area(view_position, t, p);
    o_caustic = area > 0.0 ? vec4(v_intensity * f / area, 1.0) : vec4(0.0, 0.0, 0.0, 1.0);
#endif
#else
#ifdef LIGHT_SPACE
    float m = cl.caustic_plane.y;
    float w_t = texel_solid_angle(gl_FragCoord.xy / m * 2.0 - 1.0, cl.caustic_plane);
    o_caustic = vec4(v_intensity * w_t * f, 1.0);
#else
    o_caustic = vec4(v_intensity * max(cos_direct, 0.0) * f / d2, 1.0);
#endif
#endif
}
