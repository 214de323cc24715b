#version 460
// The final render (the paper's Fig. 2, from above): each pixel's ray meets the water surface
// (the height field, two fixed-point steps), is split by the Fresnel equations into the sky it
// reflects and the ray it refracts (Snell, Pass 1's normals), which meets the bottom, lit by the
// caustic (E / E_flat times flat water's irradiance), or a wall, lit by the refracted light
// without caustics; extinction e^(-epsilon l) along the way. Around the pool a grey deck.
#include "pool.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D height_field;
layout(set = 0, binding = 2) uniform sampler2D normals;
layout(set = 0, binding = 3) uniform sampler2D receiver;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D final_image;

const float PI = 3.14159265358979;

vec2 grid_uv(vec2 xz) { return (xz + u.pool.w) / u.pool.x; }

float height_at(vec2 xz) {
    float h = texture(height_field, grid_uv(xz)).r;
    if (u.grid.z != 0u) h = unadjust(h, u.enc_height_slope.x, u.enc_height_slope.y);
    return h;
}

vec3 normal_at(vec2 xz) {
    vec3 n = texture(normals, grid_uv(xz)).xyz;
    if (u.grid.z != 0u) n = unadjust(vec4(n, 0.0), u.enc_normal_lo, u.enc_normal_span).xyz;
    return normalize(n);
}

// Unpolarised Fresnel reflectance from air (n_i) into water (n_t).
float reflectance(float ci) {
    float ni = u.optics.y, nt = u.optics.z, eta = u.optics.x;
    float ct = sqrt(max(0.0, 1.0 - eta * eta * (1.0 - ci * ci)));
    float rs = (ni * ci - nt * ct) / (ni * ci + nt * ct);
    float rp = (nt * ci - ni * ct) / (nt * ci + ni * ct);
    return 0.5 * (rs * rs + rp * rp);
}

// Tiles 0.1 m wide with darker grout, so that the refraction shows.
float tiles(vec2 xz) {
    vec2 f = abs(fract(xz / 0.1 + 0.5) - 0.5) * 0.1;
    return min(f.x, f.y) < 0.002 ? 0.75 : 1.0;
}

vec3 water(vec3 p, vec3 d) {
    float half_side = u.pool.w, depth = u.pool.y, albedo = u.medium.z;
    float t_bottom = (-depth - p.y) / d.y;
    vec3 b = p + t_bottom * d;
    if (all(lessThanEqual(abs(b.xz), vec2(half_side)))) {
        float ratio = texture(receiver, grid_uv(b.xz)).r;
        float e = ratio * u.view.z;
        return vec3(albedo * tiles(b.xz) / PI * e * exp(-u.medium.y * t_bottom));
    }
    // A wall: the nearest of x = +-half, z = +-half along d.
    vec2 t_walls = (sign(d.xz) * half_side - p.xz) / d.xz;
    float t_wall = min(t_walls.x, t_walls.y);
    vec3 w = p + t_wall * d;
    vec3 n_wall = t_walls.x < t_walls.y ? vec3(-sign(d.x), 0.0, 0.0) : vec3(0.0, 0.0, -sign(d.z));
    float lit = max(0.0, dot(-u.basis_z.xyz, n_wall));
    float e_wall = u.view.z * lit / max(1e-3, dot(-u.basis_z.xyz, vec3(0.0, 1.0, 0.0)));
    return vec3(albedo * tiles(w.xz + w.yy) / PI * e_wall * exp(-u.medium.y * t_wall));
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= int(u.view.x) || px.y >= int(u.view.y)) return;
    vec2 ndc = vec2(2.0 * (px.x + 0.5) / u.view.x - 1.0, 1.0 - 2.0 * (px.y + 0.5) / u.view.y);
    vec3 d = normalize(u.cam_forward.xyz + ndc.x * u.cam_right.w * u.cam_right.xyz + ndc.y * u.cam_up.w * u.cam_up.xyz);
    vec3 o = u.eye.xyz;
    vec3 radiance = u.sky.rgb;
    if (d.y < 0.0) {
        vec3 p = o + (-o.y / d.y) * d;
        if (all(lessThanEqual(abs(p.xz), vec2(u.pool.w)))) {
            for (int i = 0; i < 2; i++) {
                p = o + ((height_at(p.xz) - o.y) / d.y) * d;
                p.xz = clamp(p.xz, -u.pool.w, u.pool.w);
            }
            vec3 n = normal_at(p.xz);
            float ci = max(1e-4, dot(-d, n));
            float r = reflectance(ci);
            vec3 t = refract(d, n, u.optics.x);
            radiance = r * u.sky.rgb + (1.0 - r) * water(p, t);
        } else if (all(lessThanEqual(abs(p.xz), vec2(4.0 * u.pool.w)))) {
            float e_deck = u.light.w * max(0.0, -u.light.y);
            radiance = vec3(0.45 / PI * e_deck * tiles(p.xz * 0.5));
        }
    }
    imageStore(final_image, px, vec4(radiance, 1.0));
}
