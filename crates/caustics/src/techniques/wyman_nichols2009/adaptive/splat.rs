//! Splatting the adaptive photons (Wyman & Nichols 2009 Sec. 3.2, step 3: "splat these photons
//! into a caustic map"): the shared point splat (`shared/splat.vert` with `ADAPTIVE_PHOTONS`),
//! the output list drawn as a vertex array of photons, its count from the traversal's counter
//! (nothing read back); or the compute splat over the same list. Batch after batch (Sec. 4.3)
//! each adds its photons to the map.

use super::photon::PHOTON_BYTES;
use super::{AdaptiveCaustics, Splat};
use crate::gpu::SplatConstants;
use crate::gpu::{BatchPart, Stage};
use crate::techniques::shared::compute_splat::{self, Photons};
use anyhow::Result;
use vkcore::{Access, Bind, CompactionPath, Frame, Targets, Use};

impl AdaptiveCaustics {
    /// Splats the output photons of light `l` (of batch `tag`, where there are batches) into its caustic-map layer
    /// by `s`'s splat: the first batch clears the map, later ones add to it (Sec. 4.3), and the
    /// compute splat stores its sum in the map after the last.
    pub fn record_splat_batch(
        &self,
        f: &mut Frame,
        s: &Splat,
        l: u32,
        tag: BatchPart,
        first: bool,
        last: bool,
    ) -> Result<()> {
        if let Some(cs) = s.compute {
            let batch = compute_splat::Batch { tag, first, last };
            return cs.record_batch(f, &s.passes, s.photon_targets, &self.photon_list(), s.cmap, l, &batch);
        }
        let list = &self.photons;
        let inp = &s.passes;
        let binds = [("frame", Bind::Uniform(inp.frame_uniforms)), ("caustics", Bind::Uniform(inp.caustic_uniforms))];
        let uses = [
            Use::buffer(&list.data, Access::VERTEX_INPUT),
            Use::buffer(&list.counter, Access::INDIRECT),
            Use::view(s.cmap, Access::COLOR_ATTACHMENT),
        ];
        f.pass(&Stage::Splat.pass().batch(tag).light(l)).bind(&self.splat, binds).uses(uses).record(|cmd| {
            cmd.begin_rendering(&Targets::color(s.cmap, first.then_some([0.0; 4])).layered(s.layers))?;
            cmd.push(&SplatConstants { light: l, vertices_per_instance: 0 })?;
            cmd.bind_vertex_buffer(&list.data, 0)?;
            match self.path {
                CompactionPath::TransformFeedback => {
                    cmd.draw_indirect_byte_count(1, &list.counter, PHOTON_BYTES as u32)?
                }
                // The draw arguments of compact_counter.glsl start at byte 32.
                CompactionPath::Compute => cmd.draw_indirect(&list.counter, 32)?,
            }
            cmd.end_rendering();
            Ok(())
        })?;
        Ok(())
    }

    /// What the compute splat reads: the output photons.
    pub fn photon_list(&self) -> Photons<'_> {
        Photons::Adaptive { list: &self.photons }
    }
}
