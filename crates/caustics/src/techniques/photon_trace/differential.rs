//! The deposit of photon differentials (`differentials = true`; Schjøth, Frisvad, Erleben &
//! Sporring 2007, "Photon Differentials", GRAPHITE): each photon's footprint, which the tracer
//! carried through every transfer, reflection and refraction (Igehy 1999's ray differentials,
//! `shaders_glsl/photon_trace/trace.comp`), is splatted into the caustic map as the anisotropic
//! Gaussian it spans, its power kept whole (`shaders_glsl/photon_trace/differential_splat.comp`
//! says the kernel and the clamp at a caustic's fold). A compute pass with float atomics, as the
//! compute splat's (`shared::ComputeSplat`): the light's accumulation cleared, the photons
//! splatted, the sum stored in the light's caustic-map layer.

use super::push::DifferentialSplatConstants;
use crate::gpu::Stage;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{Access, Bind, Buffer, Context, Frame, Memory, Pipeline, ShaderCompiler, Use};

/// The narrowest kernel, caustic-map texels (the standard deviation the clamp holds a collapsed
/// footprint to, at a caustic's fold).
pub const MIN_SIGMA: f32 = 0.5;
/// The widest kernel, caustic-map texels (where photons diverge; its support is 3 of them).
pub const MAX_SIGMA: f32 = 8.0;

pub struct DifferentialSplat {
    splat: Pipeline,
    resolve: Pipeline,
    /// One caustic-map layer of (power rgb, photons), reused light after light.
    accumulated: Buffer,
    side: u32,
}

impl DifferentialSplat {
    /// A splat into caustic-map layers of `side`² texels.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, side: u32) -> Result<DifferentialSplat> {
        let bytes = side as u64 * side as u64 * 16;
        let limit = ctx.info().max_storage_buffer_range as u64;
        if bytes > limit {
            return Err(crate::input_error!(
                "caustics.caustic_map_resolution: photon differentials accumulate {side}² texels in one storage \
                 buffer of {bytes} bytes, more than this device's maxStorageBufferRange ({limit})"
            )
            .into());
        }
        Ok(DifferentialSplat {
            splat: Pipeline::compute(
                ctx,
                "photon_trace differential splat",
                &sh.compile("photon_trace/differential_splat.comp", &[])?,
            )?,
            resolve: Pipeline::compute(
                ctx,
                "photon_trace differential resolve",
                &sh.compile("shared/splat_resolve.comp", &[])?,
            )?,
            accumulated: Buffer::new(ctx, "photon differentials accumulation", bytes, Memory::Gpu)?,
            side,
        })
    }

    /// Light `l`'s photons splatted by their footprints into its caustic-map layer.
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        let (inp, pt) = (c.inputs, c.photons);
        let cmap = &c.targets.per_light[l as usize].0;
        f.pass(&Stage::SplatClear.light(l)).uses([Use::buffer(&self.accumulated, Access::TRANSFER_WRITE)]).record(
            |cmd| {
                cmd.fill_buffer(&self.accumulated, 0);
                Ok(())
            },
        )?;
        let binds = vec![
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
            ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
            ("photon_footprint_u", Bind::Sampled(&pt.footprint_u.view, inp.nearest)),
            ("photon_footprint_v", Bind::Sampled(&pt.footprint_v.view, inp.nearest)),
            ("Accumulated", Bind::Buffer(&self.accumulated)),
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
        let resolve = [("caustic_map", Bind::Storage(cmap)), ("Accumulated", Bind::BufferRead(&self.accumulated))];
        f.pass(&Stage::SplatResolve.light(l)).bind(&self.resolve, resolve).record(|cmd| {
            cmd.dispatch(self.side.div_ceil(8), self.side.div_ceil(8), 1);
            Ok(())
        })?;
        Ok(())
    }
}
