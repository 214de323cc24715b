//! The receiver map (E / E_flat on the pool bottom) and the final render of the pool seen from
//! above through the refracting surface (`shaders_glsl/trendall_stewart2000/view.comp`).

use super::pipelines::PoolPipelines;
use super::targets::PoolTargets;
use crate::gpu::Stage;
use anyhow::Result;
use vkcore::{Bind, Buffer, Frame, Sampler};

/// Records `pool.receiver` then `pool.view`.
pub fn record_view(
    f: &mut Frame,
    p: &PoolPipelines,
    t: &PoolTargets,
    uniforms: &Buffer,
    nearest: &Sampler,
    linear: &Sampler,
) -> Result<()> {
    let n = t.receiver.view.extent.0;
    let receiver = [
        ("u", Bind::Uniform(uniforms)),
        ("convolutions", Bind::Sampled(&t.convolutions.view, nearest)),
        ("flat_convolutions", Bind::Sampled(&t.flat.view, nearest)),
        ("receiver", Bind::Storage(&t.receiver.view)),
    ];
    f.pass(&Stage::PoolReceiver.pass()).bind(&p.receiver, receiver).record(|cmd| {
        cmd.dispatch(n.div_ceil(8), n.div_ceil(8), 1);
        Ok(())
    })?;
    let view = [
        ("u", Bind::Uniform(uniforms)),
        ("height_field", Bind::Sampled(&t.height.view, linear)),
        ("normals", Bind::Sampled(&t.normals.view, linear)),
        ("receiver", Bind::Sampled(&t.receiver.view, linear)),
        ("final_image", Bind::Storage(&t.final_image.view)),
    ];
    let (w, h) = t.final_image.view.extent;
    f.pass(&Stage::PoolView.pass()).bind(&p.view, view).record(|cmd| {
        cmd.dispatch(w.div_ceil(8), h.div_ceil(8), 1);
        Ok(())
    })?;
    Ok(())
}
