// An entry of the hierarchical traversal's lists (Wyman 2008 Sec. 3.1-3.2), uvec4(x, y, level,
// final), packed into one uint: the photon buffer is at most 4096² (padded to a power of two, so
// x, y < 4096 at every level) and has at most 8 levels above it. Four bytes an entry keep the
// longest list, n² photons, within 64 MiB: half the storage-buffer range every Vulkan device
// allows, and a quarter of the traffic of a uvec4. Mirrored by `pack_entry`/`unpack_entry` in
// crates/caustics/src/caustic_map/hierarchy.rs.
#ifndef ENTRY_GLSL
#define ENTRY_GLSL
#define ENTRY_Y_SHIFT 12u
#define ENTRY_LEVEL_SHIFT 24u
#define ENTRY_FINAL_SHIFT 28u

uint pack_entry(uvec4 e) {
    return e.x | (e.y << ENTRY_Y_SHIFT) | (e.z << ENTRY_LEVEL_SHIFT) | (e.w << ENTRY_FINAL_SHIFT);
}

uvec4 unpack_entry(uint p) {
    return uvec4(p & 0xFFFu, (p >> ENTRY_Y_SHIFT) & 0xFFFu, (p >> ENTRY_LEVEL_SHIFT) & 0xFu, p >> ENTRY_FINAL_SHIFT);
}
#endif
