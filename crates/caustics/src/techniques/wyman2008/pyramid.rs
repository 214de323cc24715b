//! The photon hierarchy (Wyman 2008 Sec. 3.1): a mipmap over the photon buffer whose level-k
//! texel sums the power, photon count and positions of its 2^k x 2^k photons and bounds the
//! caustic-map texels they land in (what the convergence test of Sec. 3.2 reads). Built by one
//! compute pass per level (`shaders_glsl/wyman2008/build.comp`).

use super::push::BuildConstants;
use super::{Hierarchy, TOP_SIDE};
use crate::gpu::Stage;
use crate::image_io::{ImageF32, Layer};
use crate::techniques::shared::targets::PhotonTargets;
use crate::techniques::shared::FrameInputs;
use anyhow::Result;
use vkcore::{Bind, Context, Frame, Image, ImageView};

/// (P, L): the photon buffer side N padded to a power of two P ≥ 32 (padding texels hold no
/// photon), and the number of levels above it, the top one TOP_SIDE².
pub fn levels(n: u32) -> (u32, u32) {
    let p = n.max(2 * TOP_SIDE).next_power_of_two();
    (p, (p / TOP_SIDE).trailing_zeros())
}

/// The hierarchy images: level k (1..=L) in mip k-1 of each. The images are only held to keep
/// the views alive.
#[allow(dead_code)]
pub(super) struct Pyramid {
    /// (summed power, photon count).
    pub(super) power: Image,
    /// (summed position, 0).
    pub(super) position: Image,
    /// Caustic-map texel bounding box (min x, min y, max x, max y) of the subtree's photons.
    pub(super) texels: Image,
    /// Every mip, sampled: [power, position, texels].
    pub(super) all: [ImageView; 3],
    /// One view per mip (level k at index k-1): [power, position, texels].
    pub(super) mips: Vec<[ImageView; 3]>,
}

impl Hierarchy {
    /// Builds light `l`'s hierarchy levels 1..=L, each from the one below (level 1 from the
    /// photon buffer).
    pub(super) fn record_build(&self, f: &mut Frame, inp: &FrameInputs, pt: &PhotonTargets, l: u32) -> Result<()> {
        let py = &self.pyramid;
        for k in 1..=self.levels {
            let out = &py.mips[k as usize - 1];
            let children: [&ImageView; 3] = if k == 1 {
                [&self.dummy.view, &self.dummy.view, &self.dummy.view]
            } else {
                let c = &py.mips[k as usize - 2];
                [&c[0], &c[1], &c[2]]
            };
            let binds = [
                ("frame", Bind::Uniform(inp.frame_uniforms)),
                ("caustics", Bind::Uniform(inp.caustic_uniforms)),
                ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
                ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
                ("child_power", Bind::Sampled(children[0], inp.nearest)),
                ("child_position", Bind::Sampled(children[1], inp.nearest)),
                ("child_texels", Bind::Sampled(children[2], inp.nearest)),
                ("out_power", Bind::Storage(&out[0])),
                ("out_position", Bind::Storage(&out[1])),
                ("out_texels", Bind::Storage(&out[2])),
            ];
            f.pass(&Stage::HierarchyBuild.pass().level(k).light(l)).bind(&self.build, binds).record(|cmd| {
                cmd.push(&BuildConstants { level: k, light: l, photon_side: self.n })?;
                let side = self.padded >> k;
                cmd.dispatch(side.div_ceil(8), side.div_ceil(8), 1);
                Ok(())
            })?;
        }
        Ok(())
    }

    /// `hierarchy.exr` for the light traversed last: every level of the photon hierarchy (level
    /// 0 is the photon buffer), level k in the top-left (P/2^k)² corner of layers
    /// `level<k>.power` (R, G, B, count), `level<k>.position` (mean X, Y, Z of the subtree's
    /// photons) and `level<k>.texels` (caustic-map texel box).
    pub fn dump_levels(&self, ctx: &Context) -> Result<ImageF32> {
        let side = self.padded / 2;
        let mut layers = vec![];
        for k in 1..=self.levels {
            let s = (self.padded >> k) as usize;
            let read = |i: &Image| ctx.read_image_f32(i, k - 1, 0);
            let (power, position, texels) =
                (read(&self.pyramid.power)?, read(&self.pyramid.position)?, read(&self.pyramid.texels)?);
            let place = |src: &[f32], pick: &dyn Fn(&[f32]) -> Vec<f32>, nc: usize| {
                let mut out = vec![0.0f32; side as usize * side as usize * nc];
                for y in 0..s {
                    for x in 0..s {
                        let v = pick(&src[(y * s + x) * 4..(y * s + x) * 4 + 4]);
                        let o = (y * side as usize + x) * nc;
                        out[o..o + nc].copy_from_slice(&v);
                    }
                }
                out
            };
            let mean = |p: &[f32]| -> Vec<f32> { p[..3].to_vec() };
            let counts: Vec<f32> = power.chunks(4).map(|p| p[3]).collect();
            let mut mean_pos = position.clone();
            for (i, c) in counts.iter().enumerate() {
                for v in &mut mean_pos[i * 4..i * 4 + 3] {
                    *v /= c.max(1.0);
                }
            }
            layers.push(Layer::new(
                Some(&format!("level{k}.power")),
                &["R", "G", "B", "count"],
                place(&power, &|p| p.to_vec(), 4),
            ));
            layers.push(Layer::new(Some(&format!("level{k}.position")), &["X", "Y", "Z"], place(&mean_pos, &mean, 3)));
            layers.push(Layer::new(
                Some(&format!("level{k}.texels")),
                &["min_x", "min_y", "max_x", "max_y"],
                place(&texels, &|p| p.to_vec(), 4),
            ));
        }
        Ok(ImageF32 { width: side, height: side, layers })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_pad_to_a_power_of_two_with_a_16_squared_top() {
        assert_eq!(levels(64), (64, 2));
        assert_eq!(levels(100), (128, 3));
        assert_eq!(levels(1024), (1024, 6));
        assert_eq!(levels(4096), (4096, 8));
        assert_eq!(levels(17), (32, 1));
    }
}
