#version 460
// Pass 4 (Sec. 4.2): L_t (L_tz)^(n-1), L_t = (n_i/n_t) L_i + Gamma N (Eq. 1), in the expansion
// basis (z the direction of light through flat water: the vertical for overhead light; see
// kernels.rs). FAITHFUL: L_t is the adjusted sum of Gamma N and a constant, turned into the
// basis by the colour matrix; (L_tz)^(n-1), an unadjusted function, comes from its colour
// table indexed by L_tz's code; the product keeps L_t's scale and bias for x and y (Sec. 3.2),
// and z is stored unadjusted.
#include "pass.glsl"

layout(set = 0, binding = 1) uniform sampler2D gamma_n;
#ifdef FAITHFUL
layout(set = 0, binding = 2) uniform sampler2D colour_tables;
#endif

layout(location = 0) out vec4 out_direction;

void main() {
    vec3 g = texelFetch(gamma_n, grid_texel(), 0).xyz;
#ifdef FAITHFUL
    g = unadjust(vec4(g, 0.0), u.enc_gamma_n_lo, u.enc_gamma_n_span).xyz;
#endif
    vec3 lt_world = u.optics.x * u.light.xyz + g;
    vec3 lt = vec3(dot(lt_world, u.basis_x.xyz), dot(lt_world, u.basis_y.xyz), dot(lt_world, u.basis_z.xyz));
#ifdef FAITHFUL
    float w = texelFetch(colour_tables, ivec2(table_index(adjust(lt.z, u.enc_lt_lo.z, u.enc_lt_span.z)), 0), 0).b;
    vec4 d = vec4(w * lt, 0.0);
    out_direction = vec4(adjust(d, u.enc_direction_lo, u.enc_direction_span).xy, clamp(d.z, 0.0, 1.0), 1.0);
#else
    // (n - 1) log(L_tz), with L_tz^2 = 1 - L_tx^2 - L_ty^2 over the unit L_t.
    float across = (lt.x * lt.x + lt.y * lt.y) / dot(lt, lt);
    float w = lt.z > 0.0 ? exp(0.5 * (u.optics.w - 1.0) * log1m(across)) : 0.0;
    out_direction = vec4(w * lt, 1.0);
#endif
}
