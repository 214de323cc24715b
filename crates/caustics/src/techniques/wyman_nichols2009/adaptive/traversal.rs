//! The adaptive traversal of one light (Wyman & Nichols 2009 Sec. 3.2-4.3): its geometry
//! buffers, then one step per level from the 64² coarse grid down to the last level, each
//! step reading the pending clusters of its level (drawn or dispatched from the previous step's
//! counter: nothing is read back) and writing the next level's and the output photons; under a
//! memory limit, breadth-first to level B, then batch after batch below it, each splatted
//! before the next (Sec. 4.3).

use super::super::push::{AdaptiveConstants, BatchConstants, CountConstants};
use super::photon::{unpack_cell, AdaptivePhoton};
use super::{AdaptiveCaustics, Kernels};
use crate::gpu::{BatchPart, PassName, Stage};
use crate::techniques::shared::compute_splat::{groups, ComputeSplat};
use crate::techniques::shared::lists;
use crate::techniques::shared::targets::PhotonTargets;
use crate::techniques::shared::FrameInputs;
use crate::techniques::wyman_nichols2009::geometry_buffers::Uniforms;
use crate::techniques::wyman_nichols2009::settings::tests_convergence;
use anyhow::Result;
use vkcore::{
    Access, Bind, CompactStream, CompactionPath, Context, Frame, ImageView, Named, Pipeline, StepInput, Targets, Use,
};

/// Where each batch's photons are splatted (none: the traversal alone, for the dumps).
pub struct Splat<'a> {
    pub inputs: &'a FrameInputs<'a>,
    /// The compute splat, else the point splat.
    pub compute: Option<&'a ComputeSplat>,
    pub photon_targets: &'a PhotonTargets,
    /// The light's caustic-map layers.
    pub cmap: &'a ImageView,
    /// How many: 4 for the multi-resolution map (varying-multires splats), else 1.
    pub layers: u32,
}

/// Where a transform-feedback kernel writes.
enum XfbOut<'a> {
    /// A list whose capture starts at offset 0.
    List(&'a CompactStream),
    /// The output photons, appended after what earlier steps wrote.
    Photons,
}

impl AdaptiveCaustics {
    /// Light `l`'s geometry buffers and traversal, and with `splat` the splat of its photons:
    /// breadth-first down to level B, then batch after batch below it, each splatted before the
    /// next (Sec. 4.3; one batch without a memory limit). Afterwards `photons` holds the last
    /// batch's output.
    pub fn record_traversal(&self, f: &mut Frame, inp: &FrameInputs, l: u32, splat: Option<&Splat>) -> Result<()> {
        let splatted = self.record_breadth(f, inp, l, splat)?;
        for batch in 0..self.plan.batches {
            self.record_batch(f, inp, l, batch, splat.map(|s| (s, !splatted && batch == 0)))?;
        }
        Ok(())
    }

    /// Light `l`'s geometry buffers and the breadth-first steps, levels 0 to B - 1, which write
    /// level B's pending clusters (and, with max-error, the photons of clusters that converged
    /// above it). Returns whether those photons were splatted (batched max-error traversals
    /// only: the batches reuse the photon list).
    pub fn record_breadth(&self, f: &mut Frame, inp: &FrameInputs, l: u32, splat: Option<&Splat>) -> Result<bool> {
        let u = Uniforms { frame: inp.frame_uniforms, caustics: inp.caustic_uniforms };
        self.geometry.record(f, &u, inp.meshes, inp.nearest, l)?;
        self.refractors.record(f, &u, inp.meshes, Stage::AdaptiveGeometry, l)?;
        let b = self.plan.breadth;
        self.record_reset(f, Stage::AdaptiveReset.light(l), 1, Some(l))?;
        for k in 0..b {
            self.record_step(f, inp, l, k, &self.clusters[k as usize], k == 0, BatchPart::Whole)?;
            self.record_counts(f, l, k, BatchPart::Whole)?;
        }
        if !(self.plan.batched() && (0..b).any(|k| tests_convergence(self.metric, k))) {
            return Ok(false);
        }
        // Clusters converged above level B: splatted before the batches reuse the photons.
        self.record_finalize_photons(f, l, BatchPart::Breadth)?;
        if let Some(s) = splat {
            self.record_splat_batch(f, s, l, BatchPart::Breadth, true, false)?;
        }
        Ok(true)
    }

