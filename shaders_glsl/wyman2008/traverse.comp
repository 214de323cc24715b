// Hierarchical traversal, compute path: one invocation per entry of the previous level's list,
// appending its children (or the converged cluster) with an atomic counter. The entry count
// comes from the previous level's counter through vkCmdDispatchIndirect; its dispatch and
// draw arguments are written by vkcore/compact_finalize.comp after this pass.
#version 450
#include "wyman2008/traverse.glsl"
#include "vkcore/compact_counter.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 5) readonly buffer Input { uint in_entries[]; };
layout(std430, binding = 6) readonly buffer InputCounter { CompactCounter in_counter; };
layout(std430, binding = 7) writeonly buffer Output { uint out_entries[]; };
layout(std430, binding = 8) buffer OutputCounter { CompactCounter out_counter; };

void main() {
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
    if (i >= min(in_counter.count, in_counter.capacity)) return;
    uvec4 outs[4];
    uint n = expand(unpack_entry(in_entries[i]), outs);
    if (n == 0u) return;
    uint slot = atomicAdd(out_counter.count, n);
    for (uint k = 0u; k < n; ++k) {
        if (slot + k < out_counter.capacity) out_entries[slot + k] = pack_entry(outs[k]);
    }
}
