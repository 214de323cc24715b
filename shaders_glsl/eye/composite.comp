// The final image: refractors and reflectors over the diffuse background.
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D background_radiance;
layout(binding = 1) uniform sampler2D surface_radiance;
layout(binding = 2, rgba32f) uniform writeonly image2D final_image;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(final_image)))) return;
    vec4 s = texelFetch(surface_radiance, p, 0);
    vec4 b = texelFetch(background_radiance, p, 0);
    imageStore(final_image, p, vec4(s.a > 0.5 ? s.rgb : b.rgb, 1.0));
}
