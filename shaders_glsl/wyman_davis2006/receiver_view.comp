// The orthographic view straight down on the receiver plane that the eye-space techniques render
// the receiver map from: pixel (i, j) sees the receiver texel (i, j), at its centre
// (x0 + (i + 0.5)(x1 - x0)/N, plane_y, z0 + (j + 0.5)(z1 - z0)/N), normal +y (the receiver
// map's convention, receiver/receiver_map.comp). Only the plane is in this view.
#version 450
#include "common/frame.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1, rgba32f) uniform writeonly image2D view_position;
layout(binding = 2, rgba32f) uniform writeonly image2D view_normal;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    int n = int(frame.receiver.y);
    if (ij.x >= n || ij.y >= n) return;
    vec4 r = frame.receiver_range;
    vec3 p = vec3(r.x + (float(ij.x) + 0.5) * (r.y - r.x) / float(n),
                  frame.receiver.x,
                  r.z + (float(ij.y) + 0.5) * (r.w - r.z) / float(n));
    imageStore(view_position, ij, vec4(p, 1.0));
    imageStore(view_normal, ij, vec4(0.0, 1.0, 0.0, 0.0));
}
