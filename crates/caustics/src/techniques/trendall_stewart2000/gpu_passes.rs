//! Records the pool's GPU passes of Sec. 4.2: the height field (Sec. 4.3, timed on its own as
//! the paper times it), then passes 1-6, each a fragment pass over the n x n grid that reads
//! the previous passes' targets and writes its own.

use super::pipelines::PassPipelines;
use super::targets::PoolTargets;
use crate::gpu::Stage;
use crate::gpu::Target;
use anyhow::Result;
use vkcore::{Access, Bind, Buffer, Frame, Named, Pipeline, Sampler, Targets, Use};

/// What the passes read besides their targets.
pub struct PassInputs<'a> {
    pub uniforms: &'a Buffer,
    pub nearest: &'a Sampler,
}

/// One fragment pass: a triangle over `target`, every texel written.
fn fragment_pass<'a>(
    f: &mut Frame,
    stage: Stage,
    p: &'a Pipeline,
    binds: Vec<Named<'a>>,
    target: &'a Target,
) -> Result<()> {
    f.pass(&stage.pass()).bind(p, binds).uses([Use::view(&target.view, Access::COLOR_ATTACHMENT)]).record(|cmd| {
        cmd.begin_rendering(&Targets::color(&target.view, Some([0.0; 4])))?;
        cmd.draw(3, 1, 0, 0);
        cmd.end_rendering();
        Ok(())
    })?;
    Ok(())
}

/// The height field and passes 1-6; Pass 6 writes `output` (the convolutions, or E_flat).
pub fn record_passes<'a>(
    f: &mut Frame,
    p: &'a PassPipelines,
    t: &'a PoolTargets,
    inp: &PassInputs<'a>,
    output: &'a Target,
) -> Result<()> {
    let u = ("u", Bind::Uniform(inp.uniforms));
    let nearest = inp.nearest;
    let s = |name: &'static str, target: &'a Target| (name, Bind::Sampled(&target.view, nearest));
    // The faithful path's lookup tables, appended to the passes that read them.
    let pixel_texture: Vec<Named> = t.tables.iter().map(|l| s("pixel_texture", &l.pixel_texture)).collect();
    let colour_tables: Vec<Named> = t.tables.iter().map(|l| s("colour_tables", &l.colour_tables)).collect();
    fragment_pass(f, Stage::PoolHeightField, &p.height_field, vec![u], &t.height)?;
    fragment_pass(
        f,
        Stage::PoolPass1Normals,
        &p.pass1_normals,
        [vec![u, s("height_field", &t.height)], pixel_texture].concat(),
        &t.normals,
    )?;
    let pass2 = [vec![u, s("normals", &t.normals)], colour_tables.clone()].concat();
    fragment_pass(f, Stage::PoolPass2GammaN, &p.pass2_gamma_n, pass2, &t.gamma_n)?;
    let pass3 =
        [vec![u, s("normals", &t.normals), s("light_radiance", &t.light_radiance)], colour_tables.clone()].concat();
    fragment_pass(f, Stage::PoolPass3Transmitted, &p.pass3_transmitted, pass3, &t.transmitted)?;
    let pass4 = [vec![u, s("gamma_n", &t.gamma_n)], colour_tables].concat();
    fragment_pass(f, Stage::PoolPass4Direction, &p.pass4_direction, pass4, &t.direction)?;
    let pass5 = vec![u, s("transmitted", &t.transmitted), s("direction", &t.direction)];
    fragment_pass(f, Stage::PoolPass5Integrand, &p.pass5_integrand, pass5, &t.integrand)?;
    let pass6 = vec![u, s("integrand", &t.integrand), ("k", Bind::BufferRead(&t.kernels))];
    fragment_pass(f, Stage::PoolPass6Convolution, &p.pass6_convolution, pass6, output)
}
