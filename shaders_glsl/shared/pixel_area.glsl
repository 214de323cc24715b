// The world area a pixel of a view covers, from the world positions of the pixels next to it
// (xyz, w = 1 on a surface): Wyman & Davis 2006 Sec. 3.2.2 step 2 (2)'s neighbour areas (not
// their Eq. 5), which the eye-space gathers and screen-space photon mapping divide power by.
#ifndef PIXEL_AREA_GLSL
#define PIXEL_AREA_GLSL

// The difference to the neighbour across pixel q along `axis` of a view's world positions
// (w = 1 on a surface): central where both neighbours lie on the surface at similar distances,
// else the shorter valid side.
vec3 position_edge(sampler2D positions, ivec2 q, ivec2 axis, vec3 p) {
    ivec2 size = textureSize(positions, 0);
    ivec2 a = q + axis, b = q - axis;
    bool va = all(lessThan(a, size)) && all(greaterThanEqual(a, ivec2(0)));
    bool vb = all(lessThan(b, size)) && all(greaterThanEqual(b, ivec2(0)));
    vec4 pa = va ? texelFetch(positions, a, 0) : vec4(0.0);
    vec4 pb = vb ? texelFetch(positions, b, 0) : vec4(0.0);
    va = va && pa.w > 0.5;
    vb = vb && pb.w > 0.5;
    vec3 da = pa.xyz - p, db = p - pb.xyz;
    if (va && vb) {
        float la = length(da), lb = length(db);
        if (la < 2.0 * lb && lb < 2.0 * la) return 0.5 * (da + db);
        return la < lb ? da : db;
    }
    if (va) return da;
    if (vb) return db;
    return vec3(0.0);
}

// The area pixel q at world position p covers.
float pixel_area(sampler2D positions, ivec2 q, vec3 p) {
    return length(cross(position_edge(positions, q, ivec2(1, 0), p), position_edge(positions, q, ivec2(0, 1), p)));
}
#endif
