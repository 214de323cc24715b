// Diffuse surfaces seen from the eye: Lambertian radiance L = albedo / pi * E, with E the
// physically scaled irradiance from every light (I cos(theta) / r^2) where the shadow map
// says the light is visible, plus the caustic irradiance from the caustic maps. Also writes the geometry buffer that refraction looks up.
#version 450
#define SHADOW_BINDING 1
#define SPOT_BINDING 2
#define CAUSTICS_BINDING 3
#define CAUSTIC_MAP_BINDING 4
#define RECEIVER_POSITIONS_BINDING 5
#include "common/lighting.glsl"
#include "common/caustic_lookup.glsl"
#include "common/mesh_constants.glsl"
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in float v_thickness;
layout(location = 0) out vec4 o_radiance;
layout(location = 1) out vec4 o_position;   // xyz world, w = 1 where a surface was hit
layout(location = 2) out vec4 o_normal;     // xyz world normal facing the eye, w window depth
layout(location = 3) out vec4 o_albedo;     // rgb diffuse albedo, w = 1 where a surface was hit

const float PI = 3.14159265358979;

void main() {
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    vec3 e = direct_irradiance(v_world, n);
    // Eye-space caustics (Wyman & Davis 2006) are added after this pass, from the eye's view.
    if ((caustics.settings.w & CAUSTIC_EYE_SPACE) == 0u) e += caustic_irradiance(v_world, n);
    o_radiance = vec4(mesh.colour.rgb / PI * e, 1.0);
    o_position = vec4(v_world, 1.0);
    o_normal = vec4(n, gl_FragCoord.z);   // w: window depth, for the deferred refraction's depth test
    o_albedo = vec4(mesh.colour.rgb, 1.0);
}
