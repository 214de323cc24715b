// Wyman & Davis 2006 Sec. 3.2.1: caustic quads. Every 2x2 block of adjacent photons of the
// photon buffer is a polygon P between where they land, drawn as two triangles (six vertices,
// each fetching the block's four photons). The polygon carries the ratio R = w_B / w_P (Eq. 1-2):
// w_B the solid angle of the beam between the four photons as the light emits it (precomputed
// for the photon buffer: one texel's), w_P the solid angle P subtends from the light,
// approximated as the paper does by the area of the polygon whose vertices are P's projected on
// the unit sphere about the light: the areas of its two triangles as they are drawn, so that a
// polygon folded over itself at a caustic (a bow tie) spreads its beam over what it covers.
//
// Culled (all six vertices outside the view): blocks with a photon that did not land (it
// missed the specular object, was lost to total internal reflection or found no receiver), and
// blocks that stretch between different surfaces, tested as: the centre of the four landing
// points is not on the surface the light sees in its direction: its distance from the light
// differs from that of the light's receiver-positions map there by more than 5% of the
// polygon's longer diagonal plus 2% of the distance (the map's texels are coarse). Between two
// points of one plane (or of a smooth surface, for a small polygon) the centre lies on it;
// between a floor and a wall it hangs in the air, in front of what the light sees.
//
// Polygons smaller than a pixel (QUAD_POINTS). Drawn as triangles, a polygon whose projection
// covers less than one pixel is hit or missed whole by the rasterizer (no conservative
// rasterization on every device), and one focused near a caustic carries R in the hundreds:
// the pixels it happens to hit burn and its neighbours get nothing. Such a polygon is therefore
// not drawn as triangles here but, by the QUAD_POINTS variant (one vertex per block), as one
// point at its centre carrying its beam's whole power I w_B, which quads.frag spreads over the
// pixel's area: the power is then exact, and R (Eq. 1-4) still defines the irradiance of every
// polygon the rasterizer can resolve.
//
// Slivers (QUAD_LINES). Next to a caustic the polygons fold into slivers: a pixel or more long
// but less than one wide. The rasterizer hits or misses each along its length, and along a
// caustic curve that runs parallel to the pixel grid (the coffee-cup caustic seen from straight
// above) every sliver hits the same column of pixel centres or none does: the column burns
// (eye-space quads read 2.5x the reference's caustic flux on ring_cardioid). A polygon of a
// pixel or more whose width (area over its longest edge) is under a pixel is therefore drawn by
// the QUAD_LINES variant as a line along its longer diagonal carrying its beam's whole power,
// shared evenly by the fragments the line produces (one per pixel along its major axis).
// The three variants split the blocks between them by the same tests, so each block is drawn
// exactly once.
//
// QUAD_POLYGONS (`quad_draw = "polygons"`): the paper's way, every block as its two triangles
// whatever its size (only a polygon of no solid angle, whose R is infinite, is not drawn), the
// points and lines not drawn at all; the error of its hit-or-miss polygons is what the quality
// table measures beside the exact variant.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "wyman_davis2006/image_space.glsl"
layout(binding = 2) uniform sampler2D photon_position;
layout(binding = 3) uniform sampler2D photon_direction;
layout(binding = 4) uniform sampler2D photon_power;
layout(binding = 5) uniform sampler2D view_position;        // the view's (eye space): its size
layout(binding = 7) uniform sampler2D receiver_positions;   // light l's first diffuse surfaces
layout(location = 0) out vec3 v_position;
layout(location = 1) out vec3 v_direction;
layout(location = 2) flat out vec3 v_intensity;   // R * mean(Phi_k / w_k): W/sr the polygon carries; QUAD_POINTS: its power I w_B (W)

// Corners of the two triangles of a block: (0,0) (1,0) (1,1) and (0,0) (1,1) (0,1).
const ivec2 CORNERS[6] = ivec2[](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
const ivec2 BLOCK[4] = ivec2[](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 1));

// Below this many pixels of projected area a polygon is a point (see above).
const float SMALL_QUAD_PIXELS = 1.0;

vec4 to_clip(vec3 p) {
#ifdef LIGHT_SPACE
    return caustics.lights[constants.light].caustic_view_proj * vec4(p, 1.0);
#else
    return constants.view_proj * vec4(p, 1.0);
#endif
}

// The area, in the view's pixels, of the block's two triangles as the rasterizer gets them,
// and (`width`) that area over the polygon's longest edge: how wide a sliver it is. Infinite
// when a corner is behind the view (clipping will resolve it).
vec2 view_size() {
#ifdef LIGHT_SPACE
    return vec2(caustics.lights[constants.light].caustic_plane.y);
#else
    return vec2(textureSize(view_position, 0));
#endif
}

