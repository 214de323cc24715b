//! Which part of the mesh renderer reads each dump: every dump is read by the owner of its
//! declaration (`crate::dump::Dump::owner`), found by the declaration itself, never its name.

use super::dumps;
use super::renderer::MeshRenderer;
use crate::dump::{Dump, Space};
use crate::image_io::ImageF32;
use anyhow::Result;

impl MeshRenderer<'_> {
    /// The buffers `wanted` of the last frame that this render has, each with its image. The
    /// light-space buffers that serve every light in turn (`dump::Space::LightInTurn`) are read
    /// light by light by the caustic stages (`CausticPipeline::light_space_dumps`): layers
    /// `light<l>.<layer>`; the eye-space ones the eye render does not own by the caustic
    /// deposit; the eye's refraction's by its stage; the rest from the eye render's targets.
    pub(super) fn read_dumps(&mut self, wanted: &[&'static Dump]) -> Result<Vec<(&'static Dump, ImageF32)>> {
        let declared = super::dumps_for(&self.scene.caustics);
        let mut unique: Vec<&'static Dump> = vec![];
        for &d in wanted {
            if declared.contains(&d) && !unique.contains(&d) {
                unique.push(d);
            }
        }
        let in_turn: Vec<&'static Dump> = unique
            .iter()
            .copied()
            .filter(|&d| self.caustic.as_ref().is_some_and(|c| c.has_light_space_dump(d)))
            .collect();
        anyhow::ensure!(
            in_turn.is_empty() || !self.slots.pending(),
            "dumps: the renderer moved to a new pose after its last frame; render a frame first"
        );
        if let Some(c) = self.caustic.as_mut() {
            c.prepare_dumps(self.ctx, self.shaders, &in_turn)?;
        }
        let mut read = match &self.caustic {
            Some(c) => {
                let lights = self.targets.shadow.lights;
                c.light_space_dumps(self.ctx, &self.caustic_inputs(), &self.caustic_targets, lights, &in_turn)?
            }
            None => vec![],
        };
        let mut out = vec![];
        for d in unique {
            let img = match read.iter().position(|(r, _)| *r == d) {
                Some(i) => Some(read.swap_remove(i).1),
                None if d.space == Space::LightInTurn => None,
                // An eye-space buffer the eye render does not own is its caustic deposit's.
                None if d.space == Space::Eye && !dumps::EYE_DUMPS.contains(&d) => match &self.caustic {
                    Some(c) => c.dump(self.ctx, d)?,
                    None => None,
                },
                None => match self.refraction.dump(self.ctx, &self.targets.final_image, d)? {
                    Some(img) => Some(img),
                    None => {
                        let photons = self.caustic.as_ref().map(|c| c.photon_targets());
                        dumps::dump(self.ctx, &self.targets, &self.caustic_targets, photons, d)?
                    }
                },
            };
            if let Some(img) = img {
                out.push((d, img));
            }
        }
        Ok(out)
    }
}
