// The splat of photon differentials (`photon-trace --differentials`; Schjøth, Frisvad, Erleben &
// Sporring 2007): each photon's footprint on the surface it landed on (photon_trace/trace.comp:
// the derivatives of its position along the emission square's two coordinates, times the
// stratum's side, vectors a and b) is projected into the caustic map (the derivative of its
// perspective projection, in texels), and the photon's power is spread over the caustic-map
// texels by a Gaussian in the footprint's own lattice coordinates: covariance
// C = FOOTPRINT_SIGMA^2 (a a^T + b b^T), which sums to a nearly flat field over a regular
// lattice of such photons (ripple about 0.2% at 0.6: 2 exp(-2 pi^2 0.6^2)). The weights are
// divided by their sum over the
// texel centres they cover, so each photon deposits exactly its power (and, in alpha, one
// photon), as the fixed splat's do (shared/splat_photon.glsl), less the kernel's part that
// falls off the map, as theirs. (The ripple is a regular
// lattice's, `jitter = false`; jittered photons are not one.) With a dispersive material each
// photon carries one channel at three times the power while its footprint is the whole grid's:
// each channel's kernels are about sqrt(3) too narrow, the flux still whole.
//
// The clamp: C's eigenvalues are held to [min_sigma^2, max_sigma^2] caustic-map texels^2. At a
// caustic's fold the footprint collapses (a and b parallel, or zero: the derivative of the map
// from the emission square to the surface is singular) and the density it implies is infinite;
// held to min_sigma (half a texel), the photon goes to about one texel, as binning into the
// caustic map's grid would put it. Where photons diverge, max_sigma (8 texels) bounds the
// kernel's width and its cost; there the splat is narrower than the footprint, the flux still
// kept whole.
#version 450
#extension GL_EXT_shader_atomic_float : require
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
layout(local_size_x = 64) in;
layout(push_constant) uniform DifferentialSplatConstants {
    uint photon_texels;
    uint light;
    float min_sigma;   // caustic-map texels
    float max_sigma;
} constants;
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D photon_power;
layout(binding = 4) uniform sampler2D photon_footprint_u;
layout(binding = 5) uniform sampler2D photon_footprint_v;
// M x M texels of (power rgb, photon count) of the light's layer, zeroed before the dispatch.
layout(std430, binding = 6) buffer Accumulated { float texels[]; };

#define FOOTPRINT_SIGMA 0.6
// The kernel's support, in standard deviations.
#define SUPPORT 3.0

// The derivative, in caustic-map texels, of where point `p` (its clip position `clip`) lands
// in light `cl`'s caustic map, along world vector `v`.
vec2 texel_derivative(CausticLight cl, vec4 clip, vec3 v) {
    vec4 dclip = cl.caustic_view_proj * vec4(v, 0.0);
    vec2 dndc = (dclip.xy * clip.w - clip.xy * dclip.w) / (clip.w * clip.w);
    return dndc * 0.5 * cl.caustic_plane.y;
}

#include "shared/splat_deposit.glsl"

void main() {
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
    if (i >= constants.photon_texels) return;
    uint width = uint(textureSize(photon_position, 0).x);
    ivec2 texel = ivec2(i % width, i / width);
    vec4 pos = texelFetch(photon_position, texel, 0);
    if (pos.w == 0.0) return;
    vec3 power = texelFetch(photon_power, texel, 0).rgb;
    CausticLight cl = caustics.lights[constants.light];
    vec4 clip = cl.caustic_view_proj * vec4(pos.xyz, 1.0);
    if (clip.w <= 0.0) return;
    int m = int(cl.caustic_plane.y);
    vec2 centre = (clip.xy / clip.w * 0.5 + 0.5) * float(m);
    // As the fixed splat's (shared/splat_photon.glsl): a photon centred off the map splats nothing.
    if (!(all(greaterThanEqual(centre, vec2(0.0))) && all(lessThanEqual(centre, vec2(m))))) return;
    vec2 a = texel_derivative(cl, clip, texelFetch(photon_footprint_u, texel, 0).xyz);
    vec2 b = texel_derivative(cl, clip, texelFetch(photon_footprint_v, texel, 0).xyz);
    if (any(isnan(a)) || any(isinf(a)) || any(isnan(b)) || any(isinf(b))) {
        // No footprint to speak of: the smallest kernel.
        a = vec2(0.0);
        b = vec2(0.0);
    }
    // C = s^2 (a a^T + b b^T): its eigenvalues and the unit eigenvector of the larger.
    float s2 = FOOTPRINT_SIGMA * FOOTPRINT_SIGMA;
    float cxx = s2 * (a.x * a.x + b.x * b.x);
    float cyy = s2 * (a.y * a.y + b.y * b.y);
    float cxy = s2 * (a.x * a.y + b.x * b.y);
    float half_trace = 0.5 * (cxx + cyy);
    float disc = sqrt(max(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy, 0.0));
    float l1 = half_trace + disc;
    float l2 = max(half_trace - disc, 0.0);
    vec2 e1 = abs(cxy) > 1e-12 ? normalize(vec2(l1 - cyy, cxy)) : (cxx >= cyy ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
    if (!(l1 <= 3.4e38) || any(isnan(e1))) {
        // A footprint too large for f32's squares: the widest kernel.
        l1 = constants.max_sigma * constants.max_sigma;
        l2 = l1;
        e1 = vec2(1.0, 0.0);
    }
    vec2 e2 = vec2(-e1.y, e1.x);
    float lo = constants.min_sigma * constants.min_sigma;
    float hi = constants.max_sigma * constants.max_sigma;
    l1 = clamp(l1, lo, hi);
    l2 = clamp(l2, lo, hi);
    // The clamped C's inverse, and the box of its support.
    mat2 inv = outerProduct(e1, e1) / l1 + outerProduct(e2, e2) / l2;
    vec2 half_box = SUPPORT * sqrt(vec2(l1 * e1.x * e1.x + l2 * e2.x * e2.x, l1 * e1.y * e1.y + l2 * e2.y * e2.y));
    // The weights' sum over every texel centre of the support, on the map or not (as the fixed
    // splat's, shared/splat_photon.glsl: the kernel's part off the map is light off it); the
    // deposit over those on the map.
    ivec2 box_from = ivec2(ceil(centre - half_box - 0.5));
    ivec2 box_to = ivec2(floor(centre + half_box - 0.5));
    ivec2 from = max(box_from, ivec2(0));
    ivec2 to = min(box_to, ivec2(m - 1));
    float sum = 0.0;
    for (int y = box_from.y; y <= box_to.y; ++y) {
        for (int x = box_from.x; x <= box_to.x; ++x) {
            vec2 d = vec2(x, y) + 0.5 - centre;
            float q = dot(d, inv * d);
            if (q <= SUPPORT * SUPPORT) sum += exp(-0.5 * q);
        }
    }
    if (!(sum > 0.0)) {
        // The kernel misses every texel centre: the nearest texel takes the whole photon.
        deposit(0, clamp(ivec2(centre), ivec2(0), ivec2(m - 1)), m, vec4(power, 1.0));
        return;
    }
    for (int y = from.y; y <= to.y; ++y) {
        for (int x = from.x; x <= to.x; ++x) {
            vec2 d = vec2(x, y) + 0.5 - centre;
            float q = dot(d, inv * d);
            if (q <= SUPPORT * SUPPORT) deposit(0, ivec2(x, y), m, vec4(power, 1.0) * (exp(-0.5 * q) / sum));
        }
    }
}