float projected_pixels(vec3 p[4], out float width) {
    width = 1e30;
    vec2 size = view_size();
    vec2 s[4];
    for (int k = 0; k < 4; ++k) {
        vec4 c = to_clip(p[k]);
        if (c.w <= 0.0) return 1e30;
        s[k] = (c.xy / c.w * 0.5 + 0.5) * size;
    }
    vec2 a = s[1] - s[0], b = s[2] - s[0], d = s[3] - s[0];
    float area = 0.5 * (abs(a.x * b.y - a.y * b.x) + abs(b.x * d.y - b.y * d.x));
    float longest = max(max(length(a), length(s[2] - s[1])), max(length(s[3] - s[2]), length(d)));
    width = longest > 0.0 ? area / longest : 0.0;
    return area;
}

void main() {
    uint n = constants.photon_side;
#if defined(QUAD_POINTS)
    uint quad = uint(gl_VertexIndex);
    gl_PointSize = 1.0;
#elif defined(QUAD_LINES)
    uint quad = uint(gl_VertexIndex) / 2u;
#else
    uint quad = uint(gl_VertexIndex) / 6u;
#endif
    ivec2 base = ivec2(quad % (n - 1u), quad / (n - 1u));
    CausticLight cl = caustics.lights[constants.light];
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    v_position = vec3(0.0);
    v_direction = vec3(0.0);
    v_intensity = vec3(0.0);
    vec3 p[4];
    vec3 u[4];
    vec3 intensity = vec3(0.0);
    vec3 direction = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 texel = base + BLOCK[k];
        vec4 pos = texelFetch(photon_position, texel, 0);
        if (pos.w < 0.5) return;
        p[k] = pos.xyz;
        u[k] = normalize(pos.xyz - cl.position.xyz);
        direction += texelFetch(photon_direction, texel, 0).xyz;
        // The photon's power over its texel's solid angle: the light's intensity times what
        // the specular surfaces let through (Eq. 1's E_B without the beam's solid angle).
        vec2 ndc = (vec2(texel) + 0.5) / float(n) * 2.0 - 1.0;
        intensity += texelFetch(photon_power, texel, 0).rgb / texel_solid_angle(ndc, cl.photon_plane);
    }
    intensity *= 0.25;
    vec3 centre = 0.25 * (p[0] + p[1] + p[2] + p[3]);
    float span = max(distance(p[2], p[0]), distance(p[3], p[1]));
    vec2 ndc_c;
    if (!caustic_map_ndc(cl, centre, ndc_c)) return;
    vec4 seen = texture(receiver_positions, ndc_c * 0.5 + 0.5);
    float d_centre = distance(centre, cl.position.xyz);
    float d_seen = distance(seen.xyz, cl.position.xyz);
    if (seen.w < 0.5 || abs(d_seen - d_centre) > 0.05 * span + 0.02 * d_centre) return;
    // Eq. 1-2: R = w_B / w_P. The beam's corners are the four photon texels' centres, so it
    // spans one texel, centred on the block's shared corner.
    vec2 corner = vec2(base + 1) / float(n) * 2.0 - 1.0;
    float w_b = texel_solid_angle(corner, cl.photon_plane);
    float w_p = 0.5 * (length(cross(u[1] - u[0], u[2] - u[0])) + length(cross(u[2] - u[0], u[3] - u[0])));
    float width;
    float pixels = projected_pixels(p, width);
    bool small = !(w_p > 0.0) || pixels < SMALL_QUAD_PIXELS;
    bool sliver = !small && width < SMALL_QUAD_PIXELS;
#if defined(QUAD_LINES)
    if (!sliver) return;
    // The longer diagonal; its fragments: one per pixel along its major axis (at least one).
    bool first = distance(p[2], p[0]) >= distance(p[3], p[1]);
    vec3 ends[2] = first ? vec3[2](p[0], p[2]) : vec3[2](p[1], p[3]);
    vec4 c0 = to_clip(ends[0]), c1 = to_clip(ends[1]);
    if (c0.w <= 0.0 || c1.w <= 0.0) return;
    vec2 size = view_size();
    vec2 run = abs(c1.xy / c1.w - c0.xy / c0.w) * 0.5 * size;
    float fragments = max(1.0, round(max(run.x, run.y)));
    vec3 here = ends[gl_VertexIndex % 2];
    vec4 clip = to_clip(here);
    v_position = here;
    v_direction = direction;
    v_intensity = intensity * w_b / fragments;
    gl_Position = vec4(clip.xy / clip.w, 0.5, 1.0);
#elif defined(QUAD_POINTS)
    if (!small) return;
    vec4 clip = to_clip(centre);
    if (clip.w <= 0.0) return;
    v_position = centre;
    v_direction = direction;
    v_intensity = intensity * w_b;
    gl_Position = vec4(clip.xy / clip.w, 0.5, 1.0);
#else
#ifdef QUAD_POLYGONS
    if (!(w_p > 0.0)) return;
#else
    if (small || sliver) return;
#endif
    ivec2 c = base + CORNERS[gl_VertexIndex % 6];
    vec3 here = texelFetch(photon_position, c, 0).xyz;
    v_position = here;
    v_direction = texelFetch(photon_direction, c, 0).xyz;
    v_intensity = intensity * (w_b / w_p);
    gl_Position = to_clip(here);
#endif
}
