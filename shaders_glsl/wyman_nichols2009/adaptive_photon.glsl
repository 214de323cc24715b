// What the adaptive traversal of Wyman & Nichols 2009 (Sec. 3.2-4.2) stores, mirrored by
// crates/caustics/src/techniques/wyman_nichols2009/adaptive/photon.rs:
// - a cell of the virtual photon hierarchy, packed in a uint: level k's grid has (64 2^k)^2
//   cells over the photon frustum (k <= 8: x, y < 16384, 14 bits each; the level in 4 bits);
//   a cluster of the traversal's lists is the 2x2 photons (2x + i, 2y + j) of level k, stored
//   as the cell (x, y) with level k (its parent's index on the coarser grid);
// - an adaptive photon (32 bytes): where it lands, its cell (a photon of level k, or a
//   converged cluster of level k stored as its parent cell at level k - 1), its power and, with
//   varying splats, its splat radius (the solid angle it stands for follows from its cell);
// - a cluster's hits (144 bytes, the transform-feedback path's first kernel of a max-error step,
//   Sec. 4.1): the cluster, which photons landed, whether its footprint is all refractor, and
//   its four photons.
#ifndef ADAPTIVE_PHOTON_GLSL
#define ADAPTIVE_PHOTON_GLSL
#define CELL_Y_SHIFT 14u
#define CELL_LEVEL_SHIFT 28u
#define CELL_MASK 0x3FFFu
#define NO_CELL 0xFFFFFFFFu

uint pack_cell(uvec3 c) { return c.x | (c.y << CELL_Y_SHIFT) | (c.z << CELL_LEVEL_SHIFT); }
uvec3 unpack_cell(uint p) { return uvec3(p & CELL_MASK, (p >> CELL_Y_SHIFT) & CELL_MASK, p >> CELL_LEVEL_SHIFT); }

struct AdaptivePhoton {
    vec3 position;   // where it lands on the first diffuse surface
    uint cell;       // pack_cell(x, y, level)
    vec3 power;      // W
    float footprint; // varying splats (Wyman 2008 Sec. 3.3): the splat radius, caustic-map texels; 0 with fixed splats
};

struct ClusterHits {
    uvec4 header;                 // x: the packed cluster, y: mask of its photons that landed, z: 1 if all covered
    AdaptivePhoton photons[4];    // photon i = (2x + (i & 1), 2y + (i >> 1)); zero where it did not land
};

// The photon's two 16-byte words as a transform-feedback output writes them (bit for bit).
uvec4 photon_word0(AdaptivePhoton p) { return uvec4(floatBitsToUint(p.position), p.cell); }
uvec4 photon_word1(AdaptivePhoton p) { return uvec4(floatBitsToUint(p.power), floatBitsToUint(p.footprint)); }
#endif
