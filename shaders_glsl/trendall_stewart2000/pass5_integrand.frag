#version 460
// Pass 5 (Sec. 4.2): F, the function to be convolved: (Pass 3) (Pass 4). FAITHFUL: an
// adjusted function times an unadjusted one, (gf)~ = g f~ + (1 - g) beta (Sec. 3.2), which keeps
// Pass 4's scale and bias.
#include "pass.glsl"

layout(set = 0, binding = 1) uniform sampler2D transmitted;
layout(set = 0, binding = 2) uniform sampler2D direction;

layout(location = 0) out vec4 out_integrand;

void main() {
    ivec2 ij = grid_texel();
    float g = texelFetch(transmitted, ij, 0).r;
    vec3 d = texelFetch(direction, ij, 0).xyz;
#ifdef FAITHFUL
    vec3 beta = -u.enc_direction_lo.xyz / u.enc_direction_span.xyz;
    out_integrand = vec4(g * d + (1.0 - g) * beta, 1.0);
#else
    out_integrand = vec4(g * d, 1.0);
#endif
}
