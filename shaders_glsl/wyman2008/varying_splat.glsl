// Varying splat sizes (Wyman 2008 Sec. 3.3): a photon's splat radius, in caustic-map texels, from
// its adjacent photons in the photon buffer, which record how the specular objects spread or
// focused its beam. Two ways (caustics.settings.w, CAUSTIC_BEAM_AREA):
// - max-distance (the paper's choice, "beam area computations lack robustness"): the largest
//   distance in the caustic map from the photon to its four adjacent photons;
// - beam-area: Eq. 1-2 as written.
// Both measure the beam in the caustic map's own texels, and both give 1 texel at least.
// Clusters of converging photons (level > 0) land in one texel by construction: radius 1.
// Needs photon_position (shared/splat_photon.glsl) and common/caustics.glsl.
#ifndef VARYING_SPLAT_GLSL
#define VARYING_SPLAT_GLSL

// The valid photon at photon-buffer texel `q`, if there is one.
bool adjacent_photon(ivec2 q, out vec3 p) {
    int n = textureSize(photon_position, 0).x;
    p = vec3(0.0);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(n)))) return false;
    vec4 v = texelFetch(photon_position, q, 0);
    p = v.xyz;
    return v.w > 0.5;
}

// The approximation "based on the maximum distance between adjacent photons rather than area",
// over the photon buffer's four neighbours of texel `t`.
float photon_buffer_max_distance(ivec2 t, vec2 centre, CausticLight cl) {
    const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    vec2 landed_at[4];
    uint landed = 0u;
    for (int k = 0; k < 4; ++k) {
        vec3 p;
        if (adjacent_photon(t + offsets[k], p) && caustic_map_texel(cl, p, landed_at[k])) landed |= 1u << uint(k);
    }
    return max_distance_radius(centre, landed_at, landed);
}

// Eq. 1-2: photon p_i at distance d_i from the light stands for a beam of solid angle w_i (its
// photon-buffer texel). Unoccluded, the beam would light an area w_i d_i^2 / (N.D_i) of a
// surface of normal N hit from direction D_i; the adjacent photons span a quadrilateral of area
// A_i. In widths of the unoccluded beam the splat radius is r_i = sqrt(A_i (N.D_i) / (w_i d_i^2))
// (Eq. 2; Eq. 1 without the obliquity), and one such width is sqrt(w_i / w_c) caustic-map texels
// (w_c: the caustic-map texel's solid angle there). A_i (N.D_i) is the quadrilateral's area
// vector projected on D_i, the direction from the light (the unoccluded beam's). The paper takes
// the quadrilateral p_i p_j p_l p_k of one quadrant; the four quadrants' whose photons are all
// valid are averaged here, centring the estimate on p_i. w_i cancels: the radius is the square
// root of the quadrilateral's footprint in caustic-map texels (tests/varying_splats.rs checks
// both routes agree); it is kept to read as the paper's equation.
float beam_area_radius(ivec2 t, vec3 p, CausticLight cl) {
    vec3 to_p = p - cl.position.xyz;
    float d = length(to_p);
    vec3 dir = to_p / d;
    float area = 0.0;
    int quads = 0;
    for (int q = 0; q < 4; ++q) {
        ivec2 s = ivec2((q & 1) == 0 ? 1 : -1, (q & 2) == 0 ? 1 : -1);
        vec3 pj, pk, pl;
        if (!adjacent_photon(t + ivec2(s.x, 0), pj) || !adjacent_photon(t + ivec2(0, s.y), pk)
            || !adjacent_photon(t + s, pl)) continue;
        // The area vector of p_i p_j p_l p_k: half the cross product of its diagonals.
        area += abs(dot(0.5 * cross(pl - p, pk - pj), dir));
        quads += 1;
    }
    if (quads == 0) return 0.0;
    int n = textureSize(photon_position, 0).x;
    float w_i = texel_solid_angle((vec2(t) + 0.5) / float(n) * 2.0 - 1.0, cl.photon_plane);
    float r_i = sqrt(area / float(quads) / (w_i * d * d));
    vec2 ndc;
    caustic_map_ndc(cl, p, ndc);
    float w_c = texel_solid_angle(ndc, cl.caustic_plane);
    return r_i * sqrt(w_i / w_c);
}

// The splat radius of `entry` (at `p`, landing at `centre` in the caustic map).
float varying_radius(uvec4 entry, vec3 p, vec2 centre, CausticLight cl) {
    if (entry.z != 0u) return 1.0;
    ivec2 t = ivec2(entry.xy);
    float r = (caustics.settings.w & CAUSTIC_BEAM_AREA) != 0u ? beam_area_radius(t, p, cl)
                                                              : photon_buffer_max_distance(t, centre, cl);
    return max(r, 1.0);
}
#endif
