//! The compute splat (`splat_path = compute`): the modern path beside the papers' point splats.
//! One invocation per photon adds its kernel to a float buffer with atomics
//! (`shaders_glsl/shared/splat.comp`), and a second pass stores the buffer in the light's
//! caustic-map layers. Texels, weights and multi-resolution layers come from the same GLSL as the
//! point splat's (`shared/splat_photon.glsl`), so both give the same caustic map up to the order
//! of the float additions (`tests/compute_splat.rs`).
//!
//! Passes per light, all named `splat.*` so that the tables' Gather columns count them:
//! `splat.clear` (zero the buffer), `splat.arguments` (hcm and adaptive on the xfb path: the
//! dispatch over the traversal's final list, from its byte count, nothing read back), `splat` and
//! `splat.resolve`.

use super::targets::PhotonTargets;
use crate::gpu::ComputeSplatConstants;
use crate::gpu::{BatchPart, Stage};
use anyhow::Result;
use vkcore::{
    Access, Bind, Buffer, CompactStream, CompactionPath, Context, Feature, Frame, ImageView, Memory, Pipeline,
    ShaderCompiler, Use,
};

/// Features the compute splat needs (`SplatPath::Compute`'s, in the settings layer, where
/// `CausticSettings::device_needs` lists them).
pub const FEATURES: &[Feature] = super::settings::COMPUTE_SPLAT_FEATURES;

/// Invocations per work group of splat.comp.
const GROUP: u32 = 64;

/// What the compute splat reads its photons from.
pub enum Photons<'a> {
    /// Every texel of the photon texture (invalid photons add nothing).
    Dense,
    /// The hierarchical traversal's final list (Wyman 2008 Sec. 3.1-3.2): photons and clusters.
    List {
        /// The photon hierarchy, every level: (power sum, count) and (position sum, 0).
        power: &'a ImageView,
        position: &'a ImageView,
        list: &'a CompactStream,
    },
    /// The adaptive traversal's output photons (Wyman & Nichols 2009 Sec. 3.2).
    Adaptive { list: &'a CompactStream },
}

/// Which traversal's list a compute splat reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ListKind {
    /// Packed entries of Wyman 2008's hierarchy.
    HierarchyEntries,
    /// Adaptive photons (Wyman & Nichols 2009).
    AdaptivePhotons,
}

/// The list a compute splat reads, as the traversal that writes it describes it
/// (`Hierarchy::splat_list`, `AdaptiveCaustics::splat_list`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SplatList {
    pub kind: ListKind,
    /// The traversal path that writes it.
    pub path: CompactionPath,
    /// The bytes of one element (`ENTRY_BYTES` in `shared/splat.comp`).
    pub element_bytes: u64,
}

use super::FrameInputs;

/// One batch of a splat made in batches: its number (None: no batches), and whether it is the
/// first (the sum is cleared) and the last (the sum is stored in the caustic map).
pub struct Batch {
    pub tag: BatchPart,
    pub first: bool,
    pub last: bool,
}

/// Where the dispatch over the traversal's final list finds its work groups.
enum ListDispatch {
    /// The compute traversal's append counter holds them (vkcore/compact_finalize.comp).
    AppendCounter,
    /// The xfb traversal's counter holds bytes: shared/splat_args.comp turns them into work
    /// groups in this buffer.
    ByteCount(Box<(Pipeline, Buffer)>),
}

/// What a compute splat adds its photons into with float atomics, and the pass that stores it in
/// the caustic map: one light's caustic-map layers as (power rgb, photon count) floats, layer by
/// layer, cleared before the light's splat and resolved after it (`shared/splat_resolve.comp`).
/// The compute splat's and photon differentials' (`photon_trace::differential`).
pub struct Accumulated {
    pub buffer: Buffer,
    resolve: Pipeline,
    side: u32,
    layers: u32,
}

