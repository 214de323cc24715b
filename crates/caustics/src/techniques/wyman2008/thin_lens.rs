//! Wyman & Dachsbacher's varying splats from a per-photon thin-lens model (`splat = thin-lens`,
//! the second column of Wyman 2008 Fig. 7): the photon buffer's point splat with each splat's
//! radius from the photon's own ray through a thin lens (`shaders_glsl/wyman2008/thin_lens.glsl`
//! states the model; `thin_lens_splat.vert` is the point splat's vertex shader with it), into
//! the single caustic map. What it needs of the other settings is [`SplatMode::needs`]'s. The
//! baseline Sec. 3.3 improves on: it reads no neighbouring photon.

#[cfg(doc)]
use super::settings::SplatMode;
use crate::techniques::shared::pipelines::point_splat_desc;
use crate::techniques::shared::splat::PointSplat;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{Bind, Context, Frame, Pipeline, ShaderCompiler};

/// The point splat's vertex shader with the thin-lens radius.
const SHADER: &str = "wyman2008/thin_lens_splat.vert";

/// The thin-lens point splat.
pub struct ThinLensSplat {
    points: PointSplat,
}

impl ThinLensSplat {
    /// `per_instance`: vertices per instance of the instanced photon fetch.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, per_instance: u32) -> Result<ThinLensSplat> {
        let mut d = point_splat_desc(sh)?;
        d.name = "splat_thin_lens".into();
        d.vertex = sh.compile(SHADER, &[])?;
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

#[cfg(test)]
mod tests {
    use crate::gpu::SplatConstants;
    use vkcore::{check_push_constants, ShaderCompiler};

    /// The thin-lens vertex shader pushes the point splat's constants.
    #[test]
    fn thin_lens_splat_pushes_the_point_splats_constants() {
        let sh = ShaderCompiler::new(&crate::render::shader_root()).unwrap();
        check_push_constants::<SplatConstants>(&sh.compile(super::SHADER, &[]).unwrap()).unwrap();
    }
}
