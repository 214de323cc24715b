#version 460
// Pass 6 (Sec. 4.1-4.2): the three convolutions E_j = sum over the kernel of F_j K_j, and their
// sum E, the irradiance on the bottom (Eq. 2). The kernels (kernels.rs) hold the receiver's
// cosine, the exponentiated cosine's P terms and the extinction. Surface texels outside the
// pool hold no water and add nothing. FAITHFUL: the convolution of the adjusted F (an affine
// function of F), the post-convolution scale and bias back to F's units, the colour matrix's
// sum, and each result stored with its own scale and bias (the OpenGL 1.2 imaging pipeline).
#include "pass.glsl"

layout(set = 0, binding = 1) uniform sampler2D integrand;
layout(set = 0, binding = 2) readonly buffer Kernels { vec4 taps[]; } k;

layout(location = 0) out vec4 out_convolution;

void main() {
    ivec2 ij = grid_texel();
    int side = int(u.grid.y), r = u.kernel.z, n = int(u.grid.x);
    vec3 e = vec3(0.0);
    for (int b = 0; b < side; b++) {
        for (int a = 0; a < side; a++) {
            ivec2 s = ij - (ivec2(a - r, b - r) + u.kernel.xy);
            if (any(lessThan(s, ivec2(0))) || any(greaterThanEqual(s, ivec2(n)))) continue;
            vec3 f = texelFetch(integrand, s, 0).xyz;
#ifdef FAITHFUL
            f = unadjust(vec4(f, 0.0), u.enc_direction_lo, u.enc_direction_span).xyz;
#endif
            e += f * k.taps[b * side + a].xyz;
        }
    }
    vec4 result = vec4(e, e.x + e.y + e.z);
#ifdef FAITHFUL
    result = adjust(result, u.enc_convolution_lo, u.enc_convolution_span);
#endif
    out_convolution = result;
}
