// Caustic irradiance at a receiver point from the caustic maps (needs CAUSTICS_BINDING,
// CAUSTIC_MAP_BINDING and RECEIVER_POSITIONS_BINDING). A caustic-map texel holds the power
// (W) of the photons splatted into it; the texel covers solid angle w from the light, i.e.
// area A = w d^2 / cos(theta) on the receiver (Wyman & Davis 2006, Eq. 5-8), so
// E = power cos(theta) / (w d^2). A point receives a texel's light only if it is the first
// diffuse surface the light sees there (the receiver-positions map, `on_first_surface`), like a
// shadow map. With CAUSTIC_TUTORIAL_LOOKUP (`lookup = "tutorial"`), the caustics mapping
// tutorial's lookup instead (`tutorial_lookup`).
#ifndef CAUSTIC_LOOKUP_GLSL
#define CAUSTIC_LOOKUP_GLSL
#include "common/caustics.glsl"
#include "common/lighting.glsl"
layout(binding = CAUSTIC_MAP_BINDING) uniform sampler2DArray caustic_map;
layout(binding = RECEIVER_POSITIONS_BINDING) uniform sampler2DArray receiver_positions;

// Power of base-resolution texel `texel` of light `l`. With the multi-resolution map, Eq. 3 of
// Wyman 2008: C = sum_i C_i / 4^i, level i holding its splats in the corner (M/2^i)^2 of layer
// 4l + i. A coarse level is read as a mipmap level is, bilinearly at the base texel's centre
// (clamped to the level's corner): each level-i texel's power spreads over the base texels
// around it with tent weights that sum to 4^i, so the sum conserves power, and the coarse
// levels add no 2^i-texel blocks to the caustic.
vec3 caustic_level(ivec2 texel, int layer, uint i, float size) {
    float scale = float(1u << i);
    // The corner holds ceil(M / 2^i) texels a side: with M not a multiple of 2^i the last one
    // straddles the map's edge and still holds power.
    int last = int(ceil(size / scale)) - 1;
    vec2 u = (vec2(texel) + 0.5) / scale - 0.5;
    ivec2 t0 = ivec2(floor(u));
    vec2 f = u - vec2(t0);
    ivec2 a = clamp(t0, ivec2(0), ivec2(last));
    ivec2 b = clamp(t0 + 1, ivec2(0), ivec2(last));
    vec3 c00 = texelFetch(caustic_map, ivec3(a.x, a.y, layer), 0).rgb;
    vec3 c10 = texelFetch(caustic_map, ivec3(b.x, a.y, layer), 0).rgb;
    vec3 c01 = texelFetch(caustic_map, ivec3(a.x, b.y, layer), 0).rgb;
    vec3 c11 = texelFetch(caustic_map, ivec3(b.x, b.y, layer), 0).rgb;
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

// Interpolated splats (Wyman 2008 Fig. 7's third column, Wyman & Dachsbacher's multiple splat
// sizes): layer 4l + i holds every photon splatted at radius r_i = splat.x * 2^i, its alpha the
// photons per texel. Like a k-nearest-neighbour estimate, a texel reads the smallest radius that
// gathers INTERPOLATED_PHOTONS photons: n_i = alpha_i * pi r_i^2 photons fall within r_i of it;
// between the two radii whose n_i bracket that count the power is interpolated (linearly in
// log n, so halfway in log count between them is halfway between the layers); below it at the
// largest radius, the largest radius's. Each layer holds every photon's whole power, so the
// estimate keeps the caustic's power where the chosen radius changes slowly. (Reconstructed
// from the description in Wyman 2008 Sec. 3.3 and Wyman & Dachsbacher's abstract: a
// variable-radius estimate from four splat sizes; the selection rule is ours.)
vec3 interpolated_power(ivec2 texel, uint l) {
    vec4 below = vec4(0.0);
    float n_below = 0.0;
    for (uint i = 0u; i < INTERPOLATED_LEVELS; ++i) {
        vec4 c = texelFetch(caustic_map, ivec3(texel, int(l * INTERPOLATED_LEVELS + i)), 0);
        float r = caustics.splat.x * float(1u << i);
        float n = c.a * 3.14159265 * r * r;
        if (n >= INTERPOLATED_PHOTONS || i + 1u == INTERPOLATED_LEVELS) {
            if (i == 0u || n < INTERPOLATED_PHOTONS || n_below <= 0.0) return c.rgb;
            float t = log(INTERPOLATED_PHOTONS / n_below) / log(n / n_below);
            return mix(below.rgb, c.rgb, clamp(t, 0.0, 1.0));
        }
        below = c;
        n_below = n;
    }
    return below.rgb;
}

vec3 caustic_power(ivec2 texel, uint l, float size) {
    if (caustics.splat.w == SPLAT_INTERPOLATED) return interpolated_power(texel, l);
    if (caustics.splat.w != SPLAT_VARYING_MULTIRES) {
        return texelFetch(caustic_map, ivec3(texel, int(l)), 0).rgb;
    }
    vec3 c = texelFetch(caustic_map, ivec3(texel, int(l * MULTIRES_LEVELS)), 0).rgb;
    for (uint i = 1u; i < MULTIRES_LEVELS; ++i) {
        int layer = int(l * MULTIRES_LEVELS + i);
        c += caustic_level(texel, layer, i, size) / float(1u << (2u * i));
    }
    return c;
}

// Whether `first` (a receiver-positions texel: the first diffuse surface the light sees there,
// rasterized at the texel's centre) is the surface point `p` lies on, `p` being `d` from the
// light with its normal at `cos_theta` to it. The texel spans sqrt(w) d across (w its solid
// angle), up to that over cos_theta along a tilted surface: two of those (and `reach`, how far
// the points `p` stands for spread: half a receiver texel's diagonal for an averaged lookup) is
// "the same surface". An occluder standing on the receiver is then not lit through: with a
// tolerance of 2% of the light's distance (before), a light 20 m up lit the floor under a 10 cm
// block in `underwater.toml`.
bool on_first_surface(vec4 first, vec3 p, float d, float w, float cos_theta, float reach) {
    float across = sqrt(w) * d;
    return first.w >= 0.5 && distance(first.xyz, p) <= reach + 2.0 * across / max(cos_theta, 0.1);
}

// The irradiance base-resolution texel `texel` of light `l`'s caustic map gives point `p` (`d`
// from the light, its normal at `cos_theta` to it), or none where `p` is not on the first
// surface the light sees there (`reach`: see `on_first_surface`).
vec3 texel_irradiance(CausticLight cl, uint l, ivec2 texel, vec3 p, float d, float cos_theta, float reach) {
    vec4 first = texelFetch(receiver_positions, ivec3(texel, int(l)), 0);
    vec2 centre = (vec2(texel) + 0.5) / cl.caustic_plane.y * 2.0 - 1.0;
    float w = texel_solid_angle(centre, cl.caustic_plane);
    if (!on_first_surface(first, p, d, w, cos_theta, reach)) return vec3(0.0);
    return caustic_power(texel, l, cl.caustic_plane.y) * cos_theta / (w * d * d);
}

// The light that caustic irradiance `e` from light `l` at `p` (normal `n`) adds. Physical: `e`.
// The tutorial's lookup (its get_caustics and psDiffuse): the Lambert term of the light, unshadowed,
// times pow(c, 1.3), c the caustic map's value. The tutorial's map holds 1000 * (4 / g_ppRes) per
// photon (a light intensity over the grid's resolution), a scale with no unit tuned by sliders; here c is e over the light's
// unoccluded irradiance E0, the light-space concentration P / (w I) (a texel's power over the
// power the light sends through its solid angle w directly), which is 1 where the caustic is as
// bright as the light unrefracted: the physical lookup is E0 c, the tutorial's E0 pow(c, 1.3).
vec3 tutorial_lookup(uint l, vec3 e, vec3 p, vec3 n) {
    vec3 e0 = unoccluded_irradiance(l, p, n);
    vec3 c = vec3(e0.r > 0.0 ? e.r / e0.r : 0.0, e0.g > 0.0 ? e.g / e0.g : 0.0, e0.b > 0.0 ? e.b / e0.b : 0.0);
    return e0 * pow(c, vec3(1.3));
}

vec3 looked_up(uint l, vec3 e, vec3 p, vec3 n) {
    return (caustics.settings.w & CAUSTIC_TUTORIAL_LOOKUP) != 0u ? tutorial_lookup(l, e, p, n) : e;
}

vec3 caustic_irradiance(vec3 p, vec3 n) {
    vec3 e = vec3(0.0);
    for (uint l = 0u; l < caustics.settings.x; ++l) {
        CausticLight cl = caustics.lights[l];
        vec2 ndc;
        if (!caustic_map_ndc(cl, p, ndc)) continue;
        if (any(greaterThan(abs(ndc), vec2(1.0)))) continue;
        ivec2 texel = ivec2(clamp((ndc * 0.5 + 0.5) * cl.caustic_plane.y, vec2(0.0), vec2(cl.caustic_plane.y - 1.0)));
        vec3 to_light = cl.position.xyz - p;
        float d = length(to_light);
        float cos_theta = max(dot(n, to_light / d), 0.0);
        e += looked_up(l, texel_irradiance(cl, l, texel, p, d, cos_theta, 0.0), p, n);
    }
    return e;
}

// Area of the convex quadrilateral `q` (either winding) clipped to the rectangle [lo, hi], by
// Sutherland-Hodgman against its four sides.
float area_in_rect(vec2 q[4], vec2 lo, vec2 hi) {
    vec2 a[8];
    vec2 b[8];
    for (int k = 0; k < 4; ++k) a[k] = q[k];
    int n = 4;
    for (int side = 0; side < 4; ++side) {
        int axis = side & 1;
        float bound = side < 2 ? lo[axis] : hi[axis];
        float keep = side < 2 ? 1.0 : -1.0;  // inside: keep * (x - bound) >= 0
        int m = 0;
        for (int k = 0; k < n; ++k) {
            vec2 s = a[k];
            vec2 e = a[(k + 1) % n];
            float ds = keep * (s[axis] - bound);
            float de = keep * (e[axis] - bound);
            if (ds >= 0.0 && m < 8) b[m++] = s;
            if ((ds >= 0.0) != (de >= 0.0) && m < 8) b[m++] = mix(s, e, ds / (ds - de));
        }
        n = m;
        for (int k = 0; k < n; ++k) a[k] = b[k];
        if (n < 3) return 0.0;
    }
    float twice = 0.0;
    for (int k = 0; k < n; ++k) {
        vec2 s = a[k];
        vec2 e = a[(k + 1) % n];
        twice += s.x * e.y - e.x * s.y;
    }
    return 0.5 * abs(twice);
}

// The caustic irradiance averaged over the receiver-map texel centred on `p` and spanned by
// `half_u`, `half_v` (half its sides), what the exact reference estimates for the texel.
// `caustic_irradiance` at the texel's centre is a point sample of a map whose irradiance is
// constant over each caustic-map texel's footprint: where the two grids' texels are of like
// size, the sum of point samples aliases (on `sphere_on_plane`, whose focus lies on both grids'
// centre lines, the caustic flux swung from 0.93 to 1.05 of the reference's as the receiver
// grid moved by half a texel). Here each caustic-map texel adds its irradiance weighted by the
// share of the receiver texel it covers: the receiver texel's corners project to a quadrilateral
// in the caustic map (a perspective projection keeps edges straight) and each texel's share is
// its area inside that quadrilateral. A receiver texel inside one caustic-map texel gets what
// `caustic_irradiance` gives at its centre; summed over the receiver grid, every caustic-map
// texel inside it gives back its power. Up to MAX_TEXELS_ACROSS texels a side are read (a
// bounded loop): a map so much finer than the receiver grid is averaged over the receiver
// texel's central MAX_TEXELS_ACROSS² texels, whose mean stands for the whole texel's, an
// approximation (on sphere_on_plane with a 16² receiver map and a 2048² caustic map, 83 texels
// a side, the caustic flux read 0.75 of the reference's): make the receiver map finer.
#define MAX_TEXELS_ACROSS 48
vec3 caustic_irradiance_over(vec3 p, vec3 half_u, vec3 half_v, vec3 n) {
    vec3 e = vec3(0.0);
    for (uint l = 0u; l < caustics.settings.x; ++l) {
        CausticLight cl = caustics.lights[l];
        float size = cl.caustic_plane.y;
        vec2 q[4];
        vec3 corners[4] = vec3[4](p - half_u - half_v, p + half_u - half_v, p + half_u + half_v, p - half_u + half_v);
        bool in_front = true;
        for (int k = 0; k < 4; ++k) in_front = caustic_map_texel(cl, corners[k], q[k]) && in_front;
        if (!in_front) continue;
        vec2 lo = min(min(q[0], q[1]), min(q[2], q[3]));
        vec2 hi = max(max(q[0], q[1]), max(q[2], q[3]));
        float quad_area = 0.5 * abs((q[2].x - q[0].x) * (q[3].y - q[1].y) - (q[3].x - q[1].x) * (q[2].y - q[0].y));
        if (quad_area <= 0.0) continue;
        vec2 mid = 0.5 * (lo + hi);
        ivec2 t0 = ivec2(max(floor(max(lo, mid - 0.5 * float(MAX_TEXELS_ACROSS))), vec2(0.0)));
        ivec2 t1 = ivec2(min(floor(min(hi, mid + 0.5 * float(MAX_TEXELS_ACROSS) - 1.0)), vec2(size - 1.0)));
        vec3 to_light = cl.position.xyz - p;
        float d = length(to_light);
        float cos_theta = max(dot(n, to_light / d), 0.0);
        // Where the texels read do not cover the quadrilateral's part inside the map (more than
        // MAX_TEXELS_ACROSS a side), their shares are scaled up to it.
        float inside = area_in_rect(q, vec2(0.0), vec2(size));
        float read = area_in_rect(q, vec2(t0), vec2(t1 + 1));
        float scale = read > 0.0 ? inside / read : 0.0;
        float reach = length(half_u + half_v);
        vec3 el = vec3(0.0);
        for (int y = t0.y; y <= t1.y; ++y) {
            for (int x = t0.x; x <= t1.x; ++x) {
                float share = area_in_rect(q, vec2(x, y), vec2(x + 1, y + 1)) / quad_area;
                if (share > 0.0) el += share * texel_irradiance(cl, l, ivec2(x, y), p, d, cos_theta, reach);
            }
        }
        e += looked_up(l, el * scale, p, n);
    }
    return e;
}
#endif
