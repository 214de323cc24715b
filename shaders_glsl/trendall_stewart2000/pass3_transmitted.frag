#version 460
// Pass 3 (Sec. 4.2): L_s cos(theta_i) T(cos(theta_i)), T the Fresnel transmission coefficient
// averaged over polarisations (Sec. 4). Both factors are in [0, 1]: neither is adjusted.
// FAITHFUL: cos(theta_i) T from its colour table; L_s an 8-bit texture (footnote 1).
#include "pass.glsl"

layout(set = 0, binding = 1) uniform sampler2D normals;
layout(set = 0, binding = 2) uniform sampler2D light_radiance;
#ifdef FAITHFUL
layout(set = 0, binding = 3) uniform sampler2D colour_tables;
#endif

layout(location = 0) out vec4 out_transmitted;

float transmittance(float ci) {
    float ni = u.optics.y, nt = u.optics.z, eta = u.optics.x;
    float ct = sqrt(max(0.0, 1.0 - eta * eta * (1.0 - ci * ci)));
    float s = ni * ci / (ni * ci + nt * ct);
    float p = ni * ci / (nt * ci + ni * ct);
    return ci > 0.0 ? 2.0 * (nt * ct) / (ni * ci) * (s * s + p * p) : 0.0;
}

void main() {
    ivec2 ij = grid_texel();
    vec3 n = texelFetch(normals, ij, 0).xyz;
    float ls = texelFetch(light_radiance, ij, 0).r;
#ifdef FAITHFUL
    n = unadjust(vec4(n, 0.0), u.enc_normal_lo, u.enc_normal_span).xyz;
    float cos_i = dot(-u.light.xyz, n);
    float cos_t_i = texelFetch(colour_tables, ivec2(table_index(adjust(cos_i, u.enc_cos.x, u.enc_cos.y)), 0), 0).g;
    out_transmitted = vec4(ls * cos_t_i, 0.0, 0.0, 1.0);
#else
    float cos_i = dot(-u.light.xyz, n);
    out_transmitted = vec4(ls * cos_i * transmittance(cos_i), 0.0, 0.0, 1.0);
#endif
}
