// The viewer's display image (crates/caustics/src/render/display.rs): the final image's linear
// radiance times the exposure, through the ACES fit and the sRGB curve, as 8-bit codes: the
// same arithmetic as final.png (image_io::write_png_tonemapped), so that the window shows what
// `render` writes. Scaled to the window by nearest texel; in split view the columns from `split`
// on come from render_b, with a one-pixel divider.
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D render_a;
layout(binding = 1) uniform sampler2D render_b;
layout(binding = 2, rgba8) uniform writeonly image2D display;
layout(push_constant) uniform DisplayConstants {
    float exposure;
    // The first column drawn from render_b (the display's width or more: none).
    uint split;
};

// Narkowicz's ACES fit (image_io::tonemap_aces), 1 from 1e6 on.
float aces(float x) {
    if (x >= 1.0e6) return 1.0;
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

float srgb_encode(float x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

// One channel to its 8-bit code over 255 (image_io::tonemap_to_srgb8); negative, NaN and
// infinite radiance are black, as in the PNG.
float code(float v) {
    if (isnan(v) || isinf(v) || !(v > 0.0)) return 0.0;
    float x = v * exposure;
    if (isinf(x)) x = 3.4028235e38;
    return clamp(round(srgb_encode(aces(x)) * 255.0), 0.0, 255.0) / 255.0;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(display);
    if (any(greaterThanEqual(p, size))) return;
    bool b = uint(p.x) >= split;
    ivec2 src_size = b ? textureSize(render_b, 0) : textureSize(render_a, 0);
    ivec2 s = min(ivec2((vec2(p) + 0.5) * vec2(src_size) / vec2(size)), src_size - 1);
    vec3 c = b ? texelFetch(render_b, s, 0).rgb : texelFetch(render_a, s, 0).rgb;
    vec3 rgb = vec3(code(c.r), code(c.g), code(c.b));
    if (uint(p.x) == split) rgb = vec3(1.0);
    imageStore(display, p, vec4(rgb, 1.0));
}
