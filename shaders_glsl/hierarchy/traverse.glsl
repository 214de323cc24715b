// One step of the hierarchical photon traversal (Wyman 2008 Sec. 3.1-3.2), shared by the
// geometry-shader (transform feedback) and compute paths. An entry is uvec4(x, y, level,
// final). A final entry (a converged cluster) is passed on unchanged, as the paper's single
// output stream with a flag does. Otherwise the entry at level k either converges (every
// photon below it lands in one caustic-map texel: Sec. 3.2, when clustering is tested at this
// level) and becomes final, or emits those of its four children at level k-1 that hold at
// least one valid photon; children of a level-1 entry are photons of the photon buffer.
// object.info: x = level k, y = light, z = 1 when convergence is tested at this level,
// w = photon buffer side N. Needs CAUSTICS_BINDING (for common/frame.glsl's push constants).
#ifndef TRAVERSE_GLSL
#define TRAVERSE_GLSL
#include "common/frame.glsl"
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D hierarchy_power;    // level k at mip k-1: (power, count)
layout(binding = 4) uniform sampler2D hierarchy_texels;   // caustic-map texel bounding box

bool has_photons(uvec2 t, uint level) {
    if (level == 0u) {
        uint n = object.info.w;
        return t.x < n && t.y < n && texelFetch(photon_position, ivec2(t), 0).w > 0.5;
    }
    return texelFetch(hierarchy_power, ivec2(t), int(level) - 1).w > 0.0;
}

bool converges(uvec2 t, uint level) {
    vec4 box = texelFetch(hierarchy_texels, ivec2(t), int(level) - 1);
    return has_photons(t, level) && box.x == box.z && box.y == box.w;
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
    if (object.info.z != 0u && converges(e.xy, level)) {
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
