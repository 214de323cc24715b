//! Records one frame of the eye render: shadow maps, diffuse background with its geometry
//! buffer, then the refractors and reflectors: forward (Wyman 2005: back faces, front faces,
//! composite) or deferred (Wyman & Nichols 2009 Sec. 3.1, `techniques::stages::EyeRefraction`),
//! then the receiver map.

use super::pipelines::EyePipelines;
use super::targets::EyeTargets;
use crate::gpu::*;
use crate::gpu::{mesh_uses, GpuMesh, Stage};
use crate::techniques::stages::refraction::{EyeRefraction, RefractionInputs};
use anyhow::Result;
use vkcore::{Access, Bind, Buffer, Cmd, Frame, Sampler, Targets, Use};

/// What every pass reads.
pub struct EyeInputs<'a> {
    pub uniforms: &'a Buffer,
    pub caustic_uniforms: &'a Buffer,
    pub caustics: &'a crate::techniques::CausticTargets,
    pub meshes: &'a [GpuMesh],
    pub nearest: &'a Sampler,
    pub linear: &'a Sampler,
    /// Eye-space caustics: the receiver view's caustic irradiance, which the receiver map reads.
    pub receiver_view_caustic: Option<&'a vkcore::ImageView>,
    /// The eye's refraction: deferred refraction's passes, or forward (recorded here).
    pub refraction: &'a EyeRefraction,
}

fn draw_meshes<'m>(
    cmd: &mut Cmd,
    meshes: impl Iterator<Item = &'m GpuMesh>,
    instances: u32,
    light: u32,
) -> vkcore::Result<()> {
    meshes.into_iter().try_for_each(|m| m.draw(cmd, instances, light))
}

pub fn record(f: &mut Frame, p: &EyePipelines, t: &EyeTargets, inp: &EyeInputs) -> Result<()> {
    record_shadows_and_background(f, p, t, inp)?;
    record_after_background(f, p, t, inp)
}

/// The shadow maps and the diffuse background with its geometry buffer (what eye-space caustics
/// are rendered into).
pub fn record_shadows_and_background(f: &mut Frame, p: &EyePipelines, t: &EyeTargets, inp: &EyeInputs) -> Result<()> {
    let meshes = inp.meshes;

    // Shadow map per light: all six cube faces in one instanced draw (gl_Layer per instance).
    for (l, (dist, depth)) in t.shadow.per_light.iter().enumerate() {
        f.pass(&Stage::ShadowMap.light(l as u32))
            .bind(&p.shadow_map, [("frame", Bind::Uniform(inp.uniforms))])
            .uses([Use::view(dist, Access::COLOR_ATTACHMENT), Use::view(depth, Access::DEPTH_ATTACHMENT)])
            .uses(mesh_uses(meshes))
            .record(|cmd| {
                cmd.begin_rendering(
                    &Targets::color(dist, Some([f32::MAX; 4])).with_depth(depth, Some(1.0)).layered(6),
                )?;
                draw_meshes(cmd, meshes.iter(), 6, l as u32)?;
                cmd.end_rendering();
                Ok(())
            })?;
    }

    let background = [&t.background, &t.position, &t.normal, &t.albedo];
    f.pass(&Stage::Background.pass())
        .bind(
            &p.background,
            [
                ("frame", Bind::Uniform(inp.uniforms)),
                ("shadow_map", Bind::Sampled(&t.shadow.distance.view, inp.nearest)),
                ("spot_textures", Bind::Sampled(&t.spot_textures.view, inp.linear)),
                ("caustics", Bind::Uniform(inp.caustic_uniforms)),
                ("caustic_map", Bind::Sampled(&inp.caustics.caustic_map.view, inp.nearest)),
                ("receiver_positions", Bind::Sampled(&inp.caustics.receiver_positions.view, inp.nearest)),
            ],
        )
        .uses(background.map(|x| Use::view(&x.view, Access::COLOR_ATTACHMENT)))
        .uses([Use::view(&t.depth.view, Access::DEPTH_ATTACHMENT)])
        .uses(mesh_uses(meshes))
        .record(|cmd| {
            let targets = Targets::colors(background.iter().map(|x| (&x.view, Some([0.0; 4]))).collect());
            cmd.begin_rendering(&targets.with_depth(&t.depth.view, Some(1.0)))?;
            draw_meshes(cmd, meshes.iter().filter(|m| m.kind() == MATERIAL_DIFFUSE), 1, 0)?;
            cmd.end_rendering();
            Ok(())
        })?;
    Ok(())
}

