// The `splats` dump of hcm: each entry of the traversal's final list as the splat passes
// (shared/splat.vert, splat.comp) splat it, from the same shared/splat_photon.glsl: where it
// lands, its radius and layer, its power. Three vec4 per entry:
// - (centre x, centre y, radius, layer), centre and radius in texels of the base caustic map
//   (the layer holds the splat at 1/2^layer of both; radius 0: all in the nearest texel);
// - (power rgb, photons);
// - (splatted, 0, 0, 0): 1 when drawn. An entry that is not drawn keeps what is known of it: a
//   varying splat too wide for the last map level has the level it would need (4 or more),
//   one centred off the map its centre; one behind the light is all zeros.
#version 450
#define CAUSTICS_BINDING 1
#define HIERARCHY 1
#include "common/caustics.glsl"
#include "shared/splat_photon.glsl"
layout(local_size_x = 64) in;
// Mirrored by `FootprintConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform FootprintConstants {
    uint entries;   // in the final list
    uint light;
} constants;
layout(std430, binding = 6) readonly buffer Entries { uint entries[]; };   // packed (hierarchy/entry.glsl)
layout(std430, binding = 7) writeonly buffer Footprints { vec4 footprints[]; };

void main() {
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
    if (i >= constants.entries) return;
    uvec4 entry = unpack_entry(entries[i]);
    vec4 pos;
    vec3 power;
    Splat s;
    photon_of_entry(entry, pos, power);
    bool splatted = splat_of(pos, power, entry, caustics.lights[constants.light], s);
    float scale = exp2(float(s.layer));
    footprints[3u * i] = vec4(s.centre * scale, max(s.radius, 0.0) * scale, float(s.layer));
    footprints[3u * i + 1u] = vec4(power, pos.w);
    footprints[3u * i + 2u] = vec4(splatted ? 1.0 : 0.0, 0.0, 0.0, 0.0);
}
