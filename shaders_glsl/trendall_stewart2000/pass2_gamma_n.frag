#version 460
// Pass 2 (Sec. 4.2): Gamma N of Eq. 1, Gamma = (n_i/n_t) cos(theta_i) - cos(theta_t).
// FAITHFUL: cos(theta_i) = -L_i . N by the colour matrix, -Gamma (an unadjusted function in
// [0, 1]) from its colour table, and the product with the adjusted N (Sec. 3.2, Products),
// stored with Gamma N's own scale and bias.
#include "pass.glsl"

layout(set = 0, binding = 1) uniform sampler2D normals;
#ifdef FAITHFUL
layout(set = 0, binding = 2) uniform sampler2D colour_tables;
#endif

layout(location = 0) out vec4 out_gamma_n;

void main() {
    vec3 n = texelFetch(normals, grid_texel(), 0).xyz;
#ifdef FAITHFUL
    n = unadjust(vec4(n, 0.0), u.enc_normal_lo, u.enc_normal_span).xyz;
    float cos_i = dot(-u.light.xyz, n);
    float minus_gamma = texelFetch(colour_tables, ivec2(table_index(adjust(cos_i, u.enc_cos.x, u.enc_cos.y)), 0), 0).r;
    out_gamma_n = vec4(adjust(vec4(-minus_gamma * n, 0.0), u.enc_gamma_n_lo, u.enc_gamma_n_span).xyz, 1.0);
#else
    float cos_i = dot(-u.light.xyz, n);
    float eta = u.optics.x;
    float cos_t = sqrt(max(0.0, 1.0 - eta * eta * (1.0 - cos_i * cos_i)));
    out_gamma_n = vec4((eta * cos_i - cos_t) * n, 1.0);
#endif
}
