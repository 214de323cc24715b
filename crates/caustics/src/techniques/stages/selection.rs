//! The selection: which of a light's photons, or clusters of them, reach the deposit.

use crate::dump::Dump;
use crate::gpu::{GpuMesh, Stage};
use crate::scene::Scene;
use crate::techniques::shared::{CausticPasses, LightDump, SplatList};
use crate::techniques::wyman2008::photon_copy::{CopyType, PhotonCopy};
use crate::techniques::wyman2008::settings::{HIERARCHY, HIERARCHY_LISTS, SPLATS};
use crate::techniques::wyman2008::splat_footprints::{self, SplatFootprints};
use crate::techniques::wyman2008::{self, Hierarchy};
use crate::techniques::wyman_nichols2009::adaptive::{self, AdaptiveCaustics, Part};
use crate::techniques::wyman_nichols2009::settings::{ADAPTIVE_DUMPS, ADAPTIVE_GEOMETRY, ADAPTIVE_LISTS};
use crate::techniques::Technique;
use anyhow::{Context as _, Result};
use vkcore::{Context, Frame, FrameOptions, ShaderCompiler};

/// Which photons reach the deposit.
// One per renderer: boxing the larger variants would save nothing.
#[allow(clippy::large_enum_variant)]
pub enum Selection {
    /// Every texel of the photon buffer (invalid ones culled where they are drawn).
    Dense,
    /// The photon buffer copied into a vertex array first (Wyman 2008 Table 1's copy path).
    Copy(PhotonCopy),
    /// The photon hierarchy traversed top-down, converging photons clustered (Wyman 2008
    /// Sec. 3.1-3.2); with what the `splats` dump reads its splats with (made by the first).
    Hierarchy(Hierarchy, Option<SplatFootprints>),
    /// The adaptive traversal of a virtual photon hierarchy, refining where photons diverge and
    /// creating them from the geometry buffers as it goes, batch after batch (Wyman & Nichols
    /// 2009 Sec. 3.2-4.3). It calls the deposit itself after each batch.
    Adaptive(AdaptiveCaustics),
}

