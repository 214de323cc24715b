// Photon hierarchy (Wyman 2008 Sec. 3.1): level k of a mipmap over the photon buffer, built from
// level k-1 (level 0 is the photon buffer itself, padded to a power of two with invalid texels).
// Each texel holds what its subtree of valid photons needs: the summed power and photon count
// (hierarchy_power), the summed position (hierarchy_position), and the bounding box of the
// caustic-map texels they project to (hierarchy_texels). The count drives the traversal's
// discard of empty subtrees; the box is the convergence test of Sec. 3.2 (all photons in one
// caustic-map texel); power and position make a converged cluster one photon.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
// Mirrored by `BuildConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform BuildConstants {
    uint level;         // k >= 1
    uint light;
    uint photon_side;   // the photon buffer side N
} constants;
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D photon_power;
layout(binding = 4) uniform sampler2D child_power;      // level k-1 (k >= 2), one mip
layout(binding = 5) uniform sampler2D child_position;
layout(binding = 6) uniform sampler2D child_texels;
layout(binding = 7, rgba32f) uniform writeonly image2D out_power;
layout(binding = 8, rgba32f) uniform writeonly image2D out_position;
layout(binding = 9, rgba32f) uniform writeonly image2D out_texels;

// The caustic-map texel photon position `p` lands in (as in shared/splat.vert); photons
// behind the light's caustic frustum get texel (-1, -1).
vec2 caustic_texel(vec3 p, uint l) {
    vec2 t;
    return caustic_map_texel(caustics.lights[l], p, t) ? floor(t) : vec2(-1.0);
}

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, imageSize(out_power)))) return;
    uint k = constants.level;
    uint l = constants.light;
    int n = int(constants.photon_side);
    vec4 power = vec4(0.0);
    vec3 position = vec3(0.0);
    vec4 box = vec4(3.0e38, 3.0e38, -3.0e38, -3.0e38);
    for (int c = 0; c < 4; ++c) {
        ivec2 ct = 2 * t + ivec2(c & 1, c >> 1);
        if (k == 1u) {
            if (ct.x >= n || ct.y >= n) continue;
            vec4 p = texelFetch(photon_position, ct, 0);
            if (p.w < 0.5) continue;
            vec2 texel = caustic_texel(p.xyz, l);
            power += vec4(texelFetch(photon_power, ct, 0).rgb, 1.0);
            position += p.xyz;
            box = vec4(min(box.xy, texel), max(box.zw, texel));
        } else {
            vec4 cp = texelFetch(child_power, ct, 0);
            if (cp.w <= 0.0) continue;
            vec4 cb = texelFetch(child_texels, ct, 0);
            power += cp;
            position += texelFetch(child_position, ct, 0).xyz;
            box = vec4(min(box.xy, cb.xy), max(box.zw, cb.zw));
        }
    }
    imageStore(out_power, t, power);
    imageStore(out_position, t, vec4(position, 0.0));
    imageStore(out_texels, t, box);
}
