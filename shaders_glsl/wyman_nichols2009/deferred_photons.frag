// Deferred caustic maps (Wyman & Nichols 2009 Sec. 3.2, Fig. 10's "dense photon buffer with a
// deferred renderpass"): the dense photon buffer written by one full-screen pass over the
// light-space geometry buffers (wyman_nichols2009/light_geometry.*) instead of by rasterizing the
// specular objects' front faces (shared/photon_buffer.frag). Texel t of the photon buffer reads
// texel t of the geometry buffers, which hold exactly the interpolants the forward pass's
// fragment at t traced from, and is traced by the same code (shared/trace.glsl): same texel,
// same photon.
//
// With several specular objects (REFRACTORS > 1), Sec. 3.1.1's multi-layer refraction applied to
// photons ("caustics from more than two refractive interfaces, using multi-layered deferred
// refraction when rendering photons", Sec. 5, Fig. 13): see deferred_photon_layers.glsl.
#version 450
#include "shared/trace.glsl"   // bindings 0-4: frame, caustics, back faces, receiver positions, spot textures; MeshConstants (light)
// All specular objects as the forward pass sees them (the first surface each photon meets).
layout(binding = 5) uniform sampler2DArray surface_position;  // front: position, d_N
layout(binding = 6) uniform sampler2DArray surface_normal;    // front: normal, object + 1 (0: none)
layout(binding = 7) uniform sampler2DArray surface_material;  // front: colour, mean ior (0: mirror)
#include "wyman_nichols2009/deferred_photon_layers.glsl"
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_direction;
layout(location = 2) out vec4 o_power;

void main() {
    uint l = mesh.light;
    CausticLight cl = caustics.lights[l];
    ivec2 t = ivec2(gl_FragCoord.xy);
    vec4 normal = texelFetch(surface_normal, ivec3(t, 0), 0);
    o_position = vec4(0.0);
    o_direction = vec4(0.0);
    o_power = vec4(0.0);
    if (normal.w < 0.5) return;   // no specular surface: no photon (the forward pass's clear)
    vec4 position = texelFetch(surface_position, ivec3(t, 0), 0);
    vec4 m = texelFetch(surface_material, ivec3(t, 0), 0);
    SpecularMaterial material = SpecularMaterial(m.a > 0.0 ? MATERIAL_REFRACTIVE : MATERIAL_REFLECTIVE, m.rgb, m.a);
    vec2 ndc = gl_FragCoord.xy / cl.photon_plane.y * 2.0 - 1.0;
    float omega = texel_solid_angle(ndc, cl.photon_plane);
    Photon ph = trace_photon_through(l, position.xyz, normalize(normal.xyz), position.w, omega, material);
#if REFRACTORS > 1
    ph = through_further_refractors(l, ph, position.xyz, uint(normal.w) - 1u);
#endif
    o_position = ph.position;
    o_direction = ph.direction;
    o_power = ph.power;
}
