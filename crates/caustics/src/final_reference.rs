//! The reference final image (issue 51 item 2): the eye's frame as every technique renders it
//! (the shadow maps, the eye's refraction, the caustic-map lookup of `common/caustic_lookup.glsl`),
//! its caustic map filled by exact photons (`photon-trace`: Snell, Fresnel, total internal
//! reflection, mirrors, through a BVH of every triangle) fine enough, with a splat small enough,
//! that refining it further changes the image by less than any technique's FLIP.
//!
//! A [`Refinement`] of level L doubles the caustic map's resolution and halves the splat's
//! width on the receivers (its radius stays [`SPLAT_RADIUS`] texels) at each level, and
//! multiplies the photons by 8, so that the photons a splat gathers double while it shrinks:
//! the bias of the splat's blur halves and the relative noise falls by √2 a level. More photons
//! than one photon buffer holds (4096²) are traced as several frames, each with its own seed,
//! and their final images averaged: the final image is linear in the caustic map (irradiance =
//! power cos θ / (w d²), Wyman & Davis 2006 Eq. 5-8 as `common/caustic_lookup.glsl` reads it; the
//! eye's refraction a linear lookup of what it sees), so the mean of the frames is the image of
//! the mean caustic map, the caustic map of all their photons.
//!
//! `causticlab reference --final` writes it; `scripts/final_reference.sh` shows the convergence
//! (docs/flip.md, "The reference final image").

use crate::image_io::{ImageF32, Layer};
use crate::render::{self, RenderRequest};
use crate::scene::Scene;
use crate::techniques::photon_trace::settings::Deposit as PhotonDeposit;
use crate::techniques::shared::settings::SplatKernel;
use crate::techniques::Technique;
use anyhow::{Context as _, Result};
use vkcore::{Context, ShaderCompiler};

/// The splat's radius in caustic-map texels at every level (Gaussian): the caustic map's
/// resolution sets the blur.
pub const SPLAT_RADIUS: f32 = 1.5;

/// The largest photon buffer side one frame traces (`caustics.photons`' limit).
pub const MAX_PHOTON_SIDE: u32 = 4096;

/// The deepest level: level 4 is a 4096² caustic map and 2^32 photons at the default base.
pub const MAX_LEVEL: u32 = 4;

/// The level every table's final-image FLIP is against (`reference --final`'s default): on
/// `sphere_on_plane` refining it to level 2 or 3 changes the image by less than a third of any
/// technique's FLIP, and no technique's FLIP by more than 2% (`scripts/final_reference.sh`,
/// docs/flip.md).
pub const TABLE_LEVEL: u32 = 1;

/// Level 0 of the refinements.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Base {
    /// The caustic map's resolution at level 0.
    pub caustic_map_resolution: u32,
    /// The photon buffer's side at level 0 (side² photons per light).
    pub photons: u32,
}

/// The refinements `causticlab reference --final` renders: level 0 a 256² caustic map and 1024²
/// photons; on `sphere_on_plane` (512² pixels) a caustic-map texel is then about half an eye
/// pixel across the floor under the sphere.
pub const BASE: Base = Base { caustic_map_resolution: 256, photons: 1024 };

/// One refinement of the reference final image.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Refinement {
    pub level: u32,
    pub caustic_map_resolution: u32,
    /// The photon buffer's side of each frame (side² photons per light and frame).
    pub photons: u32,
    /// Frames traced and averaged, each with its own seed (the first seed, then the next ...).
    pub frames: u32,
    /// Caustic-map texels.
    pub splat_radius: f32,
}

impl Refinement {
    /// Level `level` above `base`: the caustic map `2^level` times finer, `8^level` times the
    /// photons (in frames of at most [`MAX_PHOTON_SIDE`]² photons).
    pub fn at(level: u32, base: Base) -> Result<Refinement> {
        if level > MAX_LEVEL {
            return Err(crate::input_error!("--level {level}: the deepest level is {MAX_LEVEL}").into());
        }
        let caustic_map_resolution = base.caustic_map_resolution << level;
        let total = (base.photons as u64).pow(2) << (3 * level);
        let photons = (base.photons << level).min(MAX_PHOTON_SIDE);
        let frames = total.div_ceil((photons as u64).pow(2)) as u32;
        Ok(Refinement { level, caustic_map_resolution, photons, frames, splat_radius: SPLAT_RADIUS })
    }

