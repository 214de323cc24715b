// Adaptive traversal, compute path: one invocation per pending cluster of level k (a list
// entry), appending its four children to the next level's list, or its photons (or the one
// photon of a converged cluster) to the photon list, with atomic counters. The cluster count
// comes from this level's counter through vkCmdDispatchIndirect (written by
// vkcore/compact_finalize.comp after the previous step): nothing is read back between steps.
// One kernel per step for both metrics (wyman_nichols2009/adaptive.glsl).
#version 450
#include "wyman_nichols2009/adaptive.glsl"
#include "vkcore/compact_counter.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 9) readonly buffer Input { uint in_entries[]; };
layout(std430, binding = 10) readonly buffer InputCounter { CompactCounter in_counter; };
layout(std430, binding = 11) writeonly buffer Output { uint out_entries[]; };
layout(std430, binding = 12) buffer OutputCounter { CompactCounter out_counter; };
layout(std430, binding = 13) writeonly buffer Photons { AdaptivePhoton photons[]; };
layout(std430, binding = 14) buffer PhotonCounter { CompactCounter photon_counter; };

void emit(AdaptivePhoton p) {
    uint slot = atomicAdd(photon_counter.count, 1u);
    if (slot < photon_counter.capacity) photons[slot] = p;
}

void refine(uvec3 c) {
    uint slot = atomicAdd(out_counter.count, 4u);
    for (uint i = 0u; i < 4u; ++i) {
        if (slot + i < out_counter.capacity) out_entries[slot + i] = pack_cell(uvec3(photon_of(c, i), c.z + 1u));
    }
}

void main() {
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
    if (i >= min(in_counter.count, in_counter.capacity)) return;
    uvec3 c = unpack_cell(in_entries[i]);
    vec2 cover = footprint_coverage(c);
    if (cover.x < 0.5) return;                            // misses the refractor: discarded
    bool last = c.z == constants.finest;
    // Max traversal (and the max-error metric's first steps, Sec. 4.2) before the last level:
    // the photons themselves are not needed, only their children.
    if (!last && constants.converge == 0u) {
        refine(c);
        return;
    }
    AdaptivePhoton p[4];
    uint landed = cluster_photons(c, p);
    if (constants.converge != 0u && converges(p, landed, cover.y > 0.5)) {
        emit(merged(c, p));
        return;
    }
    if (!last) {
        refine(c);
        return;
    }
    with_footprints(c, p, landed);
    for (uint k = 0u; k < 4u; ++k) {
        if ((landed & (1u << k)) != 0u) emit(p[k]);
    }
}
