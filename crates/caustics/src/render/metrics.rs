//! What the bench counts of a mesh-renderer frame besides its time: photons emitted and valid
//! (Wyman & Nichols 2009 Table 1), the traversal's list sizes and the points drawn.

use super::renderer::MeshRenderer;
use crate::image_io::ImageF32;
use crate::techniques::shared::settings::PHOTON_BUFFER;
use anyhow::{Context as _, Result};

impl MeshRenderer<'_> {
    /// Photons emitted per frame over all lights (0 without a caustic technique).
    pub fn photons_emitted(&self) -> u64 {
        if !self.active {
            return 0;
        }
        let c = &self.scene.caustics;
        c.technique.photons_per_light(c, self.specular_vertices) * self.targets.shadow.lights as u64
    }

    /// Photons of the last frame that met a specular object and found a receiver (the photon
    /// buffer's texels with `valid` set, over all lights), read back from the GPU; `None` where
    /// the technique has no photon buffer. Against [`Self::photons_emitted`] this is the share
    /// of the light's view that the photon view spends on photons (Wyman & Nichols 2009 Table 1).
    /// `read`: the `photon_buffer` dump where the caller read it already (it is not read again).
    pub fn valid_photons(&mut self, read: Option<&ImageF32>) -> Result<Option<u64>> {
        if !self.active || !self.scene.caustics.technique.writes_photon_buffer() {
            return Ok(None);
        }
        if let Some(img) = read {
            return Ok(Some(valid_photons_in(img)?));
        }
        let Some((_, img)) = self.read_dumps(&[&PHOTON_BUFFER])?.pop() else { return Ok(None) };
        Ok(Some(valid_photons_in(&img)?))
    }

    /// Points drawn (or compute-splat invocations) per frame over all lights
    /// (`CausticPipeline::splats_drawn`).
    pub fn splats_drawn(&self) -> Result<u64> {
        match &self.caustic {
            Some(c) => c.splats_drawn(self.ctx, self.targets.shadow.lights),
            None => Ok(0),
        }
    }
}

/// The texels with `valid` set in a `photon_buffer` dump, over all lights.
fn valid_photons_in(img: &ImageF32) -> Result<u64> {
    let mut valid = 0u64;
    for layer in img.layers.iter().filter(|l| l.name.as_deref().is_some_and(|n| n.ends_with("position"))) {
        let c = layer.channels.iter().position(|c| c == "valid").context("photon buffer without `valid`")?;
        valid += layer.data.chunks_exact(layer.channels.len()).filter(|p| p[c] > 0.5).count() as u64;
    }
    Ok(valid)
}
