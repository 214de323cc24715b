// Photon splatting (Shah et al.'s point splats; Wyman & Davis 2006 "points"): every photon is a
// point drawn into the light-space caustic map. Photons are fetched from the photon texture by
// gl_InstanceIndex and the index in a small vertex buffer (Wyman 2008 Sec. 4): no copy of the
// photon buffer into a vertex array. The kernel is normalised over the texels it covers, so a
// photon deposits exactly its power.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#ifdef PHOTON_VERTEX_ARRAY
// The faithful Wyman & Davis 2006 path (Wyman 2008 Table 1 "copy to vertex array"): the photon
// buffer was copied into a vertex array (positions) and a buffer (power), one vertex per photon.
layout(location = 0) in vec4 a_position;
#ifdef PHOTON_HALF
layout(std430, binding = 2) readonly buffer PhotonPower { uvec2 powers[]; };   // RGBA16F texels
vec3 photon_power_of(uint id) { uvec2 h = powers[id]; return vec3(unpackHalf2x16(h.x), unpackHalf2x16(h.y).x); }
#else
layout(std430, binding = 2) readonly buffer PhotonPower { vec4 powers[]; };
vec3 photon_power_of(uint id) { return powers[id].rgb; }
#endif
#else
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D photon_power;
layout(location = 0) in uint a_vertex;
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
#ifdef PHOTON_VERTEX_ARRAY
    uint id = gl_VertexIndex;
    vec4 pos = a_position;
    bool outside = false;
#else
    uint width = uint(textureSize(photon_position, 0).x);
    uint id = gl_InstanceIndex * object.info.z + a_vertex;   // info.z: vertices per instance
    ivec2 texel = ivec2(id % width, id / width);
    vec4 pos = texelFetch(photon_position, texel, 0);
    bool outside = texel.y >= textureSize(photon_position, 0).y;
#endif
    gl_PointSize = 1.0;
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);     // culled unless it is a live photon
    v_power = vec4(0.0);
    v_centre = vec2(0.0);
    v_radius = 0.0;
    if (outside || pos.w < 0.5) return;
    vec4 clip = cl.caustic_view_proj * vec4(pos.xyz, 1.0);
    if (clip.w <= 0.0) return;
    float m = cl.caustic_plane.y;
    vec2 centre = (clip.xy / clip.w * 0.5 + 0.5) * m;
    float r = caustics.splat.x;
    float size = 2.0 * ceil(r) + 2.0;
    // Sum of the kernel over every texel centre the point covers.
    float sum = 0.0;
    vec2 lo = floor(centre - 0.5 * size);
    for (float y = lo.y; y <= lo.y + size + 1.0; y += 1.0) {
        for (float x = lo.x; x <= lo.x + size + 1.0; x += 1.0) {
            sum += kernel(distance(vec2(x, y) + 0.5, centre), r);
        }
    }
#ifdef PHOTON_VERTEX_ARRAY
    vec3 power = photon_power_of(id);
#else
    vec3 power = texelFetch(photon_power, texel, 0).rgb;
#endif
    v_power = vec4(power, 1.0) / (sum > 0.0 ? sum : 1.0);
    v_centre = centre;
    v_radius = sum > 0.0 ? r : -1.0;            // -1: the kernel misses every centre: nearest texel
    gl_Position = vec4(clip.xy / clip.w, 0.5, 1.0);
    gl_PointSize = size;
}
