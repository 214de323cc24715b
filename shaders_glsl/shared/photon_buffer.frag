// Wyman & Davis 2006 Sec. 3.1 / Shah's refractive vertex grid: the specular objects rendered
// from the light at N x N; every texel is a photon that refracts twice (or reflects) and lands
// on the first diffuse surface. Its power is the light's intensity times the texel's solid angle.
#version 450
#include "shared/trace.glsl"
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in float v_thickness;
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_direction;
layout(location = 2) out vec4 o_power;

void main() {
    uint l = mesh.light;
    CausticLight cl = caustics.lights[l];
    vec2 ndc = gl_FragCoord.xy / cl.photon_plane.y * 2.0 - 1.0;
    Photon ph = trace_photon(l, v_world, normalize(v_normal), v_thickness, texel_solid_angle(ndc, cl.photon_plane));
    o_position = ph.position;
    o_direction = ph.direction;
    o_power = ph.power;
}
