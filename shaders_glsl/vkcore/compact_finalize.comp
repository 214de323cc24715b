// Turns an append counter into indirect dispatch and draw arguments, so the next step runs on
// the GPU-side count without a CPU readback.
#version 450
#include "vkcore/compact_counter.glsl"
#include "vkcore/dispatch_grid.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Counter { CompactCounter counter; };

void main() {
    uint n = min(counter.count, counter.capacity);
    counter.dispatch = uvec4(dispatch_grid((n + 63u) / 64u), 1u, 0u);
    counter.draw = uvec4(n, 1u, 0u, 0u);
}