impl Selection {
    /// The variant's name, as the stages table in `stages/mod.rs` writes it.
    pub fn name(&self) -> &'static str {
        match self {
            Selection::Dense => "Dense",
            Selection::Copy(_) => "Copy",
            Selection::Hierarchy(..) => "Hierarchy",
            Selection::Adaptive(_) => "Adaptive",
        }
    }

    /// The passes it records, by their [`Stage`] (`tests/frame_graph_stages.rs`).
    pub fn stages(&self) -> &'static [Stage] {
        match self {
            Selection::Dense => &[],
            Selection::Copy(_) => &[Stage::PhotonBufferTo16bit, Stage::PhotonCopy],
            Selection::Hierarchy(..) => &[
                Stage::HierarchyBuild,
                Stage::HierarchyReset,
                Stage::HierarchyTraverse,
                Stage::HierarchyFinalize,
                Stage::HierarchyCounts,
                Stage::SplatFootprints,
            ],
            Selection::Adaptive(_) => &[
                Stage::AdaptiveGeometry,
                Stage::AdaptiveCoverage,
                Stage::AdaptiveReset,
                Stage::AdaptiveSelect,
                Stage::AdaptiveTraverse,
                Stage::AdaptiveFinalize,
                Stage::AdaptiveSubdivide,
                Stage::AdaptiveEmit,
                Stage::AdaptiveHits,
                Stage::AdaptiveConverged,
                Stage::AdaptiveRefine,
                Stage::AdaptiveFinalizePhotons,
                Stage::AdaptiveCounts,
            ],
        }
    }

    /// The selection of `scene`'s technique over `photon_side`² photons; `copy`: Wyman 2008
    /// Table 1's copy into a vertex array (checked by [`super::check_photon_copy`]).
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        scene: &Scene,
        meshes: &[GpuMesh],
        photon_side: u32,
        copy: Option<CopyType>,
    ) -> Result<Selection> {
        let s = &scene.caustics;
        let lights = scene.lights.len() as u32;
        Ok(match s.technique {
            Technique::Hcm => {
                Selection::Hierarchy(Hierarchy::new(ctx, sh, photon_side, lights, s.path, s.cluster)?, None)
            }
            Technique::Adaptive => Selection::Adaptive(AdaptiveCaustics::new(ctx, sh, s, lights, meshes)?),
            _ => match copy {
                Some(ty) => Selection::Copy(PhotonCopy::new(ctx, sh, ty, photon_side)?),
                None => Selection::Dense,
            },
        })
    }

    /// Light `l`'s selection from the photons its source made (the adaptive traversal's without
    /// its deposit: see `super::CausticPipeline::record`).
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        match self {
            Selection::Dense => Ok(()),
            Selection::Copy(copy) => copy.record(f, c.photons, l),
            Selection::Hierarchy(h, _) => h.record_traversal(f, c.inputs, c.photons, l),
            Selection::Adaptive(a) => a.record_traversal(f, c.inputs, l, None),
        }
    }

    /// The list a compute splat reads (None: the photon buffer's texels).
    pub fn splat_list(&self) -> Option<SplatList> {
        match self {
            Selection::Hierarchy(h, _) => Some(h.splat_list()),
            Selection::Adaptive(a) => Some(a.splat_list()),
            Selection::Dense | Selection::Copy(_) => None,
        }
    }

    /// Whether this stage has the light-space buffer `d` (it owns `hierarchy*` and `splats`
    /// with a hierarchy, `adaptive_*` with the adaptive traversal).
    pub fn has_dump(&self, d: &'static Dump) -> bool {
        let (hierarchy, adaptive) = (wyman2008::DUMPS.contains(&d), ADAPTIVE_DUMPS.contains(&d));
        match self {
            Selection::Hierarchy(..) => !adaptive,
            Selection::Adaptive(_) => !hierarchy,
            Selection::Dense | Selection::Copy(_) => !hierarchy && !adaptive,
        }
    }

    /// Makes what dumping `wanted` needs beyond the frame's passes.
    pub fn prepare_dumps(&mut self, ctx: &Context, sh: &ShaderCompiler, wanted: &[&'static Dump]) -> Result<()> {
        if let Selection::Hierarchy(_, footprints @ None) = self {
            if wanted.contains(&&SPLATS) {
                *footprints = Some(SplatFootprints::new(ctx, sh)?);
            }
        }
        Ok(())
    }

    /// Light `l`'s part of the light-space dump `d` that this stage owns, after the light's
    /// passes were recorded last (None: not this stage's).
    pub fn dump(&self, ctx: &Context, c: &CausticPasses, d: &'static Dump, l: u32) -> Result<Option<LightDump>> {
        let records = |channels, lists| Some(LightDump::Records { channels, lists });
        Ok(match self {
            Selection::Hierarchy(h, footprints) => match d {
                d if d == &HIERARCHY => Some(LightDump::Image(h.dump_levels(ctx)?)),
                d if d == &HIERARCHY_LISTS => {
                    records(&wyman2008::LIST_CHANNELS, wyman2008::list_records(&h.read_lists(ctx)?))
                }
                d if d == &SPLATS => {
                    let footprints = footprints.as_ref().context("no splat footprints pipeline")?;
                    let splats = footprints.read(ctx, h, c.inputs, c.photons, l)?;
                    let list = (String::new(), splat_footprints::splat_records(&splats));
                    records(&splat_footprints::CHANNELS, vec![list])
                }
                _ => None,
            },
            Selection::Adaptive(a) => match d {
                d if d == &ADAPTIVE_GEOMETRY => Some(LightDump::Image(a.dump_geometry(ctx)?)),
                d if d == &ADAPTIVE_LISTS => {
                    records(&adaptive::LIST_CHANNELS, adaptive::list_records(&adaptive_lists(ctx, c, a, l)?))
                }
                _ => None,
            },
            Selection::Dense | Selection::Copy(_) => None,
        })
    }
}

/// Light `l`'s adaptive lists, after its light-space passes were recorded last. A batched
/// traversal leaves only its last batch's, so it is recorded again part by part, and each part
/// read back: the breadth-first levels, then batch after batch. Level B's list is written once,
/// so every batch selects its slice of the same list (the compute path appends in no fixed
/// order: a traversal recorded again per batch could slice another).
fn adaptive_lists(ctx: &Context, c: &CausticPasses, a: &AdaptiveCaustics, l: u32) -> Result<adaptive::LightLists> {
    if !a.plan().batched() {
        return a.read_lists(ctx, None);
    }
    let mut lists = vec![];
    let parts = std::iter::once(Part::Breadth).chain((0..a.plan().batches).map(Part::Batch));
    for part in parts {
        let mut f = ctx.frame(FrameOptions::default())?;
        match part {
            Part::Breadth => {
                crate::techniques::shared::photon_buffer::record_receiver_positions(&mut f, c, l)?;
                a.record_breadth(&mut f, c.inputs, l, None)?;
            }
            Part::Batch(b) => a.record_batch(&mut f, c.inputs, l, b, None)?,
        }
        f.submit()?;
        lists.extend(a.read_lists(ctx, Some(part))?);
    }
    Ok(lists)
}
