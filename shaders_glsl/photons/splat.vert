// Photon splatting (Shah et al.'s point splats; Wyman & Davis 2006 "points"): every photon is a
// point drawn into the light-space caustic map. The kernel is normalised over the texels it
// covers, so a photon deposits exactly its power. Where the photons come from:
// - default: fetched from the photon texture by gl_InstanceIndex and the index in a small
//   vertex buffer (Wyman 2008 Sec. 4): no copy of the photon buffer into a vertex array;
// - PHOTON_VERTEX_ARRAY: the faithful Wyman & Davis 2006 path (Wyman 2008 Table 1 "copy to
//   vertex array"): the photon buffer was copied into a vertex array (positions) and a buffer
//   (power), one vertex per photon;
// - HIERARCHY: one vertex per entry of the hierarchical traversal's final list (Wyman 2008
//   Sec. 3.1-3.2): a photon of the photon buffer (level 0) or a cluster of converging photons
//   at level k, whose summed power and mean position the photon hierarchy holds.
#version 450
#ifdef HIERARCHY
#extension GL_ARB_shader_viewport_layer_array : require
#endif
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#if defined(PHOTON_VERTEX_ARRAY)
layout(location = 0) in vec4 a_position;
#ifdef PHOTON_HALF
layout(std430, binding = 2) readonly buffer PhotonPower { uvec2 powers[]; };   // RGBA16F texels
vec3 photon_power_of(uint id) { uvec2 h = powers[id]; return vec3(unpackHalf2x16(h.x), unpackHalf2x16(h.y).x); }
#else
layout(std430, binding = 2) readonly buffer PhotonPower { vec4 powers[]; };
vec3 photon_power_of(uint id) { return powers[id].rgb; }
#endif
bool fetch_photon(out vec4 pos, out vec3 power) {
    pos = a_position;
    power = photon_power_of(gl_VertexIndex);
    return true;
}
#elif defined(HIERARCHY)
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D photon_power;
layout(binding = 4) uniform sampler2D hierarchy_power;      // level k at mip k-1: (power sum, count)
layout(binding = 5) uniform sampler2D hierarchy_position;   // (position sum, 0)
layout(location = 0) in uvec4 a_entry;                      // (x, y, level, final)
bool fetch_photon(out vec4 pos, out vec3 power) {
    ivec2 t = ivec2(a_entry.xy);
    if (a_entry.z == 0u) {
        pos = texelFetch(photon_position, t, 0);
        power = texelFetch(photon_power, t, 0).rgb;
        return true;
    }
    int mip = int(a_entry.z) - 1;
    vec4 a = texelFetch(hierarchy_power, t, mip);
    pos = vec4(texelFetch(hierarchy_position, t, mip).xyz / max(a.w, 1.0), a.w > 0.0 ? 1.0 : 0.0);
    power = a.rgb;
    return true;
}

// Splat radius (caustic-map texels) from the photon's neighbours (Wyman 2008 Sec. 3.3, Eq. 1-2
// with the paper's approximation by the largest distance between adjacent photons rather than
// the area they span). Measured in the caustic map itself, the distance already carries Eq. 2's
// d^2 and obliquity: it is the footprint of the photon's beam in texels. Clusters of converging
// photons land in one texel by construction.
float varying_radius(vec2 centre, CausticLight cl) {
    if (a_entry.z != 0u) return 1.0;
    ivec2 t = ivec2(a_entry.xy);
    int n = textureSize(photon_position, 0).x;
    const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    float dmax = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 q = t + offsets[k];
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(n)))) continue;
        vec4 p = texelFetch(photon_position, q, 0);
        if (p.w < 0.5) continue;
        vec4 clip = cl.caustic_view_proj * vec4(p.xyz, 1.0);
        if (clip.w <= 0.0) continue;
        dmax = max(dmax, distance((clip.xy / clip.w * 0.5 + 0.5) * cl.caustic_plane.y, centre));
    }
    return max(dmax, 1.0);
}
#else
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D photon_power;
layout(location = 0) in uint a_vertex;
bool fetch_photon(out vec4 pos, out vec3 power) {
    uint width = uint(textureSize(photon_position, 0).x);
    // Wyman 2008 Sec. 4: a small vertex buffer drawn instanced; info.z: vertices per instance.
    // With as many vertices as the photon buffer is wide this is the paper's s = gl_VertexID,
    // t = gl_InstanceID; other sizes index the buffer row by row.
    uint id = gl_InstanceIndex * object.info.z + a_vertex;
    ivec2 texel = ivec2(id % width, id / width);
    pos = vec4(0.0);
    power = vec3(0.0);
    if (texel.y >= textureSize(photon_position, 0).y) return false;
    pos = texelFetch(photon_position, texel, 0);
    power = texelFetch(photon_power, texel, 0).rgb;
    return true;
}
#endif
layout(location = 0) flat out vec4 v_power;     // (power, 1) / (sum of kernel weights)
layout(location = 1) flat out vec2 v_centre;    // photon position in caustic-map pixels
layout(location = 2) flat out float v_radius;

float kernel(float d, float r) {
    if (d > r) return 0.0;
    if (caustics.splat.y > 0.5) return 1.0;
    float sigma = 0.5 * r;
    return exp(-0.5 * d * d / (sigma * sigma));
}

void main() {
    uint l = object.info.y;
    CausticLight cl = caustics.lights[l];
    gl_PointSize = 1.0;
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);     // culled unless it is a live photon
    v_power = vec4(0.0);
    v_centre = vec2(0.0);
    v_radius = 0.0;
    vec4 pos;
    vec3 power;
    if (!fetch_photon(pos, power) || pos.w < 0.5) return;
    vec4 clip = cl.caustic_view_proj * vec4(pos.xyz, 1.0);
    if (clip.w <= 0.0) return;
    float m = cl.caustic_plane.y;
    vec2 centre = (clip.xy / clip.w * 0.5 + 0.5) * m;
    float r = caustics.splat.x;
#ifdef HIERARCHY
    int level = 0;
    if (caustics.splat.w != SPLAT_FIXED) {
        r = varying_radius(centre, cl);
        // photonMipLevel = trunc(log2(max(1, D / 5))); splats needing level 4 or beyond (D > 40)
        // are discarded, in the single map too, so that both maps hold the same photons.
        int wanted = int(floor(log2(max(1.0, 2.0 * r / MULTIRES_MAX_DIAMETER))));
        if (wanted >= int(MULTIRES_LEVELS)) return;
        if (caustics.splat.w == SPLAT_VARYING_MULTIRES) {
            // Level i: splatSize = D / 2^i, into the layer's corner region of (M / 2^i)^2.
            level = wanted;
            float s = exp2(float(level));
            centre /= s;
            r /= s;
        }
    }
    gl_Layer = level;
#endif
    float size = 2.0 * ceil(r) + 2.0;
    // Sum of the kernel over every texel centre the point covers.
    float sum = 0.0;
    vec2 lo = floor(centre - 0.5 * size);
    for (float y = lo.y; y <= lo.y + size + 1.0; y += 1.0) {
        for (float x = lo.x; x <= lo.x + size + 1.0; x += 1.0) {
            sum += kernel(distance(vec2(x, y) + 0.5, centre), r);
        }
    }
    v_power = vec4(power, 1.0) / (sum > 0.0 ? sum : 1.0);
    v_centre = centre;
    v_radius = sum > 0.0 ? r : -1.0;            // -1: the kernel misses every centre: nearest texel
    gl_Position = vec4(centre / m * 2.0 - 1.0, 0.5, 1.0);
    gl_PointSize = size;
}
