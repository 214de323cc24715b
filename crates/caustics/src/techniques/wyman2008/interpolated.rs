//! Wyman & Dachsbacher's multiple splat sizes (`splat = interpolated`, the third column of
//! Wyman 2008 Fig. 7), the baseline Sec. 3.3 improves on: it "interpolates between splats with
//! four different radii, but this requires all photons to be rasterized with the largest splat
//! size". Every entry of the hierarchy's final list is splatted at `splat_radius` 2^i into layer
//! i of the light's four full-resolution layers (`shared/splat_photon.glsl` with
//! INTERPOLATED_LEVEL); the lookup (`common/caustic_lookup.glsl`, `interpolated_power`) picks
//! and interpolates the radius texel by texel from the photon density. Drawn as four point
//! splats, one per radius, rather than one sprite of the largest radius writing four targets:
//! the same texels and weights, 85/64 of that sprite's fragments (1 + 4 + 16 + 64 against 64).

use super::settings::INTERPOLATED_LEVELS;
use super::Hierarchy;
use crate::gpu::Stage;
use crate::techniques::shared::pipelines::point_splat_desc;
use crate::techniques::shared::splat::ListSplat;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{Context, Frame, Pipeline, ShaderCompiler};

/// The four radii's point splats of the hierarchy's final list.
pub struct InterpolatedSplat {
    /// Level i's splat: radius `splat_radius` 2^i into layer i.
    levels: Vec<Pipeline>,
}

impl InterpolatedSplat {
    pub fn new(ctx: &Context, sh: &ShaderCompiler) -> Result<InterpolatedSplat> {
        let levels = (0..INTERPOLATED_LEVELS)
            .map(|i| {
                let mut d = point_splat_desc(sh)?;
                d.name = format!("splat_interpolated{i}");
                let level = i.to_string();
                d.vertex = sh.compile("shared/splat.vert", &[("HIERARCHY", "1"), ("INTERPOLATED_LEVEL", &level)])?;
                d.vertex_layout = Some(super::entry_layout());
                Ok(Pipeline::graphics(ctx, &d)?)
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(InterpolatedSplat { levels })
    }

    /// Splats light `l`'s final list four times (`splat.level<i>.light<l>`), the first draw
    /// clearing the light's layers.
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, h: &Hierarchy, l: u32) -> Result<()> {
        let cmap = &c.targets.per_light[l as usize].0;
        for (i, pipeline) in self.levels.iter().enumerate() {
            let to = ListSplat { cmap, layers: c.targets.levels, clear: i == 0, light: l };
            let name = Stage::Splat.pass().level(i as u32).light(l);
            h.record_splat_with(f, c.inputs, c.photons, &name, pipeline, to)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::gpu::SplatConstants;
    use vkcore::{check_push_constants, ShaderCompiler};

    /// Every level's vertex shader pushes the point splat's constants.
    #[test]
    fn interpolated_splats_push_the_point_splats_constants() {
        let sh = ShaderCompiler::new(&crate::render::shader_root()).unwrap();
        for level in ["0", "3"] {
            let spv = sh.compile("shared/splat.vert", &[("HIERARCHY", "1"), ("INTERPOLATED_LEVEL", level)]).unwrap();
            check_push_constants::<SplatConstants>(&spv).unwrap();
        }
    }
}
