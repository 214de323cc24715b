// Photon batching (Wyman & Nichols 2009 Sec. 4.3): batch b's input is the slice
// [first, first + size) of the pending clusters of level B (those that exist), copied into the
// batch's list, whose counter it writes (the count, and the dispatch and draw over it, as
// vkcore/compact_finalize.comp does; on the xfb path the byte count transform feedback would
// have written). Nothing is read back: the count of level B stays on the GPU.
#version 450
#include "vkcore/compact_counter.glsl"
#include "vkcore/dispatch_grid.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Pending { uint pending[]; };
layout(std430, binding = 1) readonly buffer PendingCounter { uint pending_counter[]; };
layout(std430, binding = 2) writeonly buffer Batch { uint batch[]; };
layout(std430, binding = 3) buffer BatchCounter { CompactCounter batch_counter; };
// Mirrored by `BatchConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform BatchConstants {
    uint first;   // the batch's first cluster
    uint size;    // clusters per batch (the batch list's capacity)
    uint xfb;     // 1: the counters are transform feedback's byte counts
} constants;

void main() {
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
    // Level B's clusters: a byte count (xfb) or an append counter's count, within its capacity.
    uint total = constants.xfb != 0u ? pending_counter[0] / 4u : min(pending_counter[0], pending_counter[1]);
    uint n = total > constants.first ? min(constants.size, total - constants.first) : 0u;
    if (i < n) batch[i] = pending[constants.first + i];
    if (i == 0u) {
        batch_counter.count = constants.xfb != 0u ? 4u * n : n;
        batch_counter.capacity = constants.size;
        batch_counter.dispatch = uvec4(dispatch_grid((n + 63u) / 64u), 1u, 0u);
        batch_counter.draw = uvec4(n, 1u, 0u, 0u);
    }
}
