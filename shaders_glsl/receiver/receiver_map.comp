// The receiver map: for texel (i, j) of an N x N grid over [x0,x1] x [z0,z1] at height
// plane_y (texel centres at x0 + (i + 0.5)(x1 - x0)/N, row 0 at z0), E/E0 per channel, where
// E is the irradiance arriving there (direct light where the shadow map says unshadowed; caustic
// light once a technique adds it) and E0 the irradiance from all lights with no occluders.
#version 450
#define SHADOW_BINDING 1
#define SPOT_BINDING 2
#define CAUSTICS_BINDING 6
#define CAUSTIC_MAP_BINDING 7
#define RECEIVER_POSITIONS_BINDING 8
#include "common/lighting.glsl"
#include "common/caustic_lookup.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 3, rgba32f) uniform writeonly image2D ratio_map;       // rgb E/E0
layout(binding = 4, rgba32f) uniform writeonly image2D irradiance_map;  // rgb E (W/m^2), a: mean E0
layout(binding = 5, rgba32f) uniform writeonly image2D caustic_only;    // rgb caustic E (W/m^2)
// Eye-space techniques (CAUSTIC_EYE_SPACE): the caustic irradiance their eye-space pass found
// from the orthographic view straight down on the receiver plane, texel for texel.
layout(binding = 9) uniform sampler2DArray receiver_view_caustic;
// photon-trace's direct deposit (CAUSTIC_RECEIVER_FLUX): per texel, the power (W, rgb) of the
// photons that landed in it, binned as the CPU reference bins them, and their count.
layout(std430, binding = 10) readonly buffer ReceiverFlux { vec4 receiver_flux[]; };

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    int n = int(frame.receiver.y);
    if (ij.x >= n || ij.y >= n) return;
    vec4 r = frame.receiver_range;
    vec3 p = vec3(r.x + (float(ij.x) + 0.5) * (r.y - r.x) / float(n),
                  frame.receiver.x,
                  r.z + (float(ij.y) + 0.5) * (r.w - r.z) / float(n));
    vec3 up = vec3(0.0, 1.0, 0.0);
    vec3 e0 = vec3(0.0);
    for (uint l = 0u; l < frame.counts.x; ++l) e0 += unoccluded_irradiance(l, p, up);
    vec3 ec;
    if ((caustics.settings.w & CAUSTIC_RECEIVER_FLUX) != 0u) {
        ec = receiver_flux[ij.y * n + ij.x].rgb * float(n * n) / ((r.y - r.x) * (r.w - r.z));
    } else if ((caustics.settings.w & CAUSTIC_EYE_SPACE) != 0u) {
        ec = texelFetch(receiver_view_caustic, ivec3(ij, 0), 0).rgb;
    } else {
        ec = caustic_irradiance_over(p, vec3(0.5 * (r.y - r.x) / float(n), 0.0, 0.0), vec3(0.0, 0.0, 0.5 * (r.w - r.z) / float(n)), up);
    }
    vec3 e = direct_irradiance(p, up) + ec;
    vec3 ratio = vec3(e0.r > 0.0 ? e.r / e0.r : 0.0, e0.g > 0.0 ? e.g / e0.g : 0.0, e0.b > 0.0 ? e.b / e0.b : 0.0);
    imageStore(ratio_map, ij, vec4(ratio, 1.0));
    imageStore(irradiance_map, ij, vec4(e, (e0.r + e0.g + e0.b) / 3.0));
    imageStore(caustic_only, ij, vec4(ec, 1.0));
}
