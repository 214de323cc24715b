//! What the adaptive traversal stores (Wyman & Nichols 2009 Sec. 3.2-4.1), the twin of
//! `shaders_glsl/wyman_nichols2009/adaptive_photon.glsl`: cells of the virtual photon hierarchy
//! packed into a u32 (the traversal's lists hold clusters as cells), and adaptive photons.

use bytemuck::{Pod, Zeroable};

/// Bit offsets of y and the level in a packed cell (x in bits 0-13), as in the GLSL.
pub(crate) const CELL_Y_SHIFT: u32 = 14;
pub(crate) const CELL_LEVEL_SHIFT: u32 = 28;
pub(crate) const CELL_MASK: u32 = (1 << CELL_Y_SHIFT) - 1;
/// Bytes of a list entry (a packed cluster).
pub const CLUSTER_BYTES: u64 = 4;
/// Bytes of a cluster's hits (the xfb path's first kernel of a max-error step, Sec. 4.1): a
/// 16-byte header and four photons.
pub const HITS_BYTES: u64 = 16 + 4 * PHOTON_BYTES;
/// Bytes of an [`AdaptivePhoton`].
pub const PHOTON_BYTES: u64 = 32;

/// (x, y, level) packed as `pack_cell` in `adaptive_photon.glsl`.
pub fn pack_cell(c: [u32; 3]) -> u32 {
    c[0] | (c[1] << CELL_Y_SHIFT) | (c[2] << CELL_LEVEL_SHIFT)
}

/// The (x, y, level) of a packed cell.
pub fn unpack_cell(p: u32) -> [u32; 3] {
    [p & CELL_MASK, (p >> CELL_Y_SHIFT) & CELL_MASK, p >> CELL_LEVEL_SHIFT]
}

/// One photon of the adaptive traversal's output: a photon of level k (its cell on the
/// (64 × 2^k)² grid), or the one photon of a converged cluster of level k, stored as the
/// cluster's cell at level k − 1 (Sec. 3.2.2).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable, Debug, Default, PartialEq)]
pub struct AdaptivePhoton {
    /// Where it lands on the first diffuse surface.
    pub position: [f32; 3],
    /// Its cell, [`pack_cell`].
    pub cell: u32,
    /// Power, W.
    pub power: [f32; 3],
    /// With varying splats (Wyman 2008 Sec. 3.3; Sec. 3.2.2 here): its splat radius in
    /// caustic-map texels, the largest distance to its adjacent photons that landed (1 for a
    /// converged cluster); 0 with fixed splats. (The solid angle it stands for, folded into its
    /// power, follows from its cell.)
    pub footprint: f32,
}

const _: () = assert!(std::mem::size_of::<AdaptivePhoton>() as u64 == PHOTON_BYTES);

impl AdaptivePhoton {
    /// Its cell as (x, y, level).
    pub fn cell(&self) -> [u32; 3] {
        unpack_cell(self.cell)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_round_trip_and_match_the_glsl() {
        for c in [[0, 0, 0], [16383, 16383, 8], [17, 9000, 3], [1, 2, 15]] {
            assert_eq!(unpack_cell(pack_cell(c)), c);
        }
        let glsl = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../shaders_glsl/wyman_nichols2009/adaptive_photon.glsl"
        ))
        .expect("adaptive_photon.glsl");
        for (name, v) in [("Y", CELL_Y_SHIFT), ("LEVEL", CELL_LEVEL_SHIFT)] {
            assert!(glsl.contains(&format!("#define CELL_{name}_SHIFT {v}u")), "CELL_{name}_SHIFT");
        }
        assert!(glsl.contains(&format!("#define CELL_MASK 0x{CELL_MASK:X}u")));
        // The GLSL struct's members, in order, are the Rust struct's.
        let body = &glsl[glsl.find("struct AdaptivePhoton {").expect("struct")..];
        let body = &body[..body.find('}').expect("end")];
        let members: Vec<&str> = body
            .lines()
            .filter_map(|l| l.split("//").next()?.trim().strip_suffix(';'))
            .map(|l| l.split_whitespace().nth(1).unwrap_or(""))
            .collect();
        assert_eq!(members, ["position", "cell", "power", "footprint"]);
        // The deepest level's last cell fits.
        let last = super::super::super::settings::MAX_LEVEL;
        let side = super::super::super::settings::TOP_PHOTONS << last;
        assert_eq!(unpack_cell(pack_cell([side - 1, side - 1, last])), [side - 1, side - 1, last]);
    }
}
