// Stores the compute splat's accumulated buffer (shared/splat.comp) in one light's caustic-map
// layers, which the final render samples as it does the point splat's.
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2DArray caustic_map;
layout(std430, binding = 1) readonly buffer Accumulated { vec4 texels[]; };

void main() {
    ivec3 size = imageSize(caustic_map);
    ivec3 t = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(t, size))) return;
    imageStore(caustic_map, t, texels[(t.z * size.y + t.y) * size.x + t.x]);
}
