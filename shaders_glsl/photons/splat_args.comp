// The compute splat's dispatch over the hierarchical traversal's final list, from its counter,
// so that nothing is read back on the CPU: (x, y, 1) groups of 64 and the entry count. XFB: the
// counter is transform feedback's byte count; otherwise vkcore's append counter.
#version 450
#include "vkcore/compact_counter.glsl"
layout(local_size_x = 1) in;
#ifdef XFB
layout(std430, binding = 0) readonly buffer Counter { uint bytes; };
#else
layout(std430, binding = 0) readonly buffer Counter { CompactCounter counter; };
#endif
layout(std430, binding = 1) writeonly buffer Arguments { uvec4 args; };

void main() {
#ifdef XFB
    uint n = bytes / ENTRY_BYTES;           // ENTRY_BYTES: defined by the caller
#else
    uint n = min(counter.count, counter.capacity);
#endif
    uint groups = (n + 63u) / 64u;
    uint x = max(min(groups, 65535u), 1u);
    args = uvec4(x, (groups + x - 1u) / x, 1u, n);
}
