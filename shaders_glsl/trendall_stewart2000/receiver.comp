#version 460
// The receiver map: E / E_flat per texel of the pool bottom (E_flat: the same passes for a flat
// surface, computed once), with E and E_flat. A validation instrument, in float for every path.
#include "pool.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D convolutions;
layout(set = 0, binding = 2) uniform sampler2D flat_convolutions;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D receiver;

float irradiance(sampler2D s, ivec2 ij) {
    float e = texelFetch(s, ij, 0).a;
    if (u.grid.z != 0u) e = unadjust(e, u.enc_convolution_lo.w, u.enc_convolution_span.w);
    return e;
}

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(ij, ivec2(u.grid.x)))) return;
    float e = irradiance(convolutions, ij), e_flat = irradiance(flat_convolutions, ij);
    imageStore(receiver, ij, vec4(e_flat > 0.0 ? e / e_flat : 0.0, e, e_flat, 1.0));
}
