// Wyman 2008 Fig. 7's varying splats from a per-photon thin-lens model: the photon buffer's
// point splat (shared/splat_points.glsl) with each splat's radius from the photon's own ray
// through the lens (wyman2008/thin_lens.glsl, which binds the photons' directions and the
// light-space back faces at 4-5).
#version 450
#define TEXEL_RADIUS 1
#include "shared/splat_points.glsl"
#include "wyman2008/thin_lens.glsl"
float texel_radius(ivec2 texel, vec3 p, CausticLight cl) { return thin_lens_radius(texel, p, cl); }
