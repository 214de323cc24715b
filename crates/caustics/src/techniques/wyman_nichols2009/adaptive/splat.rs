//! Splatting the adaptive photons (Wyman & Nichols 2009 Sec. 3.2, step 3: "splat these photons
//! into a caustic map"): the shared point splat (`shared/splat.vert` with `ADAPTIVE_PHOTONS`),
//! the output list drawn as a vertex array of photons, its count from the traversal's counter
//! (nothing read back); or the compute splat over the same list. Batch after batch (Sec. 4.3)
//! each adds its photons to the map.

use super::{AdaptiveCaustics, Splat};
use crate::gpu::{BatchPart, Stage};
use crate::techniques::shared::compute_splat::{self, Photons};
use crate::techniques::shared::splat::{record_list_splat, ListSplat};
use anyhow::Result;
use vkcore::{Bind, Frame};

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
            return cs.record_batch(f, s.inputs, s.photon_targets, &self.photon_list(), s.cmap, l, &batch);
        }
        let list = &self.photons;
        let inp = s.inputs;
        let binds = [("frame", Bind::Uniform(inp.frame_uniforms)), ("caustics", Bind::Uniform(inp.caustic_uniforms))];
        let to = ListSplat { cmap: s.cmap, layers: s.layers, clear: first, light: l };
        record_list_splat(f, &Stage::Splat.pass().batch(tag).light(l), &self.splat, binds, list, to)
    }

    /// What the compute splat reads: the output photons.
    pub fn photon_list(&self) -> Photons<'_> {
        Photons::Adaptive { list: &self.photons }
    }
}
