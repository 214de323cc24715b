#version 450
// out[i] = in[i] + add, for the pass-builder tests.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { uint in_values[]; };
layout(std430, binding = 1) buffer Out { uint out_values[]; };
layout(push_constant) uniform AddConstants { uint count; uint add; } constants;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < constants.count) out_values[i] = in_values[i] + constants.add;
}
