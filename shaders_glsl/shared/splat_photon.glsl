// One photon's splat, shared by the point splat (shared/splat.vert + splat.frag) and the compute
// splat (shared/splat.comp) so that both deposit the same power in the same texels: where the
// photon lands in the caustic map, its radius and layer, and its power divided by the kernel's
// sum over the texel centres it covers (a photon deposits exactly its power).
// Needs common/caustics.glsl; binds photon_position and photon_power at 2-3 and, with
// HIERARCHY, the photon hierarchy at 4-5 (PHOTON_VERTEX_ARRAY and ADAPTIVE_PHOTONS bring their
// own photons; TEXEL_RADIUS's shader binds what its radius reads, from 4 on). Varying splats
// (caustics.splat.w) with HIERARCHY, ADAPTIVE_PHOTONS and TEXEL_RADIUS.
#ifndef SPLAT_PHOTON_GLSL
#define SPLAT_PHOTON_GLSL
#include "shared/splat_kernel.glsl"

#if !defined(PHOTON_VERTEX_ARRAY) && !defined(ADAPTIVE_PHOTONS)
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D photon_power;

// Photon `id` of the photon texture, row by row; false past its last row.
bool photon_of_texel(uint id, out vec4 pos, out vec3 power) {
    uint width = uint(textureSize(photon_position, 0).x);
    ivec2 texel = ivec2(id % width, id / width);
    pos = vec4(0.0);
    power = vec3(0.0);
    if (texel.y >= textureSize(photon_position, 0).y) return false;
    pos = texelFetch(photon_position, texel, 0);
    power = texelFetch(photon_power, texel, 0).rgb;
    return true;
}
#endif

#ifdef HIERARCHY
#include "wyman2008/entry.glsl"
layout(binding = 4) uniform sampler2D hierarchy_power;      // level k at mip k-1: (power sum, count)
layout(binding = 5) uniform sampler2D hierarchy_position;   // (position sum, 0)

// An entry (x, y, level, final) of the traversal's final list (Wyman 2008 Sec. 3.1-3.2): a
// photon of the photon buffer (level 0) or a cluster of converging photons at level k, whose
// summed power and mean position the photon hierarchy holds. pos.w: photons (1 for a photon,
// the cluster's count for a cluster; 0: none).
bool photon_of_entry(uvec4 entry, out vec4 pos, out vec3 power) {
    ivec2 t = ivec2(entry.xy);
    if (entry.z == 0u) {
        pos = texelFetch(photon_position, t, 0);
        power = texelFetch(photon_power, t, 0).rgb;
        return true;
    }
    int mip = int(entry.z) - 1;
    vec4 a = texelFetch(hierarchy_power, t, mip);
    pos = vec4(texelFetch(hierarchy_position, t, mip).xyz / max(a.w, 1.0), a.w);
    power = a.rgb;
    return true;
}

#include "wyman2008/varying_splat.glsl"
float splat_radius_of(uvec4 entry, vec3 p, vec2 centre, CausticLight cl) { return varying_radius(entry, p, centre, cl); }
#define VARYING_SPLATS
#elif defined(ADAPTIVE_PHOTONS)
// An adaptive photon's varying splat radius came with it (entry.x: its footprint's bits, Wyman &
// Nichols 2009 Sec. 3.2.2, wyman_nichols2009/adaptive.glsl `with_footprints`): 1 texel at least.
float splat_radius_of(uvec4 entry, vec3 p, vec2 centre, CausticLight cl) { return max(uintBitsToFloat(entry.x), 1.0); }
#define VARYING_SPLATS
#elif defined(TEXEL_RADIUS)
// The photon buffer's photons, each sized by its photon-buffer texel (entry.xy) and where it
// landed (`p`): `texel_radius` is the including shader's (shared/splat_points.glsl).
float texel_radius(ivec2 texel, vec3 p, CausticLight cl);
float splat_radius_of(uvec4 entry, vec3 p, vec2 centre, CausticLight cl) { return texel_radius(ivec2(entry.xy), p, cl); }
#define VARYING_SPLATS
#endif