    /// Photons per light over all frames.
    pub fn total_photons(&self) -> u64 {
        (self.photons as u64).pow(2) * self.frames as u64
    }

    /// `scene` set to trace this refinement's photons, frame `frame` with seed `seed + frame`:
    /// technique photon-trace through the caustic map, the eye's own settings (refraction, Fresnel,
    /// ...) as the scene has them.
    pub fn scene(&self, scene: &Scene, seed: u32, frame: u32) -> Result<Scene> {
        let mut s = scene.clone();
        let c = &mut s.caustics;
        c.technique = Technique::PhotonTrace;
        c.photons = self.photons;
        c.caustic_map_resolution = self.caustic_map_resolution;
        c.splat_radius = self.splat_radius;
        c.splat_kernel = SplatKernel::Gaussian;
        c.deposit = PhotonDeposit::CausticMap;
        c.seed = seed.wrapping_add(frame);
        let origin = format!("{} (the reference final image, level {})", scene.path.display(), self.level);
        c.validate(&origin, "caustics.")?;
        c.validate_combination(&origin, "caustics.")?;
        Ok(s)
    }
}

/// Renders the reference final image of `scene` at refinement `r`, photons seeded from `seed`:
/// `r.frames` photon-trace renders averaged (see the module docs). `each_frame` is told of each
/// frame as it finishes (frame index, from 0).
pub fn render_final(
    ctx: &Context,
    shaders: &ShaderCompiler,
    scene: &Scene,
    r: &Refinement,
    seed: u32,
    mut each_frame: impl FnMut(u32),
) -> Result<ImageF32> {
    let mut sum: Vec<f64> = vec![];
    let mut first: Option<ImageF32> = None;
    for frame in 0..r.frames {
        let s = r.scene(scene, seed, frame)?;
        render::check_device(ctx, &s)?;
        let req = RenderRequest { dumps: vec![], frames: 1, frame_mode: render::FrameMode::PerPass };
        let img = render::render(ctx, shaders, &s, &req)
            .with_context(|| format!("the reference final image, level {}, frame {frame}", r.level))?
            .final_image;
        let data = &img.layers.first().context("a final image without a layer")?.data;
        if sum.is_empty() {
            sum = vec![0.0; data.len()];
        }
        for (a, &v) in sum.iter_mut().zip(data) {
            *a += v as f64;
        }
        first.get_or_insert(img);
        each_frame(frame);
    }
    let mut out = first.context("no frame rendered")?;
    let layer = &out.layers[0];
    let data = sum.iter().map(|&v| (v / r.frames as f64) as f32).collect();
    let channels: Vec<&str> = layer.channels.iter().map(String::as_str).collect();
    out.layers = vec![Layer::new(layer.name.as_deref(), &channels, data)];
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_level_doubles_the_map_and_multiplies_the_photons_by_8() {
        let at = |l| Refinement::at(l, BASE).unwrap();
        assert_eq!((at(0).caustic_map_resolution, at(0).photons, at(0).frames), (256, 1024, 1));
        assert_eq!((at(1).caustic_map_resolution, at(1).photons, at(1).frames), (512, 2048, 2));
        assert_eq!((at(2).caustic_map_resolution, at(2).photons, at(2).frames), (1024, 4096, 4));
        assert_eq!((at(3).caustic_map_resolution, at(3).photons, at(3).frames), (2048, 4096, 32));
        for l in 0..MAX_LEVEL {
            assert_eq!(at(l + 1).total_photons(), 8 * at(l).total_photons());
            assert_eq!(at(l).splat_radius, SPLAT_RADIUS);
        }
        assert!(Refinement::at(MAX_LEVEL + 1, BASE).is_err());
    }
}
