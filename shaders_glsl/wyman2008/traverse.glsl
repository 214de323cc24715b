// One step of the hierarchical photon traversal (Wyman 2008 Sec. 3.1-3.2), shared by the
// geometry-shader (transform feedback) and compute paths. An entry is uvec4(x, y, level, final),
// packed into a uint in the lists (hierarchy/entry.glsl). A final entry (a converged cluster) is
// passed on unchanged, as the paper's single output stream with a flag does. Otherwise the entry
// at level k either converges (two or more photons below it, all landing in one texel of the
// caustic map: Sec. 3.2, when clustering is tested at this level) and becomes final, or emits
// those of its four children at level k-1 that hold at least one valid photon; children of a
// level-1 entry are photons of the photon buffer.
#ifndef TRAVERSE_GLSL
#define TRAVERSE_GLSL
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "wyman2008/entry.glsl"
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D hierarchy_power;    // level k at mip k-1: (power, count)
layout(binding = 4) uniform sampler2D hierarchy_texels;   // caustic-map texel bounding box
// Mirrored by `TraverseConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform TraverseConstants {
    uint light;
    uint cluster;       // 1 when convergence is tested at this level
    uint photon_side;   // the photon buffer side N
} constants;

bool has_photons(uvec2 t, uint level) {
    if (level == 0u) {
        uint n = constants.photon_side;
        return t.x < n && t.y < n && texelFetch(photon_position, ivec2(t), 0).w > 0.5;
    }
    return texelFetch(hierarchy_power, ivec2(t), int(level) - 1).w > 0.0;
}

// A single photon is not a cluster: it goes on down to level 0, where a varying splat finds its
// size from its neighbours. Photons off the caustic map (or behind the light: texel -1) are
// splatted nowhere and converge nowhere: their mean could land on the map.
bool converges(uvec2 t, uint level) {
    vec4 box = texelFetch(hierarchy_texels, ivec2(t), int(level) - 1);
    float m = caustics.lights[constants.light].caustic_plane.y;
    bool on_map = all(greaterThanEqual(box.xy, vec2(0.0))) && all(lessThan(box.zw, vec2(m)));
    return texelFetch(hierarchy_power, ivec2(t), int(level) - 1).w >= 2.0 && on_map && box.xy == box.zw;
}

// Fills `outs` with the entries `e` turns into at this step; returns how many.
uint expand(uvec4 e, out uvec4 outs[4]) {
    if (e.w != 0u) {
        outs[0] = e;
        return 1u;
    }
    uint level = e.z;
    if (level == 0u) {
        outs[0] = e;
        return 1u;
    }
    if (constants.cluster != 0u && converges(e.xy, level)) {
        outs[0] = uvec4(e.xy, level, 1u);
        return 1u;
    }
    uint n = 0u;
    for (uint c = 0u; c < 4u; ++c) {
        uvec2 child = 2u * e.xy + uvec2(c & 1u, c >> 1u);
        if (has_photons(child, level - 1u)) {
            outs[n] = uvec4(child, level - 1u, 0u);
            n += 1u;
        }
    }
    return n;
}
#endif
