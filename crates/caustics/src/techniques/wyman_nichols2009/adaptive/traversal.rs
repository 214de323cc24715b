//! The adaptive traversal of one light (Wyman & Nichols 2009 Sec. 3.2-4.2): its geometry
//! buffers, then one step per level from the 64² coarse grid down to the last level, each
//! step reading the pending clusters of its level (drawn or dispatched from the previous step's
//! counter: nothing is read back) and writing the next level's and the output photons.

use super::photon::{unpack_cell, AdaptivePhoton, CLUSTER_BYTES, HITS_BYTES, PHOTON_BYTES};
use super::{AdaptiveCaustics, Kernels};
use crate::gpu::{AdaptiveConstants, GpuMesh};
use crate::image_io::ImageF32;
use crate::techniques::wyman_nichols2009::geometry_buffers::Uniforms;
use crate::techniques::wyman_nichols2009::settings::tests_convergence;
use anyhow::Result;
use vkcore::{
    Access, Bind, Buffer, CompactStream, CompactionPath, Context, Frame, ImageView, Pipeline, Sampler, Targets, Use,
};

/// What the traversal reads besides its own buffers.
pub struct Inputs<'a> {
    pub frame_uniforms: &'a Buffer,
    pub caustic_uniforms: &'a Buffer,
    pub meshes: &'a [GpuMesh],
    /// Every light's receiver positions (the photon trace's receivers).
    pub receiver_positions: &'a ImageView,
    pub nearest: &'a Sampler,
}

/// Where a transform-feedback kernel writes.
enum XfbOut<'a> {
    /// A list whose capture starts at offset 0.
    List(&'a CompactStream),
    /// The output photons, appended after what earlier steps wrote.
    Photons,
}

impl AdaptiveCaustics {
    /// Light `l`'s geometry buffers and traversal: afterwards `photons` holds its output.
    pub fn record_traversal(&self, f: &mut Frame, inp: &Inputs, l: u32) -> Result<()> {
        let u = Uniforms { frame: inp.frame_uniforms, caustics: inp.caustic_uniforms };
        self.geometry.record(f, &u, inp.meshes, inp.nearest, l)?;
        self.record_reset(f, l)?;
        for k in 0..=self.finest {
            self.record_step(f, inp, l, k)?;
            // This light's counts: the next level's clusters and the photons so far.
            let slot = |i: u32| (l.min(self.lights.max(1) - 1) * 2 * (self.finest + 1) + i) as u64 * 4;
            let next = self.clusters.get(k as usize + 1);
            let mut uses = vec![
                Use::buffer(&self.photons.counter, Access::TRANSFER_READ),
                Use::buffer(&self.counts, Access::TRANSFER_WRITE),
            ];
            uses.extend(next.map(|s| Use::buffer(&s.counter, Access::TRANSFER_READ)));
            f.pass(&format!("adaptive.counts.level{k}.light{l}")).uses(uses).record(|cmd| {
                if let Some(s) = next {
                    cmd.copy_buffer_region(&s.counter, 0, &self.counts, slot(k + 1), 4);
                }
                cmd.copy_buffer_region(&self.photons.counter, 0, &self.counts, slot(self.finest + 1 + k), 4);
                Ok(())
            })?;
        }
        if let Kernels::Compute { finalize, .. } = &self.kernels {
            // The splat's draw (or dispatch) over the output photons.
            f.pass(&format!("adaptive.finalize.photons.light{l}"))
                .bind(finalize, [Bind::Buffer(&self.photons.counter)])
                .record(|cmd| {
                    cmd.dispatch(1, 1, 1);
                    Ok(())
                })?;
        }
        Ok(())
    }

    /// Zeroes the counters of every list the traversal writes (both paths).
    fn record_reset(&self, f: &mut Frame, l: u32) -> Result<()> {
        let written: Vec<&CompactStream> =
            self.clusters[1..].iter().chain([&self.photons, &self.spare]).chain(self.hits.as_ref()).collect();
        let uses: Vec<Use> = written.iter().map(|s| Use::buffer(&s.counter, Access::TRANSFER_WRITE)).collect();
        f.pass(&format!("adaptive.reset.light{l}")).uses(uses).record(|cmd| {
            for s in &written {
                match self.path {
                    CompactionPath::TransformFeedback => cmd.fill_buffer(&s.counter, 0),
                    CompactionPath::Compute => {
                        let header: Vec<u8> = [0u32, s.capacity, 0, 0].iter().flat_map(|x| x.to_le_bytes()).collect();
                        cmd.update_buffer(&s.counter, 0, &header)?;
                    }
                }
            }
            Ok(())
        })?;
        Ok(())
    }

