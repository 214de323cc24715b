//! The `splats` dump of `hcm`: every entry of the traversal's final list as the splat passes
//! splat it (`shaders_glsl/wyman2008/splat_footprints.comp`, from the same
//! `shared/splat_photon.glsl`): centre, radius and layer of the caustic map, power and photons.
//! This is where varying splat sizes (Wyman 2008 Sec. 3.3) can be read, photon by photon.

use super::push::FootprintConstants;
use super::Hierarchy;
use crate::gpu::Stage;
use crate::techniques::shared::compute_splat::{groups, Photons};
use crate::techniques::shared::targets::PhotonTargets;
use crate::techniques::shared::FrameInputs;
use anyhow::Result;
use vkcore::{Bind, Buffer, Context, FrameOptions, Memory, Pipeline, ShaderCompiler};

/// One splat: centre x, y and radius in base caustic-map texels, layer (of the multi-resolution
/// map), power R, G, B (W), photons (1, or a cluster's count), splatted (1 when drawn), 3 unused
/// (see `wyman2008/splat_footprints.comp` for what an entry that is not drawn holds).
pub type Footprint = [f32; 12];

/// Channels of a `splats` dump layer: the first nine of a [`Footprint`].
pub use super::settings::SPLAT_CHANNELS as CHANNELS;

pub struct SplatFootprints {
    pipeline: Pipeline,
}

impl SplatFootprints {
    pub fn new(ctx: &Context, sh: &ShaderCompiler) -> Result<SplatFootprints> {
        let shader = sh.compile("wyman2008/splat_footprints.comp", &[])?;
        Ok(SplatFootprints { pipeline: Pipeline::compute(ctx, "splat_footprints", &shader)? })
    }

    /// The splats of light `l`'s final list, as the hierarchy and photon buffer hold it now
    /// (in the list's order); records, submits and waits for its own frame.
    pub fn read(
        &self,
        ctx: &Context,
        h: &Hierarchy,
        inp: &FrameInputs,
        pt: &PhotonTargets,
        l: u32,
    ) -> Result<Vec<Footprint>> {
        let Photons::List { power, position, list } = h.final_list() else {
            anyhow::bail!("the hierarchy has no final list")
        };
        let count = list.count(ctx)?;
        let bytes = count.max(1) as u64 * std::mem::size_of::<Footprint>() as u64;
        let limit = ctx.info().max_storage_buffer_range as u64;
        if bytes > limit {
            return Err(crate::input_error!(
                "--dump splats: {count} splats of light {l} need {bytes} bytes of storage buffer, more than this \
                 device's maxStorageBufferRange ({limit}); dump fewer photons"
            )
            .into());
        }
        let out = Buffer::new(ctx, "splat footprints", bytes, Memory::Gpu)?;
        let binds = [
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
            ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
            ("hierarchy_power", Bind::Sampled(power, inp.nearest)),
            ("hierarchy_position", Bind::Sampled(position, inp.nearest)),
            ("Entries", Bind::BufferRead(list.data())),
            ("Footprints", Bind::Buffer(&out)),
        ];
        let mut f = ctx.frame(FrameOptions::default())?;
        f.pass(&Stage::SplatFootprints.light(l)).bind(&self.pipeline, binds).record(|cmd| {
            cmd.push(&FootprintConstants { entries: count, light: l })?;
            let (x, y) = groups(count);
            cmd.dispatch(x, y, 1);
            Ok(())
        })?;
        f.submit()?;
        let mut all: Vec<Footprint> = ctx.read_buffer_as(&out)?;
        all.truncate(count as usize);
        Ok(all)
    }
}

/// One light's part of `splats.exr` (layer `light<l>`): a footprint per pixel in row-major
/// order (the order of `light<l>.list0` in `hierarchy_lists.exr`), channels [`CHANNELS`].
pub fn splat_records(splats: &[Footprint]) -> Vec<Vec<f32>> {
    splats.iter().map(|s| s[..CHANNELS.len()].to_vec()).collect()
}
