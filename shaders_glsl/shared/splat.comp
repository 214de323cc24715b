// Compute splat: the modern path beside the point splat (shared/splat.vert + splat.frag). One
// invocation per photon (a photon-buffer texel, an entry of the hierarchical traversal's final
// list with HIERARCHY, or an output photon of the adaptive traversal with ADAPTIVE_PHOTONS) adds
// its kernel, weighted as the point splat's fragments are, to a float buffer with atomics;
// shared/splat_resolve.comp then stores the buffer in the caustic map. The texels, weights and layers are those of the point splat (shared/splat_photon.glsl),
// so both give the same caustic map up to the order of the float additions.
#version 450
#extension GL_EXT_shader_atomic_float : require
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "shared/splat_photon.glsl"
layout(local_size_x = 64) in;
// Mirrored by `ComputeSplatConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform ComputeSplatConstants {
    uint photon_texels;   // without HIERARCHY: the photon-buffer texels, one invocation each
    uint light;
} constants;
// Layers x M x M texels of (power rgb, photon count), zeroed before the dispatch.
#if defined(HIERARCHY)
layout(std430, binding = 6) buffer Accumulated { float texels[]; };
layout(std430, binding = 7) readonly buffer Entries { uint entries[]; };   // packed (hierarchy/entry.glsl)
#define LIST_COUNTER_BINDING 8
#elif defined(ADAPTIVE_PHOTONS)
#include "wyman_nichols2009/adaptive_photon.glsl"
layout(std430, binding = 4) buffer Accumulated { float texels[]; };
// The adaptive traversal's output photons (Wyman & Nichols 2009 Sec. 3.2).
layout(std430, binding = 5) readonly buffer Records { AdaptivePhoton records[]; };
#define LIST_COUNTER_BINDING 6
#else
layout(std430, binding = 4) buffer Accumulated { float texels[]; };
#endif
#ifdef LIST_COUNTER_BINDING
// The list's counter: transform feedback's byte count (XFB) or vkcore's append counter.
#ifdef XFB
layout(std430, binding = LIST_COUNTER_BINDING) readonly buffer Counter { uint bytes; };
uint entry_count() { return bytes / ENTRY_BYTES; }
#else
#include "vkcore/compact_counter.glsl"
layout(std430, binding = LIST_COUNTER_BINDING) readonly buffer Counter { CompactCounter counter; };
uint entry_count() { return min(counter.count, counter.capacity); }
#endif
#endif

#include "shared/splat_deposit.glsl"

void main() {
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
    CausticLight cl = caustics.lights[constants.light];
    vec4 pos;
    vec3 power;
#if defined(HIERARCHY)
    if (i >= entry_count()) return;
    uvec4 entry = unpack_entry(entries[i]);
    if (!photon_of_entry(entry, pos, power)) return;
#elif defined(ADAPTIVE_PHOTONS)
    if (i >= entry_count()) return;
    uvec4 entry = uvec4(floatBitsToUint(records[i].footprint), 0u, 0u, 0u);
    pos = vec4(records[i].position, 1.0);
    power = records[i].power;
#else
    uvec4 entry = uvec4(0u);
    if (i >= constants.photon_texels || !photon_of_texel(i, pos, power)) return;
#endif
    Splat s;
    if (!splat_of(pos, power, entry, cl, s)) return;
    int m = int(cl.caustic_plane.y);
    // The point sprite's texels (splat_of dropped splats centred off the map), clipped to it: those whose centres lie within half its size of the centre.
    ivec2 lo = max(ivec2(ceil(s.centre - 0.5 * s.size - 0.5)), ivec2(0));
    ivec2 hi = min(ivec2(floor(s.centre + 0.5 * s.size - 0.5)), ivec2(m - 1));
    for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
            float w = splat_weight(s.centre, s.radius, vec2(x, y) + 0.5);
            if (w != 0.0) deposit(s.layer, ivec2(x, y), m, s.power * w);
        }
    }
}
