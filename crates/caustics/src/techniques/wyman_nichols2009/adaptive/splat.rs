//! Splatting the adaptive photons (Wyman & Nichols 2009 Sec. 3.2, step 3: "splat these photons
//! into a caustic map"): the shared point splat (`shared/splat.vert` with `ADAPTIVE_PHOTONS`),
//! the output list drawn as a vertex array of photons, its count from the traversal's counter
//! (nothing read back); or the compute splat over the same list.

use super::photon::PHOTON_BYTES;
use super::AdaptiveCaustics;
use crate::gpu::SplatConstants;
use crate::techniques::shared::compute_splat::Photons;
use crate::techniques::shared::PassInputs;
use anyhow::Result;
use vkcore::{Access, Bind, CompactionPath, Frame, ImageView, Targets, Use};

impl AdaptiveCaustics {
    /// Splats light `l`'s output photons into `cmap`, its caustic-map layer.
    pub fn record_splat(&self, f: &mut Frame, inp: &PassInputs, cmap: &ImageView, l: u32) -> Result<()> {
        let list = &self.photons;
        let binds = [Bind::Uniform(inp.frame_uniforms), Bind::Uniform(inp.caustic_uniforms)];
        let uses = [
            Use::buffer(&list.data, Access::VERTEX_INPUT),
            Use::buffer(&list.counter, Access::INDIRECT),
            Use::view(cmap, Access::COLOR_ATTACHMENT),
        ];
        f.pass(&format!("splat.light{l}")).bind(&self.splat, binds).uses(uses).record(|cmd| {
            cmd.begin_rendering(&Targets::color(cmap, Some([0.0; 4])))?;
            cmd.push(&SplatConstants { light: l, vertices_per_instance: 0 })?;
            cmd.bind_vertex_buffer(&list.data, 0);
            match self.path {
                CompactionPath::TransformFeedback => {
                    cmd.draw_indirect_byte_count(1, &list.counter, PHOTON_BYTES as u32)?
                }
                // The draw arguments of compact_counter.glsl start at byte 32.
                CompactionPath::Compute => cmd.draw_indirect(&list.counter, 32),
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
