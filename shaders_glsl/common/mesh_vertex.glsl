// The vertex layout of every scene mesh: `MeshVertex` in crates/caustics/src/render/gpu.rs.
layout(location = 0) in vec3 a_position;   // world space
layout(location = 1) in vec3 a_normal;     // world space, outward
layout(location = 2) in float a_thickness; // Wyman 2005 d_N: distance along -normal to the far side
