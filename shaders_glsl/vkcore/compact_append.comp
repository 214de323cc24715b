// Stream compaction, compute path: an append buffer. Each kept element takes a slot with an
// atomic counter. The element count comes from a push constant (first step) or from the
// previous step's counter (GPU-driven, no readback). KEEP_EXPR is a define over `v`.
#version 450
#include "vkcore/compact_counter.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Input { uvec4 in_values[]; };
layout(std430, binding = 1) readonly buffer InputCounter { CompactCounter in_counter; };
layout(std430, binding = 2) writeonly buffer Output { uvec4 out_values[]; };
layout(std430, binding = 3) buffer OutputCounter { CompactCounter out_counter; };

// Mirrored by `CompactConstants` in crates/vkcore/src/compaction.rs.
layout(push_constant) uniform CompactConstants {
    uint n;             // element count when use_in_count == 0
    uint use_in_count;  // 1: read the count from in_counter
    uint capacity;      // out_values' length
};

bool keep(uvec4 v) { return KEEP_EXPR; }

void main() {
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
    uint count = use_in_count != 0u ? min(in_counter.count, in_counter.capacity) : n;
    if (i >= count) return;
    uvec4 v = in_values[i];
    if (!keep(v)) return;
    uint slot = atomicAdd(out_counter.count, 1u);
    if (slot < capacity) out_values[slot] = v;
}
