// One step of the adaptive photon traversal (Wyman & Nichols 2009 Sec. 3.2-4.2), shared by the
// compute path (adaptive_traverse.comp) and the transform-feedback kernels (adaptive_step.geom).
// A step takes the pending 2x2 clusters of level k (their photons on the (64 2^k)^2 grid over the
// photon frustum, Sec. 3.2: "we used a 64^2 grid for this coarse sampling") and for each:
// - discards it when it misses the refractor (Sec. 3.2.1 / 3.2.2, condition 1);
// - creates its four photons by deferred shading where they are needed: the geometry buffers
//   sampled at the photons' cell centres, traced by the same code as the dense photon buffer
//   (shared/trace_surface.glsl) with the cell's solid angle;
// - max-error metric (Sec. 3.2.2, condition 2), where tested: emits one photon for a cluster
//   whose photons converge to one caustic-map texel, with their summed power;
// - at the last level L (condition 2 of Sec. 3.2.1, condition 3 of Sec. 3.2.2) emits the
//   photons that landed; otherwise refines the cluster into four clusters of level k + 1, one
//   per photon, "generating new photons on a finer grid" at the next step.
//
// The miss test, a deviation from the paper: "all photons in the current 2x2 cluster miss the
// refractor" tests four points, and a thin part of the refractor between them would be lost
// with every photon below. Here a cluster is discarded only when no geometry-buffer texel that
// any of its photons or their descendants can sample is covered: a conservative max-mip query
// of the coverage pyramid (wyman_nichols2009/coverage.comp) over the cluster's footprint. The
// last level's photons are then exactly those a dense photon buffer at that resolution holds.
// Convergence is likewise tested only where it cannot drop power: all four photons land, and
// the refractor covers the whole footprint (so the one photon stands for all its descendants).
// With several refractors that holds for the first surface only: the four photons are followed
// through the further ones, but a descendant that a further refractor would turn elsewhere or
// lose (its silhouette inside the cluster) is not tested, as the paper's four-photon test does
// not test it either.
#ifndef ADAPTIVE_GLSL
#define ADAPTIVE_GLSL
#include "shared/trace_surface.glsl"   // bindings 0-4: frame, caustics, the back faces, receiver positions, spot textures
#include "wyman_nichols2009/adaptive_photon.glsl"
layout(binding = 5) uniform sampler2DArray geometry_position;  // front: position, d_N
layout(binding = 6) uniform sampler2DArray geometry_normal;    // front: normal, object + 1 (0: none)
layout(binding = 7) uniform sampler2DArray geometry_material;  // front: colour, mean ior (0: mirror)
layout(binding = 8) uniform sampler2D coverage;                // mip m: any (r) and all (g) covered below
// Several specular objects (REFRACTORS > 1): each one's own buffers from LAYER_BINDING on, and
// photons followed through them (Sec. 3.1.1 for photons, as deferred photons are).
#include "wyman_nichols2009/deferred_photon_layers.glsl"

// Mirrored by `AdaptiveConstants` in crates/caustics/src/gpu/push.rs.
layout(push_constant) uniform AdaptiveConstants {
    uint light;
    uint level;      // k: this step's photons lie on the (64 2^k)^2 grid
    uint finest;     // L: the last level (64 2^L = caustics.photons)
    uint converge;   // 1: test convergence at this step (max-error, from the 512^2 level on)
} constants;

// The coarse sampling's photons per side (Sec. 3.2, 4.2).
#define TOP_PHOTONS 64u

// Light-space texture coordinates of the centre of cell p of a grid of `side` cells.
vec2 cell_uv(uvec2 p, float side) { return (vec2(p) + 0.5) / side; }

// The cluster's footprint on the geometry buffers: (any, all) of the texels its photons and
// their descendants sample (the texels their cell centres lie in) covered by a front surface.
// The smallest pyramid level at which the footprint spans at most 2x2 texels answers for a
// superset of it (any: conservative; all: stricter than needed).
vec2 footprint_coverage(uvec3 c) {
    uint clusters = (TOP_PHOTONS / 2u) << c.z;
    uint g = uint(textureSize(geometry_normal, 0).x);
    uvec2 lo = (c.xy * g) / clusters;
    uvec2 hi = ((c.xy + 1u) * g - 1u) / clusters;
    uint m = 0u;
    while (any(greaterThan((hi >> m) - (lo >> m), uvec2(1u)))) m += 1u;
    vec2 result = vec2(0.0, 1.0);
    for (uint y = lo.y >> m; y <= hi.y >> m; ++y) {
        for (uint x = lo.x >> m; x <= hi.x >> m; ++x) {
            vec4 v = texelFetch(coverage, ivec2(x, y), int(m));
            result = vec2(max(result.x, v.r), min(result.y, v.g));
        }
    }
    return result;
}

