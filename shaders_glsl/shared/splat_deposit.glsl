// A compute splat's addition to its accumulation (crates/caustics/src/techniques/shared/
// compute_splat.rs, `Accumulated`): texel `t` of layer `layer` of M x M texels gains `v` (power
// rgb, photons), with float atomics. Needs `texels[]`, the Accumulated buffer, declared first.
#ifndef SPLAT_DEPOSIT_GLSL
#define SPLAT_DEPOSIT_GLSL
void deposit(int layer, ivec2 t, int m, vec4 v) {
    uint i = 4u * (uint(layer * m + t.y) * uint(m) + uint(t.x));
    atomicAdd(texels[i], v.x);
    atomicAdd(texels[i + 1u], v.y);
    atomicAdd(texels[i + 2u], v.z);
    atomicAdd(texels[i + 3u], v.w);
}
#endif
