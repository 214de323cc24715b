// The compute splat's dispatch over the final list of the transform-feedback traversal, from its
// byte count, so that nothing is read back on the CPU: (x, y, 1) groups of 64. (The compute
// traversal's append counter already holds its dispatch, written by vkcore/compact_finalize.comp.)
#version 450
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Counter { uint bytes; };
layout(std430, binding = 1) writeonly buffer Arguments { uvec4 args; };

void main() {
    uint n = bytes / ENTRY_BYTES;           // ENTRY_BYTES: defined by the caller
    uint groups = (n + 63u) / 64u;
    uint x = max(min(groups, 65535u), 1u);
    args = uvec4(x, (groups + x - 1u) / x, 1u, n);
}
