// The adaptive traversal's per-level counts (Wyman & Nichols 2009 Table 1, Fig. 7): after a
// step, adds the next level's pending clusters and the photons output so far to their slots,
// summed over the batches of a batched traversal (Sec. 4.3). One invocation.
#version 450
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Clusters { uint clusters_counter[]; };
layout(std430, binding = 1) readonly buffer Photons { uint photons_counter[]; };
layout(std430, binding = 2) buffer Counts { uint counts[]; };
// Mirrored by `CountConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform CountConstants {
    uint cluster_slot;   // 0xFFFFFFFF: no next level
    uint photon_slot;
    uint xfb;            // 1: the counters are byte counts
} constants;

// Elements of a counter: bytes / element bytes (xfb), or the append count within capacity.
uint elements(uint count, uint capacity, uint bytes) {
    return constants.xfb != 0u ? count / bytes : min(count, capacity);
}

void main() {
    if (constants.cluster_slot != 0xFFFFFFFFu) {
        counts[constants.cluster_slot] += elements(clusters_counter[0], clusters_counter[1], 4u);
    }
    counts[constants.photon_slot] += elements(photons_counter[0], photons_counter[1], 32u);
}
