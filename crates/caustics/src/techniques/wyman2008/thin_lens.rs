//! Wyman & Dachsbacher's varying splats from a per-photon thin-lens model (`splat = thin-lens`,
//! the second column of Wyman 2008 Fig. 7): the photon buffer's point splat with each splat's
//! radius from the photon's own ray through a thin lens (`shaders_glsl/wyman2008/thin_lens.glsl`
//! states the model), into the single caustic map. The baseline Sec. 3.3 improves on: it reads
//! no neighbouring photon.

use crate::techniques::shared::pipelines::point_splat_desc;
use crate::techniques::shared::splat::PointSplat;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{Bind, Context, Frame, Pipeline, ShaderCompiler};

/// The thin-lens point splat.
pub struct ThinLensSplat {
    points: PointSplat,
}

impl ThinLensSplat {
    /// `per_instance`: vertices per instance of the instanced photon fetch.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, per_instance: u32) -> Result<ThinLensSplat> {
        let mut d = point_splat_desc(sh)?;
        d.name = "splat_thin_lens".into();
        d.vertex = sh.compile("shared/splat.vert", &[("THIN_LENS", "1")])?;
        Ok(ThinLensSplat { points: PointSplat::with_pipeline(ctx, Pipeline::graphics(ctx, &d)?, per_instance)? })
    }

    /// Splats light `l`'s photons, each with its thin-lens radius: the point splat, reading
    /// also the photons' directions and the light-space back faces (the lens).
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        let (pt, inp) = (c.photons, c.inputs);
        let more = [
            ("photon_direction", Bind::Sampled(&pt.direction.view, inp.nearest)),
            ("light_back_faces", Bind::Sampled(&pt.back_faces.view, inp.nearest)),
        ];
        self.points.record_with(f, c, l, more)
    }
}
