//! Splatting the traversal's final list (Wyman 2008 Sec. 3.1-3.3): each entry, a photon or a
//! cluster of converging photons, becomes a point splat; with varying splats its size comes
//! from its neighbours (Sec. 3.3, `shaders_glsl/wyman2008/varying_splat.glsl`) and, in the
//! multi-resolution map, it picks its layer with gl_Layer.

use super::Hierarchy;
use crate::gpu::{PassName, Stage};
use crate::techniques::shared::splat::{record_list_splat, ListSplat};
use crate::techniques::shared::targets::PhotonTargets;
use crate::techniques::shared::FrameInputs;
use anyhow::Result;
use vkcore::{Bind, Frame, ImageView, Pipeline};

impl Hierarchy {
    /// Splats the traversal's final list (photons and clusters) into `cmap`: one layer, or the
    /// `layers` levels of the multi-resolution map, each splat picking its layer (gl_Layer).
    pub fn record_splat(
        &self,
        f: &mut Frame,
        inp: &FrameInputs,
        pt: &PhotonTargets,
        cmap: &ImageView,
        layers: u32,
        l: u32,
    ) -> Result<()> {
        let to = ListSplat { cmap, layers, clear: true, light: l };
        self.record_splat_with(f, inp, pt, &Stage::Splat.light(l), &self.splat, to)
    }

    /// The final list's point splat through `pipeline` (a vertex shader of
    /// `shared/splat_points.glsl` with HIERARCHY), as pass `name`, into `to`.
    pub(crate) fn record_splat_with(
        &self,
        f: &mut Frame,
        inp: &FrameInputs,
        pt: &PhotonTargets,
        name: &PassName,
        pipeline: &Pipeline,
        to: ListSplat,
    ) -> Result<()> {
        let py = &self.pyramid;
        let binds = [
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
            ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
            ("hierarchy_power", Bind::Sampled(&py.all[0], inp.nearest)),
            ("hierarchy_position", Bind::Sampled(&py.all[1], inp.nearest)),
        ];
        record_list_splat(f, name, pipeline, binds, &self.lists[0], to)
    }

    /// What the compute splat reads: the hierarchy and the traversal's final list.
    pub fn final_list(&self) -> crate::techniques::shared::compute_splat::Photons<'_> {
        crate::techniques::shared::compute_splat::Photons::List {
            power: &self.pyramid.all[0],
            position: &self.pyramid.all[1],
            list: &self.lists[0],
        }
    }
}
