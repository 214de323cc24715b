//! The deposit: how the selected photons become light, in a light's caustic map or in the
//! eye's view.

use super::Selection;
use crate::dump::Dump;
use crate::gpu::Stage;
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::photon_trace::differential::DifferentialSplat;
use crate::techniques::shared::compute_splat::Photons;
use crate::techniques::shared::splat::PointSplat;
use crate::techniques::shared::{CausticPasses, ComputeSplat, EyeView, SplatPath};
use crate::techniques::wyman2008::interpolated::InterpolatedSplat;
use crate::techniques::wyman2008::thin_lens::ThinLensSplat;
use crate::techniques::wyman2008::SplatMode;
use crate::techniques::wyman_davis2006::settings::EYE_CAUSTIC;
use crate::techniques::wyman_davis2006::ImageSpace;
use crate::techniques::wyman_nichols2009::adaptive;
use anyhow::Result;
use vkcore::{Context, Frame, ImageView, ShaderCompiler};

/// How the selected photons become light.
// One per renderer: boxing the larger variants would save nothing.
#[allow(clippy::large_enum_variant)]
pub enum Deposit {
    /// Points blended into the light's caustic map: the photon buffer's texels instanced (Wyman
    /// 2008 Sec. 4), or the selection's own splat of its list or vertex array.
    Points(PointSplat),
    /// A compute shader adding each photon's kernel into the caustic map with atomics
    /// (`splat_path = compute`: the modern path beside the papers' point splats).
    Compute(ComputeSplat),
    /// The photon buffer's points, each sized by a per-photon thin-lens model (`splat =
    /// thin-lens`, Wyman 2008 Fig. 7).
    ThinLens(ThinLensSplat),
    /// The hierarchy's final list splatted at four radii, one layer each (`splat =
    /// interpolated`, Wyman 2008 Fig. 7).
    Interpolated(InterpolatedSplat),
    /// Wyman & Davis 2006's eye-space points, quads and gathers (Sec. 3.2), or their quads and
    /// gathers into the caustic map (light space); and screen-space photon mapping (Kim 2019)
    /// of the traced photons in the same eye-space views.
    ImageSpace(ImageSpace),
    /// `photon-trace --differentials`: each photon splatted as its footprint's anisotropic
    /// Gaussian (Schjøth et al. 2007), a compute pass.
    Differential(DifferentialSplat),
}