struct Splat {
    vec4 power;     // (power, photons) / (sum of kernel weights): a: photon count
    vec2 centre;    // in the layer's pixels
    float radius;   // -1: the kernel misses every texel centre: all goes to the nearest texel
    float size;     // side of the point sprite that covers the kernel, pixels
    int layer;      // of the multi-resolution map (0 otherwise)
};

// The splat of a photon at `pos` (w: how many photons it stands for, 0 for none) with `power`
// for light `cl`; false when it splats nothing (s then still holds the centre, radius and layer
// it would have had, where it has them, for the `splats` dump)
// (no photon, behind the light, centred off the map, or a varying splat too wide for the last
// map level).
// `entry` is the hierarchy entry (HIERARCHY) or the adaptive photon's footprint (ADAPTIVE_PHOTONS).
bool splat_of(vec4 pos, vec3 power, uvec4 entry, CausticLight cl, out Splat s) {
    s = Splat(vec4(0.0), vec2(0.0), 0.0, 1.0, 0);
    if (pos.w < 0.5) return false;
    vec2 centre;
    if (!caustic_map_texel(cl, pos.xyz, centre)) return false;
    float m = cl.caustic_plane.y;
    float r = caustics.splat.x;
#ifdef INTERPOLATED_LEVEL
    // Interpolated splats (Wyman 2008 Fig. 7; wyman2008/interpolated.rs): this draw's radius,
    // splat.x * 2^INTERPOLATED_LEVEL, into its own full-resolution layer.
    r *= exp2(float(INTERPOLATED_LEVEL));
    s.layer = INTERPOLATED_LEVEL;
#endif
#ifdef VARYING_SPLATS
    if (caustics.splat.w == SPLAT_VARYING_SINGLE || caustics.splat.w == SPLAT_VARYING_MULTIRES) {
        r = splat_radius_of(entry, pos.xyz, centre, cl);
        // photonMipLevel = trunc(log2(max(1, D / 5))); splats needing level 4 or beyond are
        // discarded (D >= 80 by this formula: radius >= 40 texels; the paper's text says "a
        // diameter of more than 40 pixels", which its formula puts at level 3), in the single map
        // too, so that both maps hold the same photons.
        int wanted = int(floor(log2(max(1.0, 2.0 * r / MULTIRES_MAX_DIAMETER))));
        if (caustics.splat.w == SPLAT_VARYING_MULTIRES || wanted >= int(MULTIRES_LEVELS)) {
            // Level i: splatSize = D / 2^i, into the layer's corner region of (M / 2^i)^2.
            s.layer = wanted;
            float f = exp2(float(wanted));
            centre /= f;
            r /= f;
        }
        if (wanted >= int(MULTIRES_LEVELS)) {
            s.centre = centre;
            s.radius = r;
            return false;
        }
    }
#endif
    s.centre = centre;
    s.radius = r;
    // A point whose centre leaves the clip volume may or may not be drawn where its sprite
    // overlaps the map (Vulkan's pointClippingBehavior is the driver's choice): drop it on every
    // path, so that the point and compute splats agree on every device. (Written so that a NaN
    // centre is dropped too.)
    if (!(all(greaterThanEqual(centre, vec2(0.0))) && all(lessThanEqual(centre, vec2(m))))) return false;
    float size = 2.0 * ceil(r) + 2.0;
    // Sum of the kernel over every texel centre the point covers.
    float sum = 0.0;
    vec2 lo = floor(centre - 0.5 * size);
    for (float y = lo.y; y <= lo.y + size + 1.0; y += 1.0) {
        for (float x = lo.x; x <= lo.x + size + 1.0; x += 1.0) {
            sum += splat_kernel(distance(vec2(x, y) + 0.5, centre), r);
        }
    }
    s.power = vec4(power, pos.w) / (sum > 0.0 ? sum : 1.0);
    s.centre = centre;
    s.radius = sum > 0.0 ? r : -1.0;            // -1: nearest texel (see splat_weight)
    s.size = size;
    return true;
}

#endif
