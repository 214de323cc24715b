//! Records one frame of the eye render: shadow maps, diffuse background with its geometry
//! buffer, refractor back faces, refractor/reflector front faces, composite, receiver map.

use super::pipelines::EyePipelines;
use super::targets::EyeTargets;
use crate::gpu::*;
use crate::gpu::{mesh_uses, GpuMesh};
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
    let meshes = inp.meshes;
    let ubo = Use::buffer(inp.uniforms, Access::UNIFORM_READ);

    // Shadow map per light: all six cube faces in one instanced draw (gl_Layer per instance).
    for (l, (dist, depth)) in t.shadow.per_light.iter().enumerate() {
        let mut uses = vec![
            Use::buffer(inp.uniforms, Access::UNIFORM_READ),
            Use::view(dist, Access::COLOR_ATTACHMENT),
            Use::view(depth, Access::DEPTH_ATTACHMENT),
        ];
        uses.extend(mesh_uses(meshes));
        f.pass(&format!("shadow_map.light{l}"), &uses, |cmd| {
            cmd.begin_rendering(&Targets::color(dist, Some([f32::MAX; 4])).with_depth(depth, Some(1.0)).layered(6))?;
            cmd.bind_pipeline(&p.shadow_map);
            cmd.bind(&[Bind::Uniform(inp.uniforms)])?;
            draw_meshes(cmd, meshes.iter(), 6, l as u32)?;
            cmd.end_rendering();
            Ok(())
        })?;
    }

    let shadow_read = || {
        [
            Use::view(&t.shadow.distance.view, Access::SHADER_READ),
            Use::view(&t.spot_textures.view, Access::SHADER_READ),
            Use::buffer(inp.caustic_uniforms, Access::UNIFORM_READ),
            Use::view(&inp.caustics.caustic_map.view, Access::SHADER_READ),
            Use::view(&inp.caustics.receiver_positions.view, Access::SHADER_READ),
        ]
    };
    let mut uses = vec![Use::buffer(inp.uniforms, Access::UNIFORM_READ)];
    uses.extend(shadow_read());
    uses.extend([&t.background, &t.position, &t.normal].map(|x| Use::view(&x.view, Access::COLOR_ATTACHMENT)));
    uses.push(Use::view(&t.depth.view, Access::DEPTH_ATTACHMENT));
    uses.extend(mesh_uses(meshes));
    f.pass("background", &uses, |cmd| {
        let targets = Targets::colors(vec![
            (&t.background.view, Some([0.0; 4])),
            (&t.position.view, Some([0.0; 4])),
            (&t.normal.view, Some([0.0; 4])),
        ]);
        cmd.begin_rendering(&targets.with_depth(&t.depth.view, Some(1.0)))?;
        cmd.bind_pipeline(&p.background);
        cmd.bind(&[
            Bind::Uniform(inp.uniforms),
            Bind::Sampled(&t.shadow.distance.view, inp.nearest),
            Bind::Sampled(&t.spot_textures.view, inp.linear),
            Bind::Uniform(inp.caustic_uniforms),
            Bind::Sampled(&inp.caustics.caustic_map.view, inp.nearest),
            Bind::Sampled(&inp.caustics.receiver_positions.view, inp.nearest),
        ])?;
        draw_meshes(cmd, meshes.iter().filter(|m| m.kind() == MATERIAL_DIFFUSE), 1, 0)?;
        cmd.end_rendering();
        Ok(())
    })?;

    let refractors = || meshes.iter().filter(|m| m.kind() == MATERIAL_REFRACTIVE);
    let mut uses = vec![
        Use::buffer(inp.uniforms, Access::UNIFORM_READ),
        Use::view(&t.back_faces.view, Access::COLOR_ATTACHMENT),
        Use::view(&t.back_depth.view, Access::DEPTH_ATTACHMENT),
    ];
    uses.extend(mesh_uses(meshes));
    f.pass("refractor_back_faces", &uses, |cmd| {
        cmd.begin_rendering(
            &Targets::color(&t.back_faces.view, Some([0.0; 4])).with_depth(&t.back_depth.view, Some(1.0)),
        )?;
        cmd.bind_pipeline(&p.back_faces);
        cmd.bind(&[Bind::Uniform(inp.uniforms)])?;
        draw_meshes(cmd, refractors(), 1, 0)?;
        cmd.end_rendering();
        Ok(())
    })?;

    let mut uses = vec![Use::buffer(inp.uniforms, Access::UNIFORM_READ)];
    uses.extend([&t.background, &t.position, &t.back_faces].map(|x| Use::view(&x.view, Access::SHADER_READ)));
    uses.push(Use::view(&t.surface.view, Access::COLOR_ATTACHMENT));
    uses.push(Use::view(&t.depth.view, Access::DEPTH_ATTACHMENT));
    uses.extend(mesh_uses(meshes));
    f.pass("refractor_front_faces", &uses, |cmd| {
        cmd.begin_rendering(&Targets::color(&t.surface.view, Some([0.0; 4])).with_depth(&t.depth.view, None))?;
        cmd.bind_pipeline(&p.front_faces);
        cmd.bind(&[
            Bind::Uniform(inp.uniforms),
            Bind::Sampled(&t.background.view, inp.nearest),
            Bind::Sampled(&t.position.view, inp.nearest),
            Bind::Sampled(&t.back_faces.view, inp.nearest),
        ])?;
        draw_meshes(cmd, meshes.iter().filter(|m| m.kind() != MATERIAL_DIFFUSE), 1, 0)?;
        cmd.end_rendering();
        Ok(())
    })?;

    let uses = [
        Use::view(&t.background.view, Access::SHADER_READ),
        Use::view(&t.surface.view, Access::SHADER_READ),
        Use::view(&t.final_image.view, Access::COMPUTE_READ_WRITE),
    ];
    f.pass("composite", &uses, |cmd| {
        cmd.bind_pipeline(&p.composite);
        cmd.bind(&[
            Bind::Sampled(&t.background.view, inp.nearest),
            Bind::Sampled(&t.surface.view, inp.nearest),
            Bind::Storage(&t.final_image.view),
        ])?;
        let (w, h) = t.final_image.view.extent;
        cmd.dispatch(w.div_ceil(8), h.div_ceil(8), 1);
        Ok(())
    })?;

    if let Some((ratio, irradiance, caustic)) = &t.receiver {
        let mut uses = vec![ubo];
        uses.extend(shadow_read());
        uses.push(Use::view(&ratio.view, Access::COMPUTE_READ_WRITE));
        uses.push(Use::view(&irradiance.view, Access::COMPUTE_READ_WRITE));
        uses.push(Use::view(&caustic.view, Access::COMPUTE_READ_WRITE));
        f.pass("receiver_map", &uses, |cmd| {
            cmd.bind_pipeline(&p.receiver_map);
            cmd.bind(&[
                Bind::Uniform(inp.uniforms),
                Bind::Sampled(&t.shadow.distance.view, inp.nearest),
                Bind::Sampled(&t.spot_textures.view, inp.linear),
                Bind::Storage(&ratio.view),
                Bind::Storage(&irradiance.view),
                Bind::Storage(&caustic.view),
                Bind::Uniform(inp.caustic_uniforms),
                Bind::Sampled(&inp.caustics.caustic_map.view, inp.nearest),
                Bind::Sampled(&inp.caustics.receiver_positions.view, inp.nearest),
            ])?;
            let (w, h) = ratio.view.extent;
            cmd.dispatch(w.div_ceil(8), h.div_ceil(8), 1);
            Ok(())
        })?;
    }
    Ok(())
}
