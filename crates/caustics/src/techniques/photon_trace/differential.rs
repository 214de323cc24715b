//! The deposit of photon differentials (`differentials = true`; Schjøth, Frisvad, Erleben &
//! Sporring 2007, "Photon Differentials", GRAPHITE): each photon's footprint, which the tracer
//! carried through every transfer, reflection and refraction (Igehy 1999's ray differentials,
//! `shaders_glsl/photon_trace/trace.comp`), is splatted into the caustic map as the anisotropic
//! Gaussian it spans, its power kept whole (`shaders_glsl/photon_trace/differential_splat.comp`
//! says the kernel and the clamp at a caustic's fold). A compute pass with float atomics, as the
//! compute splat's, whose accumulation it shares (`shared::compute_splat::Accumulated`): the light's accumulation cleared, the photons
//! splatted, the sum stored in the light's caustic-map layer.

use super::push::DifferentialSplatConstants;
use crate::gpu::Stage;
use crate::techniques::shared::compute_splat::Accumulated;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{Bind, Context, Frame, Pipeline, ShaderCompiler};

/// The narrowest kernel, caustic-map texels (the standard deviation the clamp holds a collapsed
/// footprint to, at a caustic's fold).
pub const MIN_SIGMA: f32 = 0.5;
/// The widest kernel, caustic-map texels (where photons diverge; its support is 3 of them).
pub const MAX_SIGMA: f32 = 8.0;

pub struct DifferentialSplat {
    splat: Pipeline,
    /// One caustic-map layer, reused light after light.
    accumulated: Accumulated,
}

impl DifferentialSplat {
    /// A splat into caustic-map layers of `side`² texels.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, side: u32) -> Result<DifferentialSplat> {
        Ok(DifferentialSplat {
            splat: Pipeline::compute(
                ctx,
                "photon_trace differential splat",
                &sh.compile("photon_trace/differential_splat.comp", &[])?,
            )?,
            accumulated: Accumulated::new(ctx, sh, side, 1, "photon differentials", "use a smaller caustic map")?,
        })
    }

    /// Light `l`'s photons splatted by their footprints into its caustic-map layer.
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        let (inp, pt) = (c.inputs, c.photons);
        self.accumulated.record_clear(f, l)?;
        let binds = vec![
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
            ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
            ("photon_footprint_u", Bind::Sampled(&pt.footprint_u.view, inp.nearest)),
            ("photon_footprint_v", Bind::Sampled(&pt.footprint_v.view, inp.nearest)),
            ("Accumulated", Bind::Buffer(&self.accumulated.buffer)),
        ];
        let texels = pt.width * pt.width;
        f.pass(&Stage::Splat.light(l)).bind(&self.splat, binds).record(|cmd| {
            cmd.push(&DifferentialSplatConstants {
                photon_texels: texels,
                light: l,
                min_sigma: MIN_SIGMA,
                max_sigma: MAX_SIGMA,
            })?;
            let (x, y) = crate::techniques::shared::compute_splat::groups(texels);
            cmd.dispatch(x, y, 1);
            Ok(())
        })?;
        self.accumulated.record_resolve(f, &c.targets.per_light[l as usize].0, l)
    }
}
