//! The passes of one mesh-renderer frame after its uniforms: the eye-space background where
//! caustics are deposited in the eye's view, the technique's caustic stages, then the eye render
//! (`super::eye`).

use super::eye;
use super::renderer::MeshRenderer;
use crate::gpu::FrameStep;
use crate::techniques::{self, EyeView};
use anyhow::Result;
use vkcore::Frame;

impl MeshRenderer<'_> {
    /// Every pass of one frame after its uniforms: eye-space backgrounds, caustics, the eye.
    pub(super) fn record_frame(&self, f: &mut Frame, step: FrameStep) -> Result<()> {
        let eye_inputs = eye::EyeInputs {
            uniforms: self.slots.frame_uniforms(),
            caustic_uniforms: self.slots.caustic_uniforms(),
            caustics: &self.caustic_targets,
            meshes: &self.meshes,
            nearest: &self.nearest,
            linear: &self.linear,
            receiver_view_caustic: self.caustic.as_ref().and_then(|c| c.receiver_caustic()),
            refraction: &self.refraction,
        };
        // Caustics deposited in the eye's view are drawn into it: the background and its
        // geometry buffer first.
        let eye_space = self.caustic.as_ref().is_some_and(|c| c.eye_space());
        if eye_space {
            eye::record_shadows_and_background(f, &self.pipelines, &self.targets, &eye_inputs)?;
        }
        match &self.caustic {
            Some(c) => {
                // One photon buffer serves every light: only one light's can be kept.
                // Progressive accumulation traces new photons every frame.
                let reuse =
                    step.reuse_photons && self.photons_ready && self.targets.shadow.lights == 1 && !c.progressive();
                let inputs = self.caustic_inputs();
                let lights = self.targets.shadow.lights;
                c.record(f, &inputs, &self.caustic_targets, lights, Some(self.eye_view()), reuse)?;
            }
            None => techniques::record_cleared(f, &self.caustic_targets)?,
        }
        if eye_space {
            eye::record_after_background(f, &self.pipelines, &self.targets, &eye_inputs)?;
        } else {
            eye::record(f, &self.pipelines, &self.targets, &eye_inputs)?;
        }
        Ok(())
    }

    /// The eye's view as this frame renders it (for caustics deposited in it).
    fn eye_view(&self) -> EyeView<'_> {
        EyeView {
            view_proj: glam::Mat4::from_cols_array(&self.slots.current().0.view_proj),
            eye: self.scene.camera.eye,
            position: &self.targets.position.view,
            normal: &self.targets.normal.view,
            albedo: &self.targets.albedo.view,
            background: &self.targets.background.view,
        }
    }

    /// What the caustic stages read of the frame: the uniforms of the slot in use, the meshes,
    /// samplers, spot textures and receiver positions.
    pub(super) fn caustic_inputs(&self) -> techniques::FrameInputs<'_> {
        techniques::FrameInputs {
            frame_uniforms: self.slots.frame_uniforms(),
            caustic_uniforms: self.slots.caustic_uniforms(),
            meshes: &self.meshes,
            nearest: &self.nearest,
            spot_textures: &self.targets.spot_textures.view,
            linear: &self.linear,
            receiver_positions: &self.caustic_targets.receiver_positions.view,
        }
    }
}