struct Surface {
    vec3 position;
    vec3 normal;
    float thickness;
    SpecularMaterial material;
    uint object;   // the scene's index of the object
};

// Sec. 3.2: "geometry buffers store object positions and normals. Interpolating these
// quantities is straightforward, allowing dynamic sampling at arbitrary locations". The
// refractor at light-space texture coordinates uv: there is one when the texel uv lies in is
// covered; its position, normal and thickness are interpolated bilinearly among the 2x2 texels
// around uv that the same object covers (weights renormalised), its material is that texel's.
bool surface_at(vec2 uv, out Surface s) {
    int g = textureSize(geometry_normal, 0).x;
    vec2 t = uv * float(g);
    ivec2 c = clamp(ivec2(floor(t)), ivec2(0), ivec2(g - 1));
    vec4 here = texelFetch(geometry_normal, ivec3(c, 0), 0);
    s = Surface(vec3(0.0), vec3(0.0), 0.0, SpecularMaterial(0u, vec3(0.0), 0.0), 0u);
    if (here.w < 0.5) return false;
    s.object = uint(here.w) - 1u;
    vec4 m = texelFetch(geometry_material, ivec3(c, 0), 0);
    s.material = SpecularMaterial(m.a > 0.0 ? MATERIAL_REFRACTIVE : MATERIAL_REFLECTIVE, m.rgb, m.a);
    vec2 f = t - 0.5;
    ivec2 i0 = ivec2(floor(f));
    vec2 w = f - vec2(i0);
    vec4 position = vec4(0.0);
    vec3 normal = vec3(0.0);
    float total = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 q = i0 + o;
        float wk = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y);
        if (wk == 0.0 || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(g)))) continue;
        vec4 n = texelFetch(geometry_normal, ivec3(q, 0), 0);
        if (n.w != here.w) continue;    // no surface there, or another object's
        position += wk * texelFetch(geometry_position, ivec3(q, 0), 0);
        normal += wk * n.xyz;
        total += wk;
    }
    // The texel uv lies in weighs at least 1/4: total > 0.
    position /= total;
    s.position = position.xyz;
    s.thickness = position.w;
    s.normal = normalize(normal / total);
    return true;
}

// Photon p of level k (a cell of the (64 2^k)^2 grid), created by deferred shading (Sec. 3.2):
// traced from the surface at its cell's centre as the photon buffer's fragment there would be
// (shared/photon_buffer.frag), with its cell's solid angle, and on through the further
// refractors with several (deferred_photon_layers.glsl). False if it misses the refractor or
// does not land (total internal reflection, no receiver).
bool create_photon(uvec2 p, uint level, out AdaptivePhoton ph) {
    CausticLight cl = caustics.lights[constants.light];
    float side = float(TOP_PHOTONS << level);
    vec2 uv = cell_uv(p, side);
    ph = AdaptivePhoton(vec3(0.0), NO_CELL, vec3(0.0), 0.0);
    Surface s;
    if (!surface_at(uv, s)) return false;
    float omega = texel_solid_angle(uv * 2.0 - 1.0, vec4(cl.photon_plane.x, side, 0.0, 0.0));
    Photon t = trace_photon_through(constants.light, s.position, s.normal, s.thickness, omega, s.material);
#if REFRACTORS > 1
    t = through_further_refractors(constants.light, t, s.position, s.object);
#endif
    if (t.position.w < 0.5) return false;
    ph = AdaptivePhoton(t.position.xyz, pack_cell(uvec3(p, level)), t.power.rgb, 0.0);
    return true;
}

// Where photon `ph` lands in the light's caustic map, in texels; false behind the light.
bool photon_texel(AdaptivePhoton ph, out vec2 t) {
    return caustic_map_texel(caustics.lights[constants.light], ph.position, t);
}