impl Accumulated {
    /// `layers` caustic-map layers of `side`² texels for `who`'s splat; the error for a buffer
    /// the device cannot bind says `remedy`.
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        side: u32,
        layers: u32,
        who: &str,
        remedy: &str,
    ) -> Result<Accumulated> {
        let bytes = side as u64 * side as u64 * layers as u64 * 16;
        let limit = ctx.info().max_storage_buffer_range as u64;
        if bytes > limit {
            return Err(crate::input_error!(
                "caustics.caustic_map_resolution: {who} accumulates {layers} layer(s) of {side}² texels in one storage \
                 buffer of {bytes} bytes, more than this device's maxStorageBufferRange ({limit}); {remedy}"
            )
            .into());
        }
        Ok(Accumulated {
            buffer: Buffer::new(ctx, &format!("{who} accumulation"), bytes, Memory::Gpu)?,
            resolve: Pipeline::compute(ctx, "splat.resolve", &sh.compile("shared/splat_resolve.comp", &[])?)?,
            side,
            layers,
        })
    }

    /// Light `l`'s clear, before its first splat.
    pub fn record_clear(&self, f: &mut Frame, l: u32) -> Result<()> {
        f.pass(&Stage::SplatClear.light(l)).uses([Use::buffer(&self.buffer, Access::TRANSFER_WRITE)]).record(
            |cmd| {
                cmd.fill_buffer(&self.buffer, 0);
                Ok(())
            },
        )?;
        Ok(())
    }

    /// Stores the sum in `cmap`, light `l`'s caustic-map layers.
    pub fn record_resolve(&self, f: &mut Frame, cmap: &ImageView, l: u32) -> Result<()> {
        let resolve = [("caustic_map", Bind::Storage(cmap)), ("Accumulated", Bind::BufferRead(&self.buffer))];
        f.pass(&Stage::SplatResolve.light(l)).bind(&self.resolve, resolve).record(|cmd| {
            cmd.dispatch(self.side.div_ceil(8), self.side.div_ceil(8), self.layers);
            Ok(())
        })?;
        Ok(())
    }
}

pub struct ComputeSplat {
    accumulated: Accumulated,
    /// hcm, adaptive: what the dispatch over the traversal's final list reads its work groups
    /// from, and which list it is.
    list: Option<(ListDispatch, ListKind)>,
    splat: Pipeline,
}

