// The point splat's vertex stage, included by a vertex shader after its #version. Photon
// splatting (Shah et al.'s point splats; Wyman & Davis 2006 "points"): every photon is a point
// drawn into the light-space caustic map, covering its kernel (shared/splat_photon.glsl).
// Where the photons come from:
// - default: fetched from the photon texture by gl_InstanceIndex and the index in a small
//   vertex buffer (Wyman 2008 Sec. 4): no copy of the photon buffer into a vertex array;
// - PHOTON_VERTEX_ARRAY: the faithful Wyman & Davis 2006 path (Wyman 2008 Table 1 "copy to
//   vertex array"): the photon buffer was copied into a vertex array (positions) and a buffer
//   (power), one vertex per photon;
// - HIERARCHY: one vertex per entry of the hierarchical traversal's final list (Wyman 2008
//   Sec. 3.1-3.2), each picking its layer of the multi-resolution map (Sec. 3.3) with gl_Layer;
// - ADAPTIVE_PHOTONS: one vertex per photon the adaptive traversal output (Wyman & Nichols 2009
//   Sec. 3.2, step 3), its position, power and varying splat radius read as vertex attributes,
//   picking its layer of the multi-resolution map as HIERARCHY's entries do;
// - TEXEL_RADIUS: the default path, each splat's radius from `texel_radius`, which the vertex
//   shader including this file defines after it (a deposit's own vertex shader, in its paper's
//   folder; docs/adding_a_technique.md).
// shared/splat.comp deposits the same splats from a compute shader. shared/splat.vert is this
// file with no deposit of its own.
#ifndef SPLAT_POINTS_GLSL
#define SPLAT_POINTS_GLSL
#if defined(HIERARCHY) || defined(ADAPTIVE_PHOTONS)
#extension GL_ARB_shader_viewport_layer_array : require
#endif
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "shared/splat_photon.glsl"
// Mirrored by `SplatConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform SplatConstants {
    uint light;
    uint vertices_per_instance;   // the instanced fetch (default path): vertices per instance
} constants;
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
uvec4 entry() { return uvec4(0u); }
#elif defined(ADAPTIVE_PHOTONS)
layout(location = 0) in vec3 a_position;                    // AdaptivePhoton (adaptive_photon.glsl)
layout(location = 1) in vec3 a_power;
layout(location = 2) in float a_footprint;
bool fetch_photon(out vec4 pos, out vec3 power) {
    pos = vec4(a_position, 1.0);
    power = a_power;
    return true;
}
uvec4 entry() { return uvec4(floatBitsToUint(a_footprint), 0u, 0u, 0u); }
#elif defined(HIERARCHY)
layout(location = 0) in uint a_entry;                       // packed (x, y, level, final)
bool fetch_photon(out vec4 pos, out vec3 power) { return photon_of_entry(unpack_entry(a_entry), pos, power); }
uvec4 entry() { return unpack_entry(a_entry); }
#else
layout(location = 0) in uint a_vertex;
// Wyman 2008 Sec. 4: a small vertex buffer drawn instanced.
// With as many vertices as the photon buffer is wide this is the paper's s = gl_VertexID,
// t = gl_InstanceID; other sizes index the buffer row by row.
uint photon_id() { return gl_InstanceIndex * constants.vertices_per_instance + a_vertex; }
bool fetch_photon(out vec4 pos, out vec3 power) { return photon_of_texel(photon_id(), pos, power); }
#ifdef TEXEL_RADIUS
// The photon's texel, which its radius is a function of.
uvec4 entry() {
    uint width = uint(textureSize(photon_position, 0).x);
    return uvec4(photon_id() % width, photon_id() / width, 0u, 0u);
}
#else
uvec4 entry() { return uvec4(0u); }
#endif
#endif
layout(location = 0) flat out vec4 v_power;     // (power, photons) / (sum of kernel weights)
layout(location = 1) flat out vec2 v_centre;    // photon position in caustic-map pixels
layout(location = 2) flat out float v_radius;

void main() {
    CausticLight cl = caustics.lights[constants.light];
    gl_PointSize = 1.0;
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);     // culled unless it is a live photon
    v_power = vec4(0.0);
    v_centre = vec2(0.0);
    v_radius = 0.0;
    vec4 pos;
    vec3 power;
    Splat s;
    if (!fetch_photon(pos, power) || !splat_of(pos, power, entry(), cl, s)) return;
#if defined(HIERARCHY) || defined(ADAPTIVE_PHOTONS)
    gl_Layer = s.layer;
#endif
    v_power = s.power;
    v_centre = s.centre;
    v_radius = s.radius;
    gl_Position = vec4(s.centre / cl.caustic_plane.y * 2.0 - 1.0, 0.5, 1.0);
    gl_PointSize = s.size;
}
#endif