    /// Batch `batch` of light `l` after [`Self::record_breadth`]: its slice of level B's
    /// pending clusters refined from level B to the last level, with `splat` (and whether it is
    /// the first splat into the caustic map) splatted. Level B's list and the levels above are
    /// only read, so batches can be recorded one at a time, in any frame after the breadth-first
    /// steps (the dumps read each batch so).
    pub fn record_batch(
        &self,
        f: &mut Frame,
        inp: &FrameInputs,
        l: u32,
        batch: u32,
        splat: Option<(&Splat, bool)>,
    ) -> Result<()> {
        let b = self.plan.breadth;
        let tag = if self.plan.batched() { BatchPart::Batch(batch) } else { BatchPart::Whole };
        let input = match &self.batch_input {
            Some(input) => {
                self.record_batch_input(f, l, batch, input, tag)?;
                self.record_reset(f, Stage::AdaptiveReset.pass().batch(tag).light(l), b as usize + 1, None)?;
                input
            }
            None => &self.clusters[b as usize],
        };
        for k in b..=self.finest {
            let input = if k == b { input } else { &self.clusters[k as usize] };
            let seeded = k == 0 && self.batch_input.is_none();
            self.record_step(f, inp, l, k, input, seeded, tag)?;
            self.record_counts(f, l, k, tag)?;
        }
        self.record_finalize_photons(f, l, tag)?;
        if let Some((s, first)) = splat {
            self.record_splat_batch(f, s, l, tag, first, batch + 1 == self.plan.batches)?;
        }
        Ok(())
    }

    /// The compute path's draw (or dispatch) over the output photons, for the splat.
    fn record_finalize_photons(&self, f: &mut Frame, l: u32, tag: BatchPart) -> Result<()> {
        if let Kernels::Compute { finalize, .. } = &self.kernels {
            finalize.record(f, &Stage::AdaptiveFinalizePhotons.pass().batch(tag).light(l), &self.photons)?;
        }
        Ok(())
    }

    /// Batch `batch`'s clusters of level B, copied from level B's list (`adaptive_batch.comp`).
    fn record_batch_input(
        &self,
        f: &mut Frame,
        l: u32,
        batch: u32,
        input: &CompactStream,
        tag: BatchPart,
    ) -> Result<()> {
        let pending = &self.clusters[self.plan.breadth as usize];
        let binds = [
            ("Pending", Bind::BufferRead(pending.data())),
            ("PendingCounter", Bind::BufferRead(pending.counter())),
            ("Batch", Bind::Buffer(input.data())),
            ("BatchCounter", Bind::Buffer(input.counter())),
        ];
        let push = BatchConstants {
            first: batch * self.plan.batch,
            size: self.plan.batch,
            xfb: (self.path == CompactionPath::TransformFeedback) as u32,
        };
        f.pass(&Stage::AdaptiveSelect.pass().batch(tag).light(l)).bind(&self.batch_select, binds).record(|cmd| {
            cmd.push(&push)?;
            let (x, y) = groups(self.plan.batch);
            cmd.dispatch(x, y, 1);
            Ok(())
        })?;
        Ok(())
    }

    /// After step k: the next level's pending clusters and the photons so far, added to light
    /// `l`'s counts (`adaptive_counts.comp`).
    fn record_counts(&self, f: &mut Frame, l: u32, k: u32, tag: BatchPart) -> Result<()> {
        let base = l.min(self.lights.max(1) - 1) * 2 * (self.finest + 1);
        let next = self.clusters.get(k as usize + 1);
        let binds = [
            ("Clusters", Bind::BufferRead(next.unwrap_or(&self.spare).counter())),
            ("Photons", Bind::BufferRead(self.photons.counter())),
            ("Counts", Bind::Buffer(&self.counts)),
        ];
        let push = CountConstants {
            cluster_slot: if next.is_some() { base + k + 1 } else { u32::MAX },
            photon_slot: base + self.finest + 1 + k,
            xfb: (self.path == CompactionPath::TransformFeedback) as u32,
        };
        f.pass(&Stage::AdaptiveCounts.pass().level(k).batch(tag).light(l)).bind(&self.count, binds).record(|cmd| {
            cmd.push(&push)?;
            cmd.dispatch(1, 1, 1);
            Ok(())
        })?;
        Ok(())
    }

