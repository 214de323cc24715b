//! The pool's pipelines: a fragment pass per stage of Sec. 4.2 (the height field and passes
//! 1-6, drawn over the n x n grid into the path's targets; `FAITHFUL` selects the 8-bit path's
//! arithmetic), and the compute passes of the receiver map and the final render.

use super::settings::Precision;
use super::targets::pass_format;
use anyhow::Result;
use vkcore::{Context, GraphicsDesc, Pipeline, ShaderCompiler};

/// The GPU passes of Sec. 4.2 (none for the CPU path, which uploads its results).
pub struct PassPipelines {
    pub height_field: Pipeline,
    pub pass1_normals: Pipeline,
    pub pass2_gamma_n: Pipeline,
    pub pass3_transmitted: Pipeline,
    pub pass4_direction: Pipeline,
    pub pass5_integrand: Pipeline,
    pub pass6_convolution: Pipeline,
}

pub struct PoolPipelines {
    pub passes: Option<PassPipelines>,
    pub receiver: Pipeline,
    pub view: Pipeline,
}

fn fragment_pass(ctx: &Context, sh: &ShaderCompiler, precision: Precision, name: &str) -> Result<Pipeline> {
    let faithful = precision == Precision::Unorm8;
    let defines: &[(&str, &str)] = if faithful { &[("FAITHFUL", "1")] } else { &[] };
    let frag = sh.compile(&format!("trendall_stewart2000/{name}.frag"), defines)?;
    let mut d = GraphicsDesc::new(
        &format!("pool.{name}"),
        sh.compile("trendall_stewart2000/fullscreen.vert", &[])?,
        Some(frag),
    );
    d.color_formats = vec![pass_format(precision)];
    Ok(Pipeline::graphics(ctx, &d)?)
}

impl PoolPipelines {
    pub fn new(ctx: &Context, sh: &ShaderCompiler, precision: Precision) -> Result<PoolPipelines> {
        let passes = if precision == Precision::F64 {
            None
        } else {
            let p = |name: &str| fragment_pass(ctx, sh, precision, name);
            Some(PassPipelines {
                height_field: p("height_field")?,
                pass1_normals: p("pass1_normals")?,
                pass2_gamma_n: p("pass2_gamma_n")?,
                pass3_transmitted: p("pass3_transmitted")?,
                pass4_direction: p("pass4_direction")?,
                pass5_integrand: p("pass5_integrand")?,
                pass6_convolution: p("pass6_convolution")?,
            })
        };
        let compute = |name: &str| -> Result<Pipeline> {
            let spirv = sh.compile(&format!("trendall_stewart2000/{name}.comp"), &[])?;
            Ok(Pipeline::compute(ctx, &format!("pool.{name}"), &spirv)?)
        };
        Ok(PoolPipelines { passes, receiver: compute("receiver")?, view: compute("view")? })
    }
}