impl ComputeSplat {
    /// A splat into `layers` caustic-map layers of `side`² texels; `list` is the traversal's list
    /// it splats (hcm, adaptive), None for the dense photon texture.
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        side: u32,
        layers: u32,
        list: Option<SplatList>,
    ) -> Result<ComputeSplat> {
        ctx.require("splat_path `compute` (float atomics in shared/splat.comp)", FEATURES)?;
        let remedy = "use a smaller caustic map or splat_path = \"raster\"";
        let accumulated = Accumulated::new(ctx, sh, side, layers, "the compute splat", remedy)?;
        let entry_bytes = list.map_or(4, |l| l.element_bytes).to_string();
        let mut defines = vec![("ENTRY_BYTES", entry_bytes.as_str())];
        let list = match list {
            // Binding 4: the accumulation buffer.
            None => None,
            Some(SplatList { kind, path, .. }) => {
                match kind {
                    // Bindings 4-8: the hierarchy, the accumulation buffer, the list and its counter.
                    ListKind::HierarchyEntries => defines.push(("HIERARCHY", "1")),
                    // Bindings 4-6: the accumulation buffer, the photons and their counter.
                    ListKind::AdaptivePhotons => defines.push(("ADAPTIVE_PHOTONS", "1")),
                }
                let dispatch = match path {
                    CompactionPath::Compute => ListDispatch::AppendCounter,
                    CompactionPath::TransformFeedback => {
                        defines.push(("XFB", "1"));
                        let args = Pipeline::compute(
                            ctx,
                            "splat.arguments",
                            &sh.compile("shared/splat_args.comp", &defines)?,
                        )?;
                        ListDispatch::ByteCount(Box::new((
                            args,
                            Buffer::new(ctx, "compute splat arguments", 16, Memory::Gpu)?,
                        )))
                    }
                };
                Some((dispatch, kind))
            }
        };
        let splat = Pipeline::compute(ctx, "splat.compute", &sh.compile("shared/splat.comp", &defines)?)?;
        Ok(ComputeSplat { accumulated, list, splat })
    }

    /// Splats light `l`'s photons into `cmap`, the light's caustic-map layers.
    pub fn record(
        &self,
        f: &mut Frame,
        inp: &FrameInputs,
        pt: &PhotonTargets,
        photons: &Photons,
        cmap: &ImageView,
        l: u32,
    ) -> Result<()> {
        self.record_batch(f, inp, pt, photons, cmap, l, &Batch { tag: BatchPart::Whole, first: true, last: true })
    }

    /// [`Self::record`] for one batch of photons (adaptive caustic maps' batches, Wyman &
    /// Nichols 2009 Sec. 4.3): the first clears the sum, the last stores it in `cmap`.
    #[allow(clippy::too_many_arguments)]
    pub fn record_batch(
        &self,
        f: &mut Frame,
        inp: &FrameInputs,
        pt: &PhotonTargets,
        photons: &Photons,
        cmap: &ImageView,
        l: u32,
        batch: &Batch,
    ) -> Result<()> {
        let tag = batch.tag;
        let texels = pt.width * pt.width;
        // Check before recording anything.
        let kind = self.list.as_ref().map(|(_, kind)| *kind);
        let given = match photons {
            Photons::Dense => None,
            Photons::List { .. } => Some(ListKind::HierarchyEntries),
            Photons::Adaptive { .. } => Some(ListKind::AdaptivePhotons),
        };
        if kind != given {
            anyhow::bail!("compute splat: built for {kind:?} (None: the photon texture), given {given:?}");
        }
        if batch.first {
            self.accumulated.record_clear(f, l)?;
        }
        let mut binds =
            vec![("frame", Bind::Uniform(inp.frame_uniforms)), ("caustics", Bind::Uniform(inp.caustic_uniforms))];
        // Adaptive photons carry their own position and power (`ADAPTIVE_PHOTONS`).
        if !matches!(photons, Photons::Adaptive { .. }) {
            binds.extend([
                ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
                ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
            ]);
        }
        // The indirect dispatch's arguments (buffer, byte offset); None: a grid over the texels.
        let mut indirect = None;
        match photons {
            Photons::Dense => binds.push(("Accumulated", Bind::Buffer(&self.accumulated.buffer))),
            Photons::List { list, .. } | Photons::Adaptive { list } => {
                match &self.list {
                    Some((ListDispatch::ByteCount(b), _)) => {
                        let (pipeline, args) = &**b;
                        f.pass(&Stage::SplatArguments.pass().batch(tag).light(l))
                            .bind(
                                pipeline,
                                [("Counter", Bind::BufferRead(list.counter())), ("Arguments", Bind::Buffer(args))],
                            )
                            .record(|cmd| {
                                cmd.dispatch(1, 1, 1);
                                Ok(())
                            })?;
                        indirect = Some((args, 0));
                    }
                    _ => indirect = Some((list.counter(), vkcore::AppendCounter::DISPATCH_OFFSET)),
                }
                if let Photons::List { power, position, .. } = photons {
                    binds.extend([
                        ("hierarchy_power", Bind::Sampled(power, inp.nearest)),
                        ("hierarchy_position", Bind::Sampled(position, inp.nearest)),
                    ]);
                }
                let list_data = if matches!(photons, Photons::Adaptive { .. }) { "Records" } else { "Entries" };
                binds.extend([
                    ("Accumulated", Bind::Buffer(&self.accumulated.buffer)),
                    (list_data, Bind::BufferRead(list.data())),
                    ("Counter", Bind::BufferRead(list.counter())),
                ]);
            }
        }
        let arguments = indirect.map(|(args, _)| Use::buffer(args, Access::INDIRECT));
        f.pass(&Stage::Splat.pass().batch(tag).light(l)).bind(&self.splat, binds).uses(arguments).record(|cmd| {
            cmd.push(&ComputeSplatConstants { photon_texels: texels, light: l })?;
            match indirect {
                Some((args, offset)) => cmd.dispatch_indirect(args, offset)?,
                None => {
                    let (x, y) = groups(texels);
                    cmd.dispatch(x, y, 1);
                }
            }
            Ok(())
        })?;
        if !batch.last {
            return Ok(());
        }
        self.accumulated.record_resolve(f, cmap, l)
    }
}

/// (x, y) work groups of [`GROUP`] invocations covering `n` in balanced rows
/// ([`vkcore::dispatch_grid`]; splat.comp flattens the grid row by row).
pub(crate) fn groups(n: u32) -> (u32, u32) {
    vkcore::dispatch_grid(n.div_ceil(GROUP))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_covers_every_photon_within_the_group_count_limit() {
        for n in [1u32, 63, 64, 65, 4096 * 4096, 65535 * 64 + 1, u32::MAX / 2] {
            let (x, y) = groups(n);
            assert!(x <= 65535 && y <= 65535, "{n}: {x} x {y}");
            assert!(x as u64 * y as u64 * GROUP as u64 >= n as u64, "{n}: {x} x {y} groups miss photons");
            assert!((x as u64 * (y as u64 - 1)) * (GROUP as u64) < n as u64, "{n}: a whole row of groups is idle");
        }
    }
}