    /// Zeroes the counters of the lists of levels `from`.. and of the hits and the photons
    /// (both paths); with `light`, also that light's counts.
    fn record_reset(&self, f: &mut Frame, name: PassName, from: usize, light: Option<u32>) -> Result<()> {
        let written: Vec<&CompactStream> =
            self.clusters[from..].iter().chain([&self.photons, &self.spare]).chain(self.hits.as_ref()).collect();
        let mut uses: Vec<Use> = written.iter().map(|s| s.reset_use()).collect();
        if light.is_some() {
            uses.push(Use::buffer(&self.counts, Access::TRANSFER_WRITE));
        }
        f.pass(&name).uses(uses).record(|cmd| {
            for s in &written {
                s.reset(cmd)?;
            }
            if let Some(l) = light {
                let slots = 2 * (self.finest + 1);
                let at = (l.min(self.lights.max(1) - 1) * slots) as u64 * 4;
                cmd.update_buffer(&self.counts, at, &vec![0u8; slots as usize * 4])?;
            }
            Ok(())
        })?;
        Ok(())
    }

    /// Bindings 0-8 of every traversal kernel (`adaptive.glsl`).
    fn textures<'a>(&'a self, inp: &FrameInputs<'a>) -> Vec<Named<'a>> {
        let g = &self.geometry;
        vec![
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("light_back_faces", Bind::Sampled(&g.back_faces, inp.nearest)),
            ("receiver_positions", Bind::Sampled(inp.receiver_positions, inp.nearest)),
            ("spot_textures", Bind::Sampled(inp.spot_textures, inp.linear)),
            ("geometry_position", Bind::Sampled(&g.position_layers, inp.nearest)),
            ("geometry_normal", Bind::Sampled(&g.normal_layers, inp.nearest)),
            ("geometry_material", Bind::Sampled(&g.material_layers, inp.nearest)),
            ("coverage", Bind::Sampled(&g.coverage_levels, inp.nearest)),
        ]
    }