/// The refractors and reflectors over the background (Wyman 2005 forward, or Wyman & Nichols
/// 2009 deferred refraction), then the receiver map.
pub fn record_after_background(f: &mut Frame, p: &EyePipelines, t: &EyeTargets, inp: &EyeInputs) -> Result<()> {
    let meshes = inp.meshes;
    let deferred = RefractionInputs {
        uniforms: inp.uniforms,
        meshes,
        background: &t.background.view,
        position: &t.position.view,
        normal: &t.normal.view,
        final_image: &t.final_image.view,
        nearest: inp.nearest,
    };
    if !inp.refraction.record_deferred(f, &deferred)? {
        record_forward(f, p, t, inp)?;
    }

    if let Some((ratio, irradiance, caustic)) = &t.receiver {
        let binds = [
            ("frame", Bind::Uniform(inp.uniforms)),
            ("shadow_map", Bind::Sampled(&t.shadow.distance.view, inp.nearest)),
            ("spot_textures", Bind::Sampled(&t.spot_textures.view, inp.linear)),
            ("ratio_map", Bind::Storage(&ratio.view)),
            ("irradiance_map", Bind::Storage(&irradiance.view)),
            ("caustic_only", Bind::Storage(&caustic.view)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("caustic_map", Bind::Sampled(&inp.caustics.caustic_map.view, inp.nearest)),
            ("receiver_positions", Bind::Sampled(&inp.caustics.receiver_positions.view, inp.nearest)),
            (
                "receiver_view_caustic",
                Bind::Sampled(inp.receiver_view_caustic.unwrap_or(&t.no_receiver_view.view), inp.nearest),
            ),
            ("ReceiverFlux", Bind::BufferRead(&inp.caustics.receiver_flux)),
        ];
        f.pass(&Stage::ReceiverMap.pass()).bind(&p.receiver_map, binds).record(|cmd| {
            let (w, h) = ratio.view.extent;
            cmd.dispatch(w.div_ceil(8), h.div_ceil(8), 1);
            Ok(())
        })?;
    }
    Ok(())
}

/// Wyman 2005's image-space refraction (Wyman & Nichols 2009 Fig. 3, top): the refractors'
/// back faces, their front faces (refracted as they are rasterized, with reflectors), composite.
fn record_forward(f: &mut Frame, p: &EyePipelines, t: &EyeTargets, inp: &EyeInputs) -> Result<()> {
    let meshes = inp.meshes;
    let refractors = || meshes.iter().filter(|m| m.kind() == MATERIAL_REFRACTIVE);
    f.pass(&Stage::RefractorBackFaces.pass())
        .bind(&p.back_faces, [("frame", Bind::Uniform(inp.uniforms))])
        .uses([
            Use::view(&t.back_faces.view, Access::COLOR_ATTACHMENT),
            Use::view(&t.back_depth.view, Access::DEPTH_ATTACHMENT),
        ])
        .uses(mesh_uses(meshes))
        .record(|cmd| {
            cmd.begin_rendering(
                &Targets::color(&t.back_faces.view, Some([0.0; 4])).with_depth(&t.back_depth.view, Some(1.0)),
            )?;
            draw_meshes(cmd, refractors(), 1, 0)?;
            cmd.end_rendering();
            Ok(())
        })?;

    f.pass(&Stage::RefractorFrontFaces.pass())
        .bind(
            &p.front_faces,
            [
                ("frame", Bind::Uniform(inp.uniforms)),
                ("background_radiance", Bind::Sampled(&t.background.view, inp.nearest)),
                ("background_position", Bind::Sampled(&t.position.view, inp.nearest)),
                ("back_faces", Bind::Sampled(&t.back_faces.view, inp.nearest)),
            ],
        )
        .uses([
            Use::view(&t.surface.view, Access::COLOR_ATTACHMENT),
            Use::view(&t.depth.view, Access::DEPTH_ATTACHMENT),
        ])
        .uses(mesh_uses(meshes))
        .record(|cmd| {
            cmd.begin_rendering(&Targets::color(&t.surface.view, Some([0.0; 4])).with_depth(&t.depth.view, None))?;
            draw_meshes(cmd, meshes.iter().filter(|m| m.kind() != MATERIAL_DIFFUSE), 1, 0)?;
            cmd.end_rendering();
            Ok(())
        })?;

    let composite = [
        ("background_radiance", Bind::Sampled(&t.background.view, inp.nearest)),
        ("surface_radiance", Bind::Sampled(&t.surface.view, inp.nearest)),
        ("final_image", Bind::Storage(&t.final_image.view)),
    ];
    f.pass(&Stage::Composite.pass()).bind(&p.composite, composite).record(|cmd| {
        let (w, h) = t.final_image.view.extent;
        cmd.dispatch(w.div_ceil(8), h.div_ceil(8), 1);
        Ok(())
    })?;
    Ok(())
}
