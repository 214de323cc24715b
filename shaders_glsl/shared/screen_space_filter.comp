// Screen-space photon mapping (Kim 2019, Ray Tracing Gems ch. 30): the photons drawn into a
// view's pixels (wyman_davis2006/photons.frag, each pixel q's power Phi_q), then their density
// estimated on the view's geometry buffer with an edge-aware kernel, in two passes:
//   NORMALIZE: for each photon pixel q, its kernel's radius r_q and support,
//              N_q = sum_t w_q(t) A_t over the pixels t within r_q that q is joined to
//              (A_t: pixel t's world area), and Phi_q / N_q;
//   otherwise: the gather, E_t = sum_q w_q(t) Phi_q / N_q over the pixels q joined to t
//              within their r_q (W/m^2).
// Each photon pixel's kernel is normalised over its own support, so sum_t E_t A_t = sum_q Phi_q:
// the filter keeps the photons' power exactly, whatever the radii (the splats' normalisation),
// wherever a photon pixel's support has an area. Where it has none (a surface one pixel wide,
// whose area the neighbouring positions cannot give: pixel_area.glsl) the pixel's photons are
// dropped.
//
// The kernel: a Gaussian of the pixel offset, sigma = r_q / 2, nothing beyond r_q (r_q = 0: the
// pixel alone), times the edge tests, which are 0 or 1 and symmetric in t and q:
//   - both pixels see a surface;
//   - each lies within `tolerance` of the other's tangent plane, |n_t . (x_q - x_t)| and
//     |n_q . (x_t - x_q)|, with tolerance = tolerance.x * (the nearer one's distance to the
//     eye; 0 in an orthographic view) + tolerance.y: a depth edge;
//   - their normals are within acos(cos_normal) of each other: a crease.
// The radius adapts to the photons' density, as photon mapping's k nearest photons do: r_q is
// the least radius (0..max_radius pixels) whose joined pixels hold `photons_per_kernel` photons,
// max_radius where none does. A caustic is never carried across a depth edge or a crease
// (tests/photon_trace_screen_space.rs renders a scene made for it).
#version 450
#include "shared/pixel_area.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

// Mirrored by `ScreenSpaceConstants` in crates/caustics/src/techniques/shared/screen_space.rs.
layout(push_constant) uniform ScreenSpaceConstants {
    vec4 eye;          // xyz: the view's eye, w: 1 for an orthographic view
    vec4 tolerance;    // x: of the distance to the eye, y: metres (the depth-edge test)
    uint max_radius;   // the largest kernel radius in pixels (at most MAX_RADIUS)
    uint slot;         // the photon layer this light's photons were drawn into
    uint light;        // lights after the first add to the view's caustic
    float cos_normal;  // the crease test's least cosine between normals
    float photons_per_kernel;   // the photons a kernel's radius is grown to hold
} constants;

const int MAX_RADIUS = 8;

layout(binding = 0) uniform sampler2DArray photons;   // rgb power (W), a: photons
layout(binding = 1) uniform sampler2D view_position;  // xyz world, w = 1 on a surface
layout(binding = 2) uniform sampler2D view_normal;
#ifdef NORMALIZE
layout(binding = 3, rgba32f) uniform writeonly image2D normalized;   // rgb Phi_q / N_q, a: r_q
#else
layout(binding = 3) uniform sampler2D normalized;
layout(binding = 4, rgba32f) uniform image2DArray gathered;   // rgb E (W/m^2), a: photon pixels (not photons) reaching it
#endif

float depth_of(vec3 p) {
    return constants.eye.w > 0.5 ? 0.0 : distance(p, constants.eye.xyz);
}

// The edge tests between pixels t and q (both on a surface).
bool joined(vec3 pt, vec3 nt, vec3 pq, vec3 nq) {
    float tol = constants.tolerance.x * min(depth_of(pt), depth_of(pq)) + constants.tolerance.y;
    bool plane = abs(dot(nt, pq - pt)) <= tol && abs(dot(nq, pt - pq)) <= tol;
    return plane && dot(nt, nq) >= constants.cos_normal;
}

// The kernel of radius r at an offset of d pixels (r = 0: the pixel alone).
float kernel(float d, float r) {
    if (d > r) return 0.0;
    if (r == 0.0) return 1.0;
    float sigma = 0.5 * r;
    return exp(-0.5 * d * d / (sigma * sigma));
}

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(view_position, 0);
    if (any(greaterThanEqual(t, size))) return;
    int r = min(int(constants.max_radius), MAX_RADIUS);
    vec4 surface = texelFetch(view_position, t, 0);
    vec3 n = texelFetch(view_normal, t, 0).xyz;
#ifdef NORMALIZE
    vec4 own = texelFetch(photons, ivec3(t, int(constants.slot)), 0);
    if (own.a == 0.0 || surface.w < 0.5) {
        imageStore(normalized, t, vec4(0.0));
        return;
    }
    // The photons of the joined pixels at each whole distance (ceil) from t, then the least
    // radius whose disc holds photons_per_kernel of them.
    float ring[MAX_RADIUS + 1];
    for (int k = 0; k <= MAX_RADIUS; ++k) ring[k] = 0.0;
#else
    if (surface.w < 0.5) {
        if (constants.light == 0u) imageStore(gathered, ivec3(t, 0), vec4(0.0));
        return;
    }
    vec4 sum = vec4(0.0);
#endif
    for (int y = -r; y <= r; ++y) {
        for (int x = -r; x <= r; ++x) {
            ivec2 q = t + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            float d = length(vec2(x, y));
            if (d > float(r)) continue;
            vec4 other = texelFetch(view_position, q, 0);
            if (other.w < 0.5 || !joined(surface.xyz, n, other.xyz, texelFetch(view_normal, q, 0).xyz)) continue;
#ifdef NORMALIZE
            ring[int(ceil(d))] += texelFetch(photons, ivec3(q, int(constants.slot)), 0).a;
#else
            vec4 photon = texelFetch(normalized, q, 0);   // rgb Phi_q / N_q, a: r_q
            float w = kernel(d, photon.a);
            sum += vec4(w * photon.rgb, w > 0.0 && photon.rgb != vec3(0.0) ? 1.0 : 0.0);
#endif
        }
    }
#ifdef NORMALIZE
    int radius = r;
    float held = 0.0;
    for (int k = 0; k <= r; ++k) {
        held += ring[k];
        if (held >= constants.photons_per_kernel) {
            radius = k;
            break;
        }
    }
    float support = 0.0;
    for (int y = -radius; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) {
            ivec2 q = t + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            float w = kernel(length(vec2(x, y)), float(radius));
            vec4 other = texelFetch(view_position, q, 0);
            if (w == 0.0 || other.w < 0.5) continue;
            if (!joined(surface.xyz, n, other.xyz, texelFetch(view_normal, q, 0).xyz)) continue;
            support += w * pixel_area(view_position, q, other.xyz);
        }
    }
    imageStore(normalized, t, support > 0.0 ? vec4(own.rgb / support, float(radius)) : vec4(0.0));
#else
    if (constants.light > 0u) sum += imageLoad(gathered, ivec3(t, 0));
    imageStore(gathered, ivec3(t, 0), sum);
#endif
}