    /// The step at level k over `input`, the pending clusters of level k (`seeded`: the coarse
    /// grid's, drawn by their number on the xfb path): refined, discarded or output.
    #[allow(clippy::too_many_arguments)]
    fn record_step(
        &self,
        f: &mut Frame,
        inp: &FrameInputs,
        l: u32,
        k: u32,
        input: &CompactStream,
        seeded: bool,
        tag: BatchPart,
    ) -> Result<()> {
        let last = k == self.finest;
        let out = self.clusters.get(k as usize + 1).unwrap_or(&self.spare);
        let converge = tests_convergence(self.metric, k);
        let push = AdaptiveConstants { light: l, level: k, finest: self.finest, converge: converge as u32 };
        let name = |kernel: Stage| kernel.pass().level(k).batch(tag).light(l);
        match &self.kernels {
            Kernels::Compute { traverse, finalize } => {
                let mut binds = self.textures(inp);
                binds.extend([
                    ("Input", Bind::BufferRead(input.data())),
                    ("InputCounter", Bind::BufferRead(input.counter())),
                    ("Output", Bind::Buffer(out.data())),
                    ("OutputCounter", Bind::Buffer(out.counter())),
                    ("Photons", Bind::Buffer(self.photons.data())),
                    ("PhotonCounter", Bind::Buffer(self.photons.counter())),
                ]);
                binds.extend(self.refractors.binds(inp.nearest));
                // The input's count is read as dispatch arguments too.
                f.pass(&name(Stage::AdaptiveTraverse)).bind(traverse, binds).uses([input.arguments_use()]).record(
                    |cmd| {
                        cmd.push(&push)?;
                        input.dispatch(cmd)
                    },
                )?;
                if !last {
                    finalize.record(f, &name(Stage::AdaptiveFinalize), out)?;
                }
            }
            Kernels::Xfb(x) => {
                // Clusters are drawn as vertices (`seeded`: the coarse grid's, by their number);
                // cluster hits are read by index.
                let clusters = StepInput { stream: input, seeded, as_vertices: true };
                match (converge, last) {
                    (false, false) => self.record_xfb(
                        f,
                        &name(Stage::AdaptiveSubdivide),
                        &x.subdivide,
                        inp,
                        &push,
                        &clusters,
                        XfbOut::List(out),
                    )?,
                    (false, true) => {
                        self.record_xfb(f, &name(Stage::AdaptiveEmit), &x.emit, inp, &push, &clusters, XfbOut::Photons)?
                    }
                    (true, _) => {
                        let hits = self.hits.as_ref().ok_or_else(|| anyhow::anyhow!("no hits stream"))?;
                        let from_hits = StepInput { stream: hits, seeded: false, as_vertices: false };
                        // Sec. 4.1's three kernels: hit positions, the converged stream, subdivision.
                        self.record_xfb(
                            f,
                            &name(Stage::AdaptiveHits),
                            &x.hits,
                            inp,
                            &push,
                            &clusters,
                            XfbOut::List(hits),
                        )?;
                        let converged = &x.converged;
                        self.record_xfb(
                            f,
                            &name(Stage::AdaptiveConverged),
                            converged,
                            inp,
                            &push,
                            &from_hits,
                            XfbOut::Photons,
                        )?;
                        if !last {
                            let refine = &x.refine;
                            self.record_xfb(
                                f,
                                &name(Stage::AdaptiveRefine),
                                refine,
                                inp,
                                &push,
                                &from_hits,
                                XfbOut::List(out),
                            )?;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// One transform-feedback kernel: a point per element of `from` (clusters as vertices, or
    /// cluster hits read by index), drawn from its byte count, writing `to`.
    #[allow(clippy::too_many_arguments)]
    fn record_xfb(
        &self,
        f: &mut Frame,
        name: &str,
        pipeline: &Pipeline,
        inp: &FrameInputs,
        push: &AdaptiveConstants,
        from: &StepInput,
        to: XfbOut,
    ) -> Result<()> {
        let mut binds = self.textures(inp);
        if !from.as_vertices {
            binds.push(("Hits", Bind::BufferRead(from.stream.data())));
        }
        binds.extend(self.refractors.binds(inp.nearest));
        let out = match to {
            XfbOut::List(s) => s,
            XfbOut::Photons => &self.photons,
        };
        // The photons are appended to what earlier steps wrote (their counter was zeroed for this
        // light or batch).
        let append = matches!(to, XfbOut::Photons);
        f.pass(name).bind(pipeline, binds).uses(out.capture_uses(*from)).record(|cmd| {
            cmd.begin_rendering(&Targets::none())?;
            cmd.push(push)?;
            out.capture(cmd, *from, append)?;
            cmd.end_rendering();
            Ok(())
        })?;
        Ok(())
    }

    /// Per light: each level's pending clusters (level 0 to L), then the photons output at each
    /// step (0 to L), summed over the batches, after the last traversal.
    pub fn level_counts(&self, ctx: &Context) -> Result<Vec<(Vec<u64>, Vec<u64>)>> {
        let levels = (self.finest + 1) as usize;
        let b = self.plan.breadth as usize;
        Ok(lists::read_counters(ctx, &self.counts, self.lights, 2 * levels)?
            .into_iter()
            .map(|counters| {
                let at = |i: usize| counters[i];
                let mut clusters = vec![self.clusters[0].capacity() as u64];
                clusters.extend((1..levels).map(at));
                // Photons so far after each step; each batch starts from none at level B.
                let so_far = |k: usize| at(levels + k);
                let emitted = (0..levels)
                    .map(|k| {
                        let before = if k == 0 || (self.plan.batched() && k == b) { 0 } else { so_far(k - 1) };
                        so_far(k).saturating_sub(before)
                    })
                    .collect();
                (clusters, emitted)
            })
            .collect())
    }

    /// The output photons of the light traversed last (with batches, of its last batch).
    pub fn read_photons(&self, ctx: &Context) -> Result<Vec<AdaptivePhoton>> {
        Ok(self.photons.read_as(ctx)?)
    }

    /// The lists of the light traversed last, named as `adaptive_lists.exr`'s layers under
    /// `light<l>.` ([`list_records`]). `part`: what was recorded last; `None`, the whole
    /// traversal of an unbatched plan: every level's pending clusters `clusters<k>`, the
    /// `photons`. [`Part::Breadth`] (batched plans): levels 0 to B's `clusters<k>`, the photons
    /// of clusters converged above B, `breadth.photons`. [`Part::Batch`]: the batch's slice of
    /// level B and its levels below, `batch<b>.clusters<k>`, its photons, `batch<b>.photons`.
    pub fn read_lists(&self, ctx: &Context, part: Option<Part>) -> Result<Vec<(String, Listed)>> {
        let read =
            |s: &CompactStream| -> Result<Listed> { Ok(Listed::Clusters(lists::read_packed(ctx, s, unpack_cell)?)) };
        let b = self.plan.breadth as usize;
        let (prefix, levels, photons) = match part {
            None => (String::new(), 0..self.clusters.len(), "photons".to_string()),
            Some(Part::Breadth) => (String::new(), 0..b + 1, "breadth.photons".to_string()),
            Some(Part::Batch(i)) => (format!("batch{i}."), b..self.clusters.len(), format!("batch{i}.photons")),
        };
        let mut out = vec![];
        for k in levels {
            // A batch's level B is its slice, copied into the batch input.
            let list = match (&part, &self.batch_input) {
                (Some(Part::Batch(_)), Some(input)) if k == b => input,
                _ => &self.clusters[k],
            };
            out.push((format!("{prefix}clusters{k}"), read(list)?));
        }
        out.push((photons, Listed::Photons(self.read_photons(ctx)?)));
        Ok(out)
    }
}

/// Which part of a batched traversal was recorded last, for [`AdaptiveCaustics::read_lists`].
#[derive(Clone, Copy, Debug)]
pub enum Part {
    /// The geometry buffers and the breadth-first steps ([`AdaptiveCaustics::record_breadth`]).
    Breadth,
    /// One batch ([`AdaptiveCaustics::record_batch`]).
    Batch(u32),
}

/// One list read back: pending clusters (x, y, level) or output photons.
pub enum Listed {
    Clusters(Vec<[u32; 3]>),
    Photons(Vec<AdaptivePhoton>),
}

/// One light's lists, named as their layers under `light<l>.`.
pub type LightLists = Vec<(String, Listed)>;

/// The channels of `adaptive_lists.exr` ([`list_records`]), as its declaration lists them.
pub use super::super::settings::LIST_CHANNELS;

/// One light's part of `adaptive_lists.exr`, from its lists ([`AdaptiveCaustics::read_lists`]):
/// a layer per list under `light<l>.`. Clusters: x, y, level of a pending cluster (the cluster
/// of photons (2x + i, 2y + j) of level k); photons: x, y, level of their cell, where they land
/// X, Y, Z, power R, G, B, varying splat radius `footprint`. A record per pixel in row-major
/// order, valid = 1 for a record (the rest of the image is padding).
pub fn list_records(named: &LightLists) -> Vec<(String, Vec<Vec<f32>>)> {
    let records = |list: &Listed| match list {
        Listed::Clusters(c) => c
            .iter()
            .map(|c| vec![c[0] as f32, c[1] as f32, c[2] as f32, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0])
            .collect(),
        Listed::Photons(p) => p
            .iter()
            .map(|p| {
                let c = p.cell();
                let [x, y, z] = p.position;
                let [r, g, b] = p.power;
                vec![c[0] as f32, c[1] as f32, c[2] as f32, x, y, z, r, g, b, p.footprint, 1.0]
            })
            .collect(),
    };
    named.iter().map(|(name, list)| (name.clone(), records(list))).collect()
}
