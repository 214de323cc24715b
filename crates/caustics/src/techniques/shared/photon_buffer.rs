//! Photon emission, shared by every photon-buffer technique (Wyman & Davis 2006 Sec. 3.1; Shah
//! et al.'s refractive vertex grid): the light's render of the first diffuse surface (receiver
//! positions, Shah step 1), the refractors' back faces from the light (Wyman 2005's exit
//! estimate), and the photon buffer, one photon per light-space texel of the specular objects,
//! each traced through the refractor (`shaders_glsl/shared/trace.glsl`). Shah's vertex photons
//! replace the last pass (see `shah2007`).

use super::CausticPasses;
use crate::gpu::{mesh_uses, Stage, MATERIAL_DIFFUSE, MATERIAL_REFRACTIVE};
use anyhow::Result;
use vkcore::{Access, Bind, Frame, Named, Targets, Use};

/// The light's views before photons are traced, for light `l`: the receiver positions (its
/// render of the diffuse surfaces) and the refractors' back faces.
pub(crate) fn record_light_views(f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
    record_receiver_positions(f, c, l)?;
    record_back_faces(f, c, l)
}

/// Light `l`'s render of the diffuse surfaces (Shah step 1): where photons land.
pub(crate) fn record_receiver_positions(f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
    let (p, ct, inp) = (c.pipelines, c.targets, c.inputs);
    let ubo_binds =
        || [("frame", Bind::Uniform(inp.frame_uniforms)), ("caustics", Bind::Uniform(inp.caustic_uniforms))];
    let (_, rpos, rdepth) = &ct.per_light[l as usize];
    f.pass(&Stage::ReceiverPositions.light(l))
        .bind(&p.receiver_positions, ubo_binds())
        .uses([Use::view(rpos, Access::COLOR_ATTACHMENT), Use::view(rdepth, Access::DEPTH_ATTACHMENT)])
        .uses(mesh_uses(inp.meshes))
        .record(|cmd| {
            cmd.begin_rendering(&Targets::color(rpos, Some([0.0; 4])).with_depth(rdepth, Some(1.0)))?;
            for m in inp.meshes.iter().filter(|m| m.kind() == MATERIAL_DIFFUSE) {
                m.draw(cmd, 1, l)?;
            }
            cmd.end_rendering();
            Ok(())
        })?;
    Ok(())
}

/// The refractors' back faces from light `l` (Wyman 2005's exit estimate).
fn record_back_faces(f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
    let (p, pt, inp) = (c.pipelines, c.photons, c.inputs);
    let ubo_binds =
        || [("frame", Bind::Uniform(inp.frame_uniforms)), ("caustics", Bind::Uniform(inp.caustic_uniforms))];
    f.pass(&Stage::PhotonBackFaces.light(l))
        .bind(&p.back_faces, ubo_binds())
        .uses([
            Use::view(&pt.back_faces.view, Access::COLOR_ATTACHMENT),
            Use::view(&pt.depth.view, Access::DEPTH_ATTACHMENT),
        ])
        .uses(mesh_uses(inp.meshes))
        .record(|cmd| {
            cmd.begin_rendering(
                &Targets::color(&pt.back_faces.view, Some([0.0; 4])).with_depth(&pt.depth.view, Some(1.0)),
            )?;
            for m in inp.meshes.iter().filter(|m| m.kind() == MATERIAL_REFRACTIVE) {
                m.draw(cmd, 1, l)?;
            }
            cmd.end_rendering();
            Ok(())
        })?;
    Ok(())
}

/// What tracing a photon reads (`shared/trace_surface.glsl`, bindings 0-4): the frame and
/// caustic uniforms, the light-space back faces, the receiver positions and the spot lights'
/// projected textures. Every pipeline that creates photons starts with these.
pub(crate) fn trace_binds<'a>(c: &CausticPasses<'a>) -> Vec<Named<'a>> {
    let (ct, pt, inp) = (c.targets, c.photons, c.inputs);
    vec![
        ("frame", Bind::Uniform(inp.frame_uniforms)),
        ("caustics", Bind::Uniform(inp.caustic_uniforms)),
        ("light_back_faces", Bind::Sampled(&pt.back_faces.view, inp.nearest)),
        ("receiver_positions", Bind::Sampled(&ct.receiver_positions.view, inp.nearest)),
        ("spot_textures", Bind::Sampled(inp.spot_textures, inp.linear)),
    ]
}

/// The photon buffer of light `l` (Wyman & Davis 2006 Sec. 3.1): the specular meshes rendered
/// from the light, each fragment a photon traced through them (position, direction, power).
pub(crate) fn record_photon_buffer(f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
    let (p, pt, inp) = (c.pipelines, c.photons, c.inputs);
    let photons = [&pt.position, &pt.direction, &pt.power];
    f.pass(&Stage::PhotonBuffer.light(l))
        .bind(&p.photon_buffer, trace_binds(c))
        .uses(mesh_uses(inp.meshes))
        .uses(photons.map(|t| Use::view(&t.view, Access::COLOR_ATTACHMENT)))
        .uses([Use::view(&pt.depth.view, Access::DEPTH_ATTACHMENT)])
        .record(|cmd| {
            let targets = Targets::colors(photons.iter().map(|t| (&t.view, Some([0.0; 4]))).collect());
            cmd.begin_rendering(&targets.with_depth(&pt.depth.view, Some(1.0)))?;
            for m in inp.meshes.iter().filter(|m| m.kind() != MATERIAL_DIFFUSE) {
                m.draw(cmd, 1, l)?;
            }
            cmd.end_rendering();
            Ok(())
        })?;
    Ok(())
}
