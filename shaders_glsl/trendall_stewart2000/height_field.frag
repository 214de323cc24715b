#version 460
// Sec. 4.3: the height field, the sum of h(t, d) over every impulse and its wall reflections.
// The paper looks d up in a distance texture T and h in a colour table holding one row of
// h(t, .); here both are evaluated per texel. FAITHFUL stores h~ = 0.5 + h / (2 height_range).
#include "pass.glsl"

layout(location = 0) out vec4 out_height;

float wave_height(float t, float d) {
    float front = u.wave.z / u.wave.y * t;
    if (t <= 0.0 || d >= front) return 0.0;
    return u.wave.x * exp(-u.wave_damping.x * (front - d)) * exp(-u.wave.w * t) * sin(u.wave.y * d - u.wave.z * t);
}

void main() {
    ivec2 ij = grid_texel();
    vec2 p = -u.pool.w + (vec2(ij) + 0.5) * u.pool.z;
    float h = 0.0;
    for (uint s = 0; s < u.grid.w; s++) {
        vec4 src = u.sources[s];
        h += wave_height(src.z, distance(p, src.xy));
    }
#ifdef FAITHFUL
    out_height = vec4(adjust(h, u.enc_height_slope.x, u.enc_height_slope.y), 0.0, 0.0, 1.0);
#else
    out_height = vec4(h, 0.0, 0.0, 1.0);
#endif
}
