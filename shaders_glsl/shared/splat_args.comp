// The compute splat's dispatch over the final list of the transform-feedback traversal, from its
// byte count, so that nothing is read back on the CPU: (x, y, 1) groups of 64. (The compute
// traversal's append counter already holds its dispatch, written by vkcore/compact_finalize.comp.)
#version 450
#include "vkcore/dispatch_grid.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Counter { uint bytes; };
layout(std430, binding = 1) writeonly buffer Arguments { uvec4 args; };

void main() {
    uint n = bytes / ENTRY_BYTES;           // ENTRY_BYTES: defined by the caller
    args = uvec4(dispatch_grid((n + 63u) / 64u), 1u, n);
}