// Photon i of cluster c: (2x + (i & 1), 2y + (i >> 1)) of level k.
uvec2 photon_of(uvec3 c, uint i) { return 2u * c.xy + uvec2(i & 1u, i >> 1u); }

// The cluster's four photons; returns the mask of those that landed.
uint cluster_photons(uvec3 c, out AdaptivePhoton p[4]) {
    uint landed = 0u;
    for (uint i = 0u; i < 4u; ++i) {
        if (create_photon(photon_of(c, i), c.z, p[i])) landed |= 1u << i;
    }
    return landed;
}

// Sec. 3.2.2, condition 2: "all photons in the cluster converge to a single caustic map
// texel" (on the map). Only where no power can be lost: all four landed and the cluster's
// footprint is all refractor.
bool converges(AdaptivePhoton p[4], uint landed, bool all_covered) {
    if (landed != 15u || !all_covered) return false;
    float m = caustics.lights[constants.light].caustic_plane.y;
    vec2 first = vec2(-1.0);
    for (int i = 0; i < 4; ++i) {
        vec2 t;
        if (!photon_texel(p[i], t)) return false;
        t = floor(t);
        if (any(lessThan(t, vec2(0.0))) || any(greaterThanEqual(t, vec2(m)))) return false;
        if (i > 0 && t != first) return false;
        first = t;
    }
    return true;
}

// "One photon is output with intensity based upon the solid angle of all cluster photons": the
// four photons' summed power (each its cell's solid angle's) at their mean position, as the
// cluster's cell (its parent at level k - 1). Its photons all landed in one caustic-map texel,
// so a varying splat gives it one texel, as Wyman 2008's converged clusters get.
AdaptivePhoton merged(uvec3 c, AdaptivePhoton p[4]) {
    bool sized = caustics.splat.w != SPLAT_FIXED;
    AdaptivePhoton m = AdaptivePhoton(vec3(0.0), pack_cell(uvec3(c.xy, c.z - 1u)), vec3(0.0), sized ? 1.0 : 0.0);
    for (int i = 0; i < 4; ++i) {
        m.position += 0.25 * p[i].position;
        m.power += p[i].power;
    }
    return m;
}

// Varying splats for the photons a last-level cluster outputs ("remaining noise is eliminated by
// rendering to a multi-resolution caustic map, splatting into lower resolution maps for
// diverging photons [WD08]", Sec. 3.2.2): each landed photon's footprint is Wyman 2008's
// max-distance radius (wyman2008/varying_splat.glsl), the largest caustic-map distance to its
// four adjacent photons on the same grid that landed. Two of them are its cluster's own; the
// other two belong to neighbouring clusters and are created here by deferred shading, as any
// photon can be (Sec. 4.3: "deferred shading allows computations in any order"). With geometry
// buffers as fine as the grid these are the dense photon buffer's neighbours, so the splats are
// those of the hierarchical caustic map's varying splats. Fixed splats: nothing to do.
void with_footprints(uvec3 c, inout AdaptivePhoton p[4], uint landed) {
    if (caustics.splat.w == SPLAT_FIXED) return;
    const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    int side = int(TOP_PHOTONS << c.z);
    for (uint i = 0u; i < 4u; ++i) {
        vec2 centre;
        if ((landed & (1u << i)) == 0u || !photon_texel(p[i], centre)) continue;
        ivec2 q = ivec2(photon_of(c, i));
        vec2 landed_at[4];
        uint neighbours = 0u;
        for (int k = 0; k < 4; ++k) {
            ivec2 n = q + offsets[k];
            ivec2 local = n - 2 * ivec2(c.xy);
            AdaptivePhoton a;
            if (all(greaterThanEqual(local, ivec2(0))) && all(lessThan(local, ivec2(2)))) {
                uint j = uint(local.x + 2 * local.y);    // a photon of this cluster
                if ((landed & (1u << j)) == 0u) continue;
                a = p[j];
            } else if (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, ivec2(side)))
                       || !create_photon(uvec2(n), c.z, a)) {
                continue;
            }
            if (photon_texel(a, landed_at[k])) neighbours |= 1u << uint(k);
        }
        p[i].footprint = max_distance_radius(centre, landed_at, neighbours);
    }
}
#endif
