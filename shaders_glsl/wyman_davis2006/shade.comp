// The eye-space caustics added to the final shading (Sec. 3.2.2 step 3): the diffuse radiance
// the caustic irradiance E_c adds, albedo / pi * E_c, onto the background the refractors look up.
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform image2D background;    // radiance, read and written
layout(binding = 1) uniform sampler2D albedo;               // rgb diffuse albedo, a = 1 on a surface
layout(binding = 2) uniform sampler2DArray caustic;         // rgb caustic irradiance (W/m^2)

const float PI = 3.14159265358979;

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, imageSize(background)))) return;
    vec4 a = texelFetch(albedo, t, 0);
    if (a.w < 0.5) return;
    vec3 e = texelFetch(caustic, ivec3(t, 0), 0).rgb;
    imageStore(background, t, imageLoad(background, t) + vec4(a.rgb / PI * e, 0.0));
}
