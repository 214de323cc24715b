#version 450
// A pass that does not finish until the host says so: each invocation spins until the host
// writes RELEASED into `release`, or for at most 60000 x 60000 steps so that a test can never
// hang. Each step adds 1 to `release`, an atomic the compiler can neither drop nor hoist (the
// sum stays far below RELEASED). llvmpipe ends an invocation's loops after about 65535
// iterations, so the test dispatches many work groups; once released, those left stop at their
// first step. Full groups of 64: with one invocation per group, llvmpipe ran each group's
// loops to that limit even after every invocation had left them.
#define RELEASED 0x80000000u
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Release { uint release; };
void main() {
    bool released = false;
    for (uint o = 0u; o < 60000u && !released; o++) {
        for (uint i = 0u; i < 60000u && !released; i++) {
            released = atomicAdd(release, 1u) >= RELEASED;
        }
    }
}
