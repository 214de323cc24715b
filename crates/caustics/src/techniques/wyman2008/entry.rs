//! A traversal list entry (Wyman 2008 Sec. 3.1): a node (x, y) of a hierarchy level, or a
//! cluster of converging photons (Sec. 3.2), packed into one u32 as
//! `shaders_glsl/wyman2008/entry.glsl` packs it.

/// Bytes of a list entry: (x, y, level, final) packed into a u32 (`wyman2008/entry.glsl`).
pub const ENTRY_BYTES: u64 = 4;
/// Bit offsets of y, level and final in a packed entry (x in bits 0-11), as in `entry.glsl`.
pub(crate) const ENTRY_Y_SHIFT: u32 = 12;
pub(crate) const ENTRY_LEVEL_SHIFT: u32 = 24;
pub(crate) const ENTRY_FINAL_SHIFT: u32 = 28;
/// The largest padded photon buffer side a packed entry can address (12 bits of x and y).
pub const MAX_SIDE: u32 = 1 << ENTRY_Y_SHIFT;

/// (x, y, level, final) packed as `pack_entry` in `shaders_glsl/wyman2008/entry.glsl` does.
pub fn pack_entry(e: [u32; 4]) -> u32 {
    e[0] | (e[1] << ENTRY_Y_SHIFT) | (e[2] << ENTRY_LEVEL_SHIFT) | (e[3] << ENTRY_FINAL_SHIFT)
}

/// The (x, y, level, final) of a packed entry.
pub fn unpack_entry(p: u32) -> [u32; 4] {
    [p & 0xFFF, (p >> ENTRY_Y_SHIFT) & 0xFFF, (p >> ENTRY_LEVEL_SHIFT) & 0xF, p >> ENTRY_FINAL_SHIFT]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_round_trip_and_match_the_glsl() {
        for e in [[0, 0, 0, 0], [4095, 4095, 8, 1], [17, 4000, 3, 0], [1, 2, 15, 1]] {
            assert_eq!(unpack_entry(pack_entry(e)), e);
        }
        let glsl =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/wyman2008/entry.glsl"))
                .expect("entry.glsl");
        for (name, v) in [("Y", ENTRY_Y_SHIFT), ("LEVEL", ENTRY_LEVEL_SHIFT), ("FINAL", ENTRY_FINAL_SHIFT)] {
            assert!(glsl.contains(&format!("#define ENTRY_{name}_SHIFT {v}u")), "entry.glsl: ENTRY_{name}_SHIFT");
        }
        // The largest photon buffer and its deepest level fit the fields.
        let (p, l) = super::super::pyramid::levels(4096);
        assert!(p <= MAX_SIDE && l < 16);
    }
}
