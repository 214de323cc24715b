// The coverage pyramid of the light-space geometry buffers (Wyman & Nichols 2009 Sec. 3.2.1,
// made conservative): texel t of level m says whether any (r) and whether all (g) of the
// geometry-buffer texels [t 2^m, (t + 1) 2^m) hold a front surface. Level 0 is the front
// layer's coverage padded with empty texels to a power-of-two side; level m is the max (r) and
// min (g) of its four children at level m - 1. A cluster of the adaptive traversal is
// discarded only when no texel its photons (and their descendants) can sample is covered
// (wyman_nichols2009/adaptive.glsl, footprint_coverage).
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray geometry_normal;   // front layer: w = object + 1
layout(binding = 1) uniform sampler2D finer;                  // level m - 1 (unused at level 0)
layout(rgba8, binding = 2) uniform writeonly image2D level_out;
// Mirrored by `CoverageConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform CoverageConstants {
    uint level;
} constants;

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, imageSize(level_out)))) return;
    vec2 c;
    if (constants.level == 0u) {
        ivec2 g = textureSize(geometry_normal, 0).xy;
        float covered = all(lessThan(t, g)) && texelFetch(geometry_normal, ivec3(t, 0), 0).w > 0.5 ? 1.0 : 0.0;
        c = vec2(covered);
    } else {
        c = vec2(0.0, 1.0);
        for (int k = 0; k < 4; ++k) {
            vec4 v = texelFetch(finer, 2 * t + ivec2(k & 1, k >> 1), 0);
            c = vec2(max(c.x, v.r), min(c.y, v.g));
        }
    }
    imageStore(level_out, t, vec4(c, 0.0, 1.0));
}
