// Varying splat sizes from a per-photon thin-lens model: Wyman & Dachsbacher's variable-sized
// splats, the second column of Wyman 2008 Fig. 7, which Sec. 3.3 describes as "approximating
// photon divergence using a per-pixel thin-lens model" (and "fragile"). Their paper is not
// among the five in shared/papers; this is the model as causticlab builds it from that
// description (docs/papers.md says so):
// - the specular objects are one thin lens, rotationally symmetric about the light's axis (the
//   fitted photon frustum's: from the light through the centre of the objects' bounds, hence
//   `photon_view = fitted`), met where the photon leaves them: on its light ray at the
//   light-space back face (Wyman 2005's exit-point estimate d_V). A photon whose light ray
//   meets no back face (a mirror's, unless a refractor lies behind it) keeps the constant radius;
// - the photon's beam is as wide there as its photon-buffer texel's solid angle spans at that
//   distance, and converges toward where the photon's exit ray crosses the axis (its focus),
//   diverging past it: photons that leave at height h from the axis with a radial direction
//   component d_r are h + d_r s from it after a distance s, so the beam's width scales by
//   |1 + d_r s / h| (the sagittal width of a rotationally symmetric lens);
// - the splat radius is half that width where the photon lands, in caustic-map texels there:
//   1 texel at least, and under the 40 texels beyond which a varying splat is dropped
//   (shared/splat_photon.glsl), so that every photon deposits its power.
// It reads only the photon's own ray, no neighbour: it misses the spread across the axis
// (spherical aberration, which draws the caustic's cusp) and any shape the lens does not fit,
// which is why Sec. 3.3 sizes splats from the photon buffer's own spacing instead.
// Needs photon_position (shared/splat_photon.glsl) and common/caustics.glsl.
#ifndef THIN_LENS_GLSL
#define THIN_LENS_GLSL
layout(binding = 4) uniform sampler2D photon_direction;
layout(binding = 5) uniform sampler2D light_back_faces;

// Just under the radius of a splat that needs the multi-resolution map's 5th level.
#define THIN_LENS_MAX_RADIUS (0.5 * MULTIRES_MAX_DIAMETER * exp2(float(MULTIRES_LEVELS)) - 0.5)

// The splat radius, in caustic-map texels, of the photon of photon-buffer texel `t` that landed
// at `hit`.
float thin_lens_radius(ivec2 t, vec3 hit, CausticLight cl) {
    float back = texelFetch(light_back_faces, t, 0).w;
    if (back <= 0.0) return caustics.splat.x;
    int n = textureSize(photon_position, 0).x;
    vec2 ndc = (vec2(t) + 0.5) / float(n) * 2.0 - 1.0;
    vec4 on_ray = inverse(cl.photon_view_proj) * vec4(ndc, 0.5, 1.0);
    vec3 light = cl.position.xyz;
    vec3 lens = light + normalize(on_ray.xyz / on_ray.w - light) * back;
    vec3 axis = normalize(cl.axis.xyz);
    vec3 radial = (lens - light) - dot(lens - light, axis) * axis;
    float h = length(radial);
    vec3 d = normalize(texelFetch(photon_direction, t, 0).xyz);
    float s = distance(lens, hit);
    // On the axis the focus is undefined: the beam keeps its width.
    float spread = h > 1e-6 * back ? abs(1.0 + dot(d, radial / h) * s / h) : 1.0;
    float beam = sqrt(texel_solid_angle(ndc, cl.photon_plane)) * back * spread;
    vec2 landed;
    caustic_map_ndc(cl, hit, landed);
    float texel = sqrt(texel_solid_angle(landed, cl.caustic_plane)) * distance(hit, light);
    return clamp(0.5 * beam / texel, 1.0, THIN_LENS_MAX_RADIUS);
}
#endif
