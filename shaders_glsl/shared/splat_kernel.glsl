// The splat kernel (Shah et al.'s point splats; Wyman & Davis 2006 "points"): Gaussian with
// sigma = r/2, or box, over the texel centres within r of the photon. Shared by the point splat
// (shared/splat.vert, splat.frag) and the compute splat (shared/splat.comp). Needs
// common/caustics.glsl (splat.y: 0 Gaussian, 1 box).
#ifndef SPLAT_KERNEL_GLSL
#define SPLAT_KERNEL_GLSL
float splat_kernel(float d, float r) {
    if (d > r) return 0.0;
    if (caustics.splat.y > 0.5) return 1.0;
    float sigma = 0.5 * r;
    return exp(-0.5 * d * d / (sigma * sigma));
}

// The weight of the texel with centre `p` in a splat at `centre` of `radius`; radius -1 means
// the kernel misses every texel centre, and the nearest texel takes the whole photon.
float splat_weight(vec2 centre, float radius, vec2 p) {
    if (radius < 0.0) return all(equal(floor(p), floor(centre))) ? 1.0 : 0.0;
    float d = distance(p, centre);
    return d > radius ? 0.0 : (caustics.splat.y > 0.5 ? 1.0 : exp(-0.5 * d * d / (0.25 * radius * radius)));
}
#endif
