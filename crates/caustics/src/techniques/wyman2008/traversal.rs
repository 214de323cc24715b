//! The breadth-first traversal of the photon hierarchy (Wyman 2008 Sec. 3.1), from its 16²
//! level down to the photon buffer, discarding empty subtrees and, with clustering, stopping at
//! nodes whose photons converge into one caustic-map texel (Sec. 3.2). Two paths give the same
//! entries: a geometry shader per level writing transform-feedback buffers, the next level drawn
//! with vkCmdDrawIndirectByteCountEXT (the paper's), or a compute kernel appending with an atomic
//! counter and dispatching the next level indirectly. Nothing is read back between levels.

use super::entry::unpack_entry;
use super::push::TraverseConstants;
use super::Hierarchy;
use crate::gpu::Stage;
use crate::techniques::shared::lists;
use crate::techniques::shared::targets::PhotonTargets;
use crate::techniques::shared::FrameInputs;
use anyhow::Result;
use vkcore::{Access, Bind, CompactionPath, Context, Frame, StepInput, Targets, Use};

impl Hierarchy {
    /// Builds the hierarchy over light `l`'s photon buffer and traverses it (Sec. 3.1-3.2).
    pub fn record_traversal(&self, f: &mut Frame, inp: &FrameInputs, pt: &PhotonTargets, l: u32) -> Result<()> {
        self.record_build(f, inp, pt, l)?;
        let py = &self.pyramid;
        let push = |cluster: bool| TraverseConstants { light: l, cluster: cluster as u32, photon_side: self.n };
        // The paper zeroes its counters before every traversal; so do we (both paths).
        let counters: Vec<Use> = self.lists.iter().map(|s| s.reset_use()).collect();
        f.pass(&Stage::HierarchyReset.light(l)).uses(counters).record(|cmd| {
            for s in &self.lists {
                s.reset(cmd)?;
            }
            Ok(())
        })?;
        for k in (1..=self.levels).rev() {
            let input = if k == self.levels { &self.seed } else { &self.lists[k as usize] };
            let out = &self.lists[k as usize - 1];
            let mut binds = vec![
                ("frame", Bind::Uniform(inp.frame_uniforms)),
                ("caustics", Bind::Uniform(inp.caustic_uniforms)),
                ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
                ("hierarchy_power", Bind::Sampled(&py.all[0], inp.nearest)),
                ("hierarchy_texels", Bind::Sampled(&py.all[2], inp.nearest)),
            ];
            let name = Stage::HierarchyTraverse.pass().level(k).light(l);
            let cluster = self.cluster.tests(k);
            match self.path {
                CompactionPath::TransformFeedback => {
                    let from = StepInput { stream: input, seeded: k == self.levels, as_vertices: true };
                    f.pass(&name).bind(&self.traverse, binds).uses(out.capture_uses(from)).record(|cmd| {
                        cmd.begin_rendering(&Targets::none())?;
                        cmd.push(&push(cluster))?;
                        out.capture(cmd, from, false)?;
                        cmd.end_rendering();
                        Ok(())
                    })?;
                }
                CompactionPath::Compute => {
                    binds.extend([
                        ("Input", Bind::BufferRead(input.data())),
                        ("InputCounter", Bind::BufferRead(input.counter())),
                        ("Output", Bind::Buffer(out.data())),
                        ("OutputCounter", Bind::Buffer(out.counter())),
                    ]);
                    // The input's count is read as dispatch arguments too.
                    f.pass(&name).bind(&self.traverse, binds).uses([input.arguments_use()]).record(|cmd| {
                        cmd.push(&push(cluster))?;
                        input.dispatch(cmd)
                    })?;
                    let finalize = self.finalize.as_ref().ok_or_else(|| anyhow::anyhow!("no finalize pipeline"))?;
                    finalize.record(f, &Stage::HierarchyFinalize.pass().level(k).light(l), out)?;
                }
            }
        }
        // Keep this light's list sizes for the photon-count tables (read after the frame).
        let mut uses: Vec<Use> = self.lists.iter().map(|s| Use::buffer(s.counter(), Access::TRANSFER_READ)).collect();
        uses.push(Use::buffer(&self.counts, Access::TRANSFER_WRITE));
        f.pass(&Stage::HierarchyCounts.light(l)).uses(uses).record(|cmd| {
            for (k, s) in self.lists.iter().enumerate() {
                let slot = (l.min(self.lights.max(1) - 1) * self.levels + k as u32) as u64 * 4;
                cmd.copy_buffer_region(s.counter(), 0, &self.counts, slot, 4);
            }
            Ok(())
        })?;
        Ok(())
    }

    /// Per light: the size of each list from level L (the seed) down to 0 (the splatted
    /// photons and clusters) after the last traversal.
    pub fn list_sizes(&self, ctx: &Context) -> Result<Vec<Vec<u64>>> {
        let counters = lists::read_counters(ctx, &self.counts, self.lights, self.levels as usize)?;
        Ok(counters
            .into_iter()
            .map(|c| {
                let mut v = vec![self.seed.capacity() as u64];
                v.extend((0..c.len()).rev().map(|k| self.lists[k].elements(c[k] as u32) as u64));
                v
            })
            .collect())
    }

    /// The final list of the last traversal (photons at level 0, clusters flagged final).
    pub fn final_entries(&self, ctx: &Context) -> Result<Vec<[u32; 4]>> {
        lists::read_packed(ctx, &self.lists[0], unpack_entry)
    }

    /// The traversal's lists of the light traversed last: `[k]` is the list the step at level
    /// k+1 wrote (level-k nodes and the clusters finished above), `[0]` what was splatted.
    pub fn read_lists(&self, ctx: &Context) -> Result<Vec<Vec<[u32; 4]>>> {
        self.lists.iter().map(|list| lists::read_packed(ctx, list, unpack_entry)).collect()
    }
}

/// The channels of `hierarchy_lists.exr` ([`list_records`]), as its declaration lists them.
pub use super::settings::LIST_CHANNELS;

/// One light's part of `hierarchy_lists.exr`, from its [`Hierarchy::read_lists`]: list k as
/// layer `list<k>` (under `light<l>.`), an entry per pixel in row-major order: x, y, level,
/// final (1 = a cluster of converging photons), valid (1 = an entry; the rest of the image is
/// padding). The layout over all lights: `crate::techniques::shared::records_image`.
pub fn list_records(lists: &[Vec<[u32; 4]>]) -> Vec<(String, Vec<Vec<f32>>)> {
    let record = |e: &[u32; 4]| vec![e[0] as f32, e[1] as f32, e[2] as f32, e[3] as f32, 1.0];
    lists.iter().enumerate().map(|(k, list)| (format!("list{k}"), list.iter().map(record).collect())).collect()
}