    /// Bindings 0-7 of every traversal kernel (`adaptive.glsl`).
    fn textures<'a>(&'a self, inp: &Inputs<'a>) -> Vec<Bind<'a>> {
        let g = &self.geometry;
        vec![
            Bind::Uniform(inp.frame_uniforms),
            Bind::Uniform(inp.caustic_uniforms),
            Bind::Sampled(&g.back_faces, inp.nearest),
            Bind::Sampled(inp.receiver_positions, inp.nearest),
            Bind::Sampled(&g.position_layers, inp.nearest),
            Bind::Sampled(&g.normal_layers, inp.nearest),
            Bind::Sampled(&g.material_layers, inp.nearest),
            Bind::Sampled(&g.coverage_levels, inp.nearest),
        ]
    }

    /// The step at level k: the pending clusters of level k refined, discarded or output.
    fn record_step(&self, f: &mut Frame, inp: &Inputs, l: u32, k: u32) -> Result<()> {
        let input = &self.clusters[k as usize];
        let last = k == self.finest;
        let out = self.clusters.get(k as usize + 1).unwrap_or(&self.spare);
        let converge = tests_convergence(self.metric, k);
        let push = AdaptiveConstants { light: l, level: k, finest: self.finest, converge: converge as u32 };
        match &self.kernels {
            Kernels::Compute { traverse, finalize } => {
                let mut binds = self.textures(inp);
                binds.extend([
                    Bind::BufferRead(&input.data),
                    Bind::BufferRead(&input.counter),
                    Bind::Buffer(&out.data),
                    Bind::Buffer(&out.counter),
                    Bind::Buffer(&self.photons.data),
                    Bind::Buffer(&self.photons.counter),
                ]);
                // The input's count is read as dispatch arguments too.
                let arguments = [Use::buffer(&input.counter, Access::INDIRECT)];
                f.pass(&format!("adaptive.traverse.level{k}.light{l}")).bind(traverse, binds).uses(arguments).record(
                    |cmd| {
                        cmd.push(&push)?;
                        cmd.dispatch_indirect(&input.counter, 16);
                        Ok(())
                    },
                )?;
                if !last {
                    f.pass(&format!("adaptive.finalize.level{}.light{l}", k + 1))
                        .bind(finalize, [Bind::Buffer(&out.counter)])
                        .record(|cmd| {
                            cmd.dispatch(1, 1, 1);
                            Ok(())
                        })?;
                }
            }
            Kernels::Xfb(x) => {
                let mut from_clusters = |name: &str, pipeline: &Pipeline, to: XfbOut| {
                    self.record_xfb(f, &format!("adaptive.{name}.level{k}.light{l}"), pipeline, inp, &push, k, None, to)
                };
                match (converge, last) {
                    (false, false) => from_clusters("subdivide", &x.subdivide, XfbOut::List(out))?,
                    (false, true) => from_clusters("emit", &x.emit, XfbOut::Photons)?,
                    (true, _) => {
                        let hits = self.hits.as_ref().ok_or_else(|| anyhow::anyhow!("no hits stream"))?;
                        // Sec. 4.1's three kernels: hit positions, the converged stream, subdivision.
                        from_clusters("hits", &x.hits, XfbOut::List(hits))?;
                        let name = format!("adaptive.converged.level{k}.light{l}");
                        self.record_xfb(f, &name, &x.converged, inp, &push, k, Some(hits), XfbOut::Photons)?;
                        if !last {
                            let name = format!("adaptive.refine.level{k}.light{l}");
                            self.record_xfb(f, &name, &x.refine, inp, &push, k, Some(hits), XfbOut::List(out))?;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// One transform-feedback kernel of step k: a point per pending cluster of level k (or per
    /// cluster's hits, `from_hits`), drawn from the stream's byte count, writing `to`.
    #[allow(clippy::too_many_arguments)]
    fn record_xfb(
        &self,
        f: &mut Frame,
        name: &str,
        pipeline: &Pipeline,
        inp: &Inputs,
        push: &AdaptiveConstants,
        k: u32,
        from_hits: Option<&CompactStream>,
        to: XfbOut,
    ) -> Result<()> {
        let input = from_hits.unwrap_or(&self.clusters[k as usize]);
        let mut binds = self.textures(inp);
        let mut uses = vec![];
        match from_hits {
            Some(h) => binds.push(Bind::BufferRead(&h.data)),
            None => uses.push(Use::buffer(&input.data, Access::VERTEX_INPUT)),
        }
        // The coarse grid's clusters are drawn by their number; later streams by their counter.
        let seeded = from_hits.is_none() && k == 0;
        if !seeded {
            uses.push(Use::buffer(&input.counter, Access::INDIRECT));
        }
        let out = match to {
            XfbOut::List(s) => s,
            XfbOut::Photons => &self.photons,
        };
        uses.push(Use::buffer(&out.data, Access::XFB_WRITE));
        uses.push(Use::buffer(&out.counter, Access::XFB_COUNTER));
        let stride = if from_hits.is_some() { HITS_BYTES } else { CLUSTER_BYTES } as u32;
        f.pass(name).bind(pipeline, binds).uses(uses).record(|cmd| {
            cmd.begin_rendering(&Targets::none())?;
            cmd.push(push)?;
            if from_hits.is_none() {
                cmd.bind_vertex_buffer(&input.data, 0);
            }
            cmd.bind_xfb_buffers(&[&out.data])?;
            match to {
                // The photons are appended to what earlier steps wrote (their counter was zeroed
                // for this light).
                XfbOut::Photons => cmd.begin_xfb(&[&out.counter], true)?,
                XfbOut::List(_) => cmd.begin_xfb(&[], false)?,
            }
            if seeded {
                cmd.draw(input.capacity, 1, 0, 0);
            } else {
                cmd.draw_indirect_byte_count(1, &input.counter, stride)?;
            }
            cmd.end_xfb(&[&out.counter])?;
            cmd.end_rendering();
            Ok(())
        })?;
        Ok(())
    }

    /// Per light: each level's pending clusters (level 0 to L), then the photons output at each
    /// step (0 to L), after the last traversal.
    pub fn level_counts(&self, ctx: &Context) -> Result<Vec<(Vec<u64>, Vec<u64>)>> {
        let raw: Vec<u32> = ctx.read_buffer_as(&self.counts)?;
        let levels = (self.finest + 1) as usize;
        let elements = |c: u32, s: &CompactStream, bytes: u64| -> u64 {
            match self.path {
                CompactionPath::TransformFeedback => c as u64 / bytes,
                CompactionPath::Compute => (c as u64).min(s.capacity as u64),
            }
        };
        Ok((0..self.lights.max(1) as usize)
            .map(|l| {
                let at = |i: usize| raw.get(l * 2 * levels + i).copied().unwrap_or(0);
                let mut clusters = vec![self.clusters[0].capacity as u64];
                clusters.extend((1..levels).map(|k| elements(at(k), &self.clusters[k], CLUSTER_BYTES)));
                let mut emitted = vec![];
                let mut before = 0;
                for k in 0..levels {
                    let total = elements(at(levels + k), &self.photons, PHOTON_BYTES);
                    emitted.push(total - before.min(total));
                    before = total;
                }
                (clusters, emitted)
            })
            .collect())
    }

    /// The output photons of the light traversed last.
    pub fn read_photons(&self, ctx: &Context) -> Result<Vec<AdaptivePhoton>> {
        Ok(self.photons.read_as(ctx)?)
    }

    /// The pending clusters of each level (0 to L), (x, y, level), of the light traversed last.
    pub fn read_clusters(&self, ctx: &Context) -> Result<Vec<Vec<[u32; 3]>>> {
        let read = |s: &CompactStream| -> vkcore::Result<Vec<[u32; 3]>> {
            Ok(s.read_as::<u32>(ctx)?.into_iter().map(unpack_cell).collect())
        };
        Ok(self.clusters.iter().map(read).collect::<vkcore::Result<_>>()?)
    }
}

/// One light's traversal as read back: the pending clusters of each level, the output photons.
pub type LightLists = (Vec<Vec<[u32; 3]>>, Vec<AdaptivePhoton>);

/// `adaptive_lists.exr` from each light's clusters and photons: layer `light<l>.clusters<k>`
/// holds the pending clusters of level k (x, y, level; the cluster of photons (2x + i, 2y + j)
/// of level k), layer `light<l>.photons` the output photons (x, y, level of their cell, where
/// they land X, Y, Z, power R, G, B, solid angle omega); a record per pixel in row-major order,
/// valid = 1 for a record (the rest of the image is padding).
pub fn lists_image(per_light: &[LightLists]) -> ImageF32 {
    let mut lists = vec![];
    for (l, (clusters, photons)) in per_light.iter().enumerate() {
        for (k, list) in clusters.iter().enumerate() {
            let records = list
                .iter()
                .map(|c| vec![c[0] as f32, c[1] as f32, c[2] as f32, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0])
                .collect();
            lists.push((format!("light{l}.clusters{k}"), records));
        }
        let records = photons
            .iter()
            .map(|p| {
                let c = p.cell();
                let [x, y, z] = p.position;
                let [r, g, b] = p.power;
                vec![c[0] as f32, c[1] as f32, c[2] as f32, x, y, z, r, g, b, p.omega, 1.0]
            })
            .collect();
        lists.push((format!("light{l}.photons"), records));
    }
    crate::techniques::shared::records_image(
        lists,
        &["x", "y", "level", "X", "Y", "Z", "R", "G", "B", "omega", "valid"],
    )
}