impl Deposit {
    /// The variant's name, as the stages table in `stages/mod.rs` writes it.
    pub fn name(&self) -> &'static str {
        match self {
            Deposit::Points(_) => "Points",
            Deposit::Compute(_) => "Compute",
            Deposit::ThinLens(_) => "ThinLens",
            Deposit::Interpolated(_) => "Interpolated",
            Deposit::ImageSpace(_) => "ImageSpace",
            Deposit::Differential(_) => "Differential",
        }
    }

    /// The passes it records, by their [`Stage`] (`tests/frame_graph_stages.rs`).
    pub fn stages(&self) -> &'static [Stage] {
        match self {
            Deposit::Points(_) | Deposit::ThinLens(_) | Deposit::Interpolated(_) => &[Stage::Splat],
            Deposit::Compute(_) => &[Stage::SplatClear, Stage::SplatArguments, Stage::Splat, Stage::SplatResolve],
            Deposit::Differential(_) => &[Stage::SplatClear, Stage::Splat, Stage::SplatResolve],
            Deposit::ImageSpace(_) => &[
                Stage::WdPhotons,
                Stage::WdGather,
                Stage::WdQuads,
                Stage::WdShade,
                Stage::WdReceiverView,
                Stage::ScreenSpaceNormalize,
                Stage::ScreenSpaceFilter,
            ],
        }
    }

    pub fn new(ctx: &Context, sh: &ShaderCompiler, scene: &Scene, selection: &Selection) -> Result<Deposit> {
        if let Some(is) = ImageSpace::new(ctx, sh, scene)? {
            return Ok(Deposit::ImageSpace(is));
        }
        let s = &scene.caustics;
        if s.technique == crate::techniques::Technique::PhotonTrace && s.differentials {
            return Ok(Deposit::Differential(DifferentialSplat::new(ctx, sh, s.caustic_map_resolution)?));
        }
        if s.splat == SplatMode::ThinLens {
            // The settings' checks refused the others (`SplatMode::needs`, `check_photon_copy`).
            anyhow::ensure!(matches!(selection, Selection::Dense), "thin-lens splats are the photon buffer's points");
            return Ok(Deposit::ThinLens(ThinLensSplat::new(ctx, sh, s.instance_vertices)?));
        }
        if s.splat == SplatMode::Interpolated {
            // The settings' checks refused it but for hcm's point splat (`SplatMode::needs`).
            anyhow::ensure!(matches!(selection, Selection::Hierarchy(..)), "interpolated splats are hcm's");
            return Ok(Deposit::Interpolated(InterpolatedSplat::new(ctx, sh)?));
        }
        Ok(match s.splat_path {
            SplatPath::Compute => {
                let (side, layers) = (s.caustic_map_resolution, s.caustic_levels());
                Deposit::Compute(ComputeSplat::new(ctx, sh, side, layers, selection.splat_list())?)
            }
            SplatPath::Raster => Deposit::Points(PointSplat::new(ctx, sh, s.instance_vertices)?),
        })
    }

    /// Light `l`'s deposit of what `selection` selected (with `reuse`, from the photons kept
    /// from the last frame). `eye`: the eye's view, for deposits into it.
    pub fn record(
        &self,
        f: &mut Frame,
        c: &CausticPasses,
        selection: &Selection,
        l: u32,
        eye: Option<EyeView>,
        reuse: bool,
    ) -> Result<()> {
        let (inp, pt) = (c.inputs, c.photons);
        let cmap = &c.targets.per_light[l as usize].0;
        let own_deposit = || anyhow::anyhow!("the adaptive traversal deposits its photons batch by batch itself");
        match self {
            Deposit::ImageSpace(is) => is.record_light(f, c, l, eye, reuse),
            Deposit::Points(points) => match selection {
                Selection::Dense => points.record(f, c, l),
                Selection::Copy(copy) => copy.record_splat(f, inp, cmap, l),
                Selection::Hierarchy(h, _) => h.record_splat(f, inp, pt, cmap, c.targets.levels, l),
                Selection::Adaptive(_) => Err(own_deposit()),
            },
            Deposit::Compute(cs) => {
                let photons = match selection {
                    Selection::Dense => Photons::Dense,
                    Selection::Hierarchy(h, _) => h.final_list(),
                    Selection::Copy(_) => anyhow::bail!("the copied vertex array has no compute splat"),
                    Selection::Adaptive(_) => return Err(own_deposit()),
                };
                cs.record(f, inp, pt, &photons, cmap, l)
            }
            Deposit::ThinLens(tl) => match selection {
                Selection::Dense => tl.record(f, c, l),
                _ => anyhow::bail!("thin-lens splats are the photon buffer's points"),
            },
            Deposit::Interpolated(is) => match selection {
                Selection::Hierarchy(h, _) => is.record(f, c, h, l),
                _ => anyhow::bail!("interpolated splats are hcm's"),
            },
            Deposit::Differential(ds) => match selection {
                Selection::Dense => ds.record(f, c, l),
                _ => anyhow::bail!("photon differentials are the traced photons'"),
            },
        }
    }

    /// After every light's deposit: the eye-space caustics added to the eye's radiance.
    pub fn record_after_lights(
        &self,
        f: &mut Frame,
        c: &CausticPasses,
        eye: Option<EyeView>,
        reuse: bool,
    ) -> Result<()> {
        match self {
            Deposit::ImageSpace(is) => is.record_after_lights(f, c, eye, reuse),
            Deposit::Points(_)
            | Deposit::Compute(_)
            | Deposit::ThinLens(_)
            | Deposit::Interpolated(_)
            | Deposit::Differential(_) => Ok(()),
        }
    }

    /// Where the adaptive traversal splats light `l`'s batches: the compute splat, else its
    /// own point splat.
    pub fn adaptive_splat<'a>(&'a self, c: &CausticPasses<'a>, l: u32) -> adaptive::Splat<'a> {
        adaptive::Splat {
            inputs: c.inputs,
            compute: match self {
                Deposit::Compute(cs) => Some(cs),
                Deposit::Points(_)
                | Deposit::ImageSpace(_)
                | Deposit::ThinLens(_)
                | Deposit::Interpolated(_)
                | Deposit::Differential(_) => None,
            },
            photon_targets: c.photons,
            cmap: &c.targets.per_light[l as usize].0,
            layers: c.targets.levels,
        }
    }

    /// Whether the caustics are deposited in the eye's view (the eye's background and geometry
    /// buffer are drawn first).
    pub fn eye_space(&self) -> bool {
        matches!(self, Deposit::ImageSpace(is) if is.eye_space())
    }

    /// The caustic irradiance of the receiver view, which the receiver map reads (eye space).
    pub fn receiver_caustic(&self) -> Option<&ImageView> {
        match self {
            Deposit::ImageSpace(is) => is.receiver_caustic(),
            Deposit::Points(_)
            | Deposit::Compute(_)
            | Deposit::ThinLens(_)
            | Deposit::Interpolated(_)
            | Deposit::Differential(_) => None,
        }
    }

    /// The dump `d` of the eye's view that this stage owns (`eye_caustic`; None where it has
    /// none).
    pub fn dump(&self, ctx: &Context, d: &'static Dump) -> Result<Option<ImageF32>> {
        match self {
            Deposit::ImageSpace(is) if d == &EYE_CAUSTIC => is.dump_eye(ctx),
            Deposit::ImageSpace(_)
            | Deposit::Points(_)
            | Deposit::Compute(_)
            | Deposit::ThinLens(_)
            | Deposit::Interpolated(_)
            | Deposit::Differential(_) => Ok(None),
        }
    }
}
