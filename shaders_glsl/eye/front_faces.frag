// Refractive and reflective surfaces seen from the eye, shaded as they are rasterized: Wyman
// 2005's forward image-space refraction (eye/image_space_refraction.glsl), step 3 of Wyman &
// Nichols 2009 Fig. 3 (top). Hidden fragments are shaded too (overdraw).
#version 450
#include "common/frame.glsl"
#include "common/mesh_constants.glsl"
layout(binding = 1) uniform sampler2D background_radiance;
layout(binding = 2) uniform sampler2D background_position;
layout(binding = 3) uniform sampler2D back_faces;
#include "eye/image_space_refraction.glsl"
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in float v_thickness;
layout(location = 0) out vec4 o_radiance;

void main() {
    o_radiance = vec4(specular_radiance(v_world, v_normal, v_thickness), 1.0);
}
