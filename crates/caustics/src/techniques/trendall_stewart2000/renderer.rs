//! `PoolRenderer`: one frame of Sec. 4.2's loop, "for each height field in the sequence": the
//! height field at the pool's time, passes 1-6, the receiver map and the final render. Init
//! computes the kernels, the lookup tables and E_flat (the same passes on a flat surface) once.
//! `--precision f64` runs the height field and passes 1-6 on the CPU (timed on the host) and
//! uploads what the receiver map and the final render read.

use super::cpu::{self, CpuPasses};
use super::gpu_passes::{record_passes, PassInputs};
use super::pipelines::PoolPipelines;
use super::settings::RECEIVER;
use super::targets::PoolTargets;
use super::uniforms::{pool_uniforms, PoolUniforms};
use super::{dumps, pool_of, water_surface, Init, Precision};
use crate::dump::Dump;
use crate::gpu::frames::{FrameRenderer, Frames, RecordFrame, Slot};
use crate::gpu::{FrameMode, FrameStep, Stage};
use crate::image_io::ImageF32;
use crate::scene::Scene;
use anyhow::{Context as _, Result};
use std::time::Instant;
use vkcore::{Access, Buffer, Context, Filter, Frame, FrameOptions, Memory, PassTiming, Sampler, ShaderCompiler, Use};

pub struct PoolRenderer<'c> {
    ctx: &'c Context,
    scene: Scene,
    init: Init,
    pipelines: PoolPipelines,
    targets: PoolTargets,
    uniforms: Buffer,
    /// Uniforms to write at the start of the next frame (a new time).
    pending: Option<PoolUniforms>,
    nearest: Sampler,
    linear: Sampler,
    /// `f64`: the last frame's passes and the flat surface's.
    cpu: Option<(CpuPasses, CpuPasses)>,
    /// One-shot frames or a ring (`crate::gpu::frames`).
    frames: Frames,
    /// Throughput frames: per slot the staging buffers of the CPU path's height field, normals
    /// and convolutions (copied inside the frame).
    cpu_staging: Vec<Vec<Buffer>>,
}

/// RGBA32F texels of a CPU grid, for upload.
fn texels(values: impl Iterator<Item = [f64; 4]>) -> Vec<f32> {
    values.flat_map(|v| v.map(|x| x as f32)).collect()
}

impl<'c> PoolRenderer<'c> {
    pub fn new(
        ctx: &'c Context,
        shaders: &ShaderCompiler,
        scene: &Scene,
        mode: FrameMode,
        pass_timestamps: bool,
    ) -> Result<Self> {
        let pool = pool_of(scene)?;
        let init = Init::new(pool, &scene.caustics)?;
        let pipelines = PoolPipelines::new(ctx, shaders, init.precision)?;
        let targets = PoolTargets::new(ctx, &init, scene.camera.width, scene.camera.height)?;
        let faithful = init.precision == Precision::Unorm8;
        // E_flat: the same passes for a flat surface (no wave has started).
        let flat_pool = crate::scene::PoolSpec { impulses: vec![], ..pool.clone() };
        let flat_uniforms = pool_uniforms(scene, &flat_pool, init.n as u32, &init.kernels, &init.adjustments, faithful);
        let uniforms = ctx.buffer_with_data("pool uniforms", bytemuck::bytes_of(&flat_uniforms))?;
        let nearest = Sampler::new(ctx, Filter::Nearest)?;
        let cpu = match &pipelines.passes {
            Some(p) => {
                let mut f = ctx.frame(FrameOptions::default())?;
                record_passes(
                    &mut f,
                    p,
                    &targets,
                    &PassInputs { uniforms: &uniforms, nearest: &nearest },
                    &targets.flat,
                )?;
                f.submit().context("computing E_flat")?;
                None
            }
            None => {
                let n = init.n;
                let flat = cpu::run(pool, n, &init.kernels, vec![0.0; n * n], &init.light_radiance);
                ctx.upload_image(
                    &targets.flat.image,
                    0,
                    0,
                    bytemuck::cast_slice(&texels(flat.convolutions.iter().copied())),
                )?;
                Some((flat.clone(), flat))
            }
        };
        let pending = Some(pool_uniforms(scene, pool, init.n as u32, &init.kernels, &init.adjustments, faithful));
        Ok(PoolRenderer {
            ctx,
            scene: scene.clone(),
            init,
            pipelines,
            targets,
            uniforms,
            pending,
            nearest,
            linear: Sampler::new(ctx, Filter::Linear)?,
            cpu,
            frames: Frames::new(ctx, mode, pass_timestamps)?,
            cpu_staging: vec![],
        })
    }

    /// Moves to `scene`, the same pool at another time (`crate::animation`).
    pub fn set_pose(&mut self, scene: &Scene) -> Result<()> {
        let pool = pool_of(scene)?;
        if pool.at_time(self.init.pool.time) != self.init.pool {
            return Err(crate::input_error!(
                "{}: pool-convolution renders the same pool at other times only: the light, and with it the \
                 kernels, lookup tables and E_flat of Init, cannot move between frames (light_path = \"static\")",
                scene.path.display()
            )
            .into());
        }
        self.init.pool = pool.clone();
        let faithful = self.init.precision == Precision::Unorm8;
        let i = &self.init;
        self.pending = Some(pool_uniforms(scene, pool, i.n as u32, &i.kernels, &i.adjustments, faithful));
        self.scene = scene.clone();
        Ok(())
    }

    /// The CPU path's height field and passes 1-6 (host times), uploaded now (per-pass frames)
    /// or into slot `slot`'s staging buffers for the frame to copy (throughput frames).
    fn cpu_passes(&mut self, slot: Option<Slot>) -> Result<Vec<PassTiming>> {
        let n = self.init.n;
        let start = Instant::now();
        let height = water_surface::height_field(&self.init.pool, n);
        let mut timings = vec![("pool.height_field", start.elapsed().as_secs_f64() * 1e3)];
        let c = cpu::run(&self.init.pool, n, &self.init.kernels, height, &self.init.light_radiance);
        timings.extend(c.timings.iter().copied());
        let start = Instant::now();
        let fields = [
            texels(c.height.iter().map(|&h| [h, 0.0, 0.0, 1.0])),
            texels(c.normals.iter().map(|v| [v.x, v.y, v.z, 1.0])),
            texels(c.convolutions.iter().copied()),
        ];
        match slot {
            None => {
                let t = &self.targets;
                for (target, v) in [&t.height, &t.normals, &t.convolutions].into_iter().zip(&fields) {
                    self.ctx.upload_image(&target.image, 0, 0, bytemuck::cast_slice(v))?;
                }
                timings.push(("pool.upload", start.elapsed().as_secs_f64() * 1e3));
            }
            Some(Slot { index: s, count }) => {
                // Every slot's at once, so that only the first frame makes any.
                while self.cpu_staging.len() < count.max(s + 1) {
                    let k = self.cpu_staging.len();
                    let bytes = (fields[0].len() * 4) as u64;
                    let make =
                        |what: &str| Buffer::new(self.ctx, &format!("pool {what}, slot {k}"), bytes, Memory::Upload);
                    self.cpu_staging.push(vec![make("height")?, make("normals")?, make("convolutions")?]);
                }
                for (b, v) in self.cpu_staging[s].iter_mut().zip(&fields) {
                    b.write_mapped(0, bytemuck::cast_slice(v))?;
                }
                timings.push(("pool.staging", start.elapsed().as_secs_f64() * 1e3));
            }
        }
        if let Some((last, _)) = &mut self.cpu {
            *last = c;
        }
        Ok(timings
            .into_iter()
            .map(|(name, ms)| PassTiming { name: name.into(), gpu_ms: Some(ms), host_ms: None, stats: None })
            .collect())
    }

    /// The uniforms if the pool moved, passes 1-6 (GPU paths) and the view.
    fn record_frame(&mut self, f: &mut Frame) -> Result<()> {
        if let Some(u) = self.pending.take() {
            f.pass(&Stage::PoolUniforms.pass()).uses([Use::buffer(&self.uniforms, Access::TRANSFER_WRITE)]).record(
                |cmd| {
                    cmd.update_buffer(&self.uniforms, 0, bytemuck::bytes_of(&u))?;
                    Ok(())
                },
            )?;
        }
        if let Some(p) = &self.pipelines.passes {
            let inputs = PassInputs { uniforms: &self.uniforms, nearest: &self.nearest };
            record_passes(f, p, &self.targets, &inputs, &self.targets.convolutions)?;
        }
        super::view::record_view(f, &self.pipelines, &self.targets, &self.uniforms, &self.nearest, &self.linear)?;
        Ok(())
    }

    /// What Init computed (the pool at its current time, the kernels, the encodings).
    pub fn init(&self) -> &Init {
        &self.init
    }
}

/// One frame of the loop: with the CPU path its passes run on the host first (timed, before a
/// one-shot frame's passes; a throughput frame copies their fields from its slot's staging
/// buffers, and its host times are not in the frame's report).
impl RecordFrame for PoolRenderer<'_> {
    fn ctx(&self) -> &Context {
        self.ctx
    }

    fn frames(&mut self) -> &mut Frames {
        &mut self.frames
    }

    fn host_passes(&mut self) -> Result<Vec<PassTiming>> {
        if self.cpu.is_some() {
            self.cpu_passes(None)
        } else {
            Ok(vec![])
        }
    }

    fn record(&mut self, f: &mut Frame, slot: Option<Slot>, _step: FrameStep) -> Result<()> {
        if let (Some(slot), true) = (slot, self.cpu.is_some()) {
            self.cpu_passes(Some(slot))?;
            let t = &self.targets;
            let staging = &self.cpu_staging[slot.index];
            let targets = [&t.height, &t.normals, &t.convolutions];
            let mut uses: Vec<Use> = staging.iter().map(|b| Use::buffer(b, Access::TRANSFER_READ)).collect();
            uses.extend(targets.iter().map(|t| Use::image(&t.image, 0..1, 0..1, Access::TRANSFER_WRITE)));
            f.pass(&Stage::PoolUpload.pass()).uses(uses).record(|cmd| {
                for (b, t) in staging.iter().zip(targets) {
                    cmd.copy_buffer_to_image(b, &t.image, 0, 0);
                }
                Ok(())
            })?;
        }
        self.record_frame(f)
    }

    fn final_view(&self) -> &vkcore::ImageView {
        &self.targets.final_image.view
    }

    /// The CPU path's passes are timed on the host already (`host_passes`), and no pool bench
    /// config asks for host pass times: its frames stay one submit.
    fn host_pass_times(&self) -> bool {
        false
    }
}

impl FrameRenderer for PoolRenderer<'_> {
    fn set_pose(&mut self, scene: &Scene) -> Result<()> {
        PoolRenderer::set_pose(self, scene)
    }

    /// The last frame's linear radiance, row 0 at the top.
    fn final_image(&self) -> Result<ImageF32> {
        let t = &self.targets.final_image;
        let texels = dumps::read(self.ctx, t)?;
        let data = texels.iter().flat_map(|p| [p[0], p[1], p[2]]).collect();
        let (w, h) = t.view.extent;
        Ok(ImageF32 { width: w, height: h, layers: vec![crate::image_io::Layer::new(None, &["R", "G", "B"], data)] })
    }

    /// The buffers `wanted` of the last frame (from `settings::DUMPS`; others are skipped).
    fn dumps(&mut self, wanted: &[&'static Dump]) -> Result<Vec<(&'static Dump, ImageF32)>> {
        let n = self.init.n;
        let mut out: Vec<(&'static Dump, ImageF32)> = vec![];
        for &d in wanted {
            if out.iter().any(|(m, _)| *m == d) {
                continue;
            }
            let img = match &self.cpu {
                Some((last, flat)) if d == &RECEIVER => {
                    Some(dumps::receiver_image(n, &last.irradiance(), &flat.irradiance()))
                }
                Some((last, flat)) => dumps::cpu_pass(last, flat, d),
                None if d == &RECEIVER => Some(dumps::gpu_receiver(self.ctx, &self.targets, n)?),
                None => dumps::gpu_pass(self.ctx, &self.targets, &self.init.adjustments, d, n)?,
            };
            if let Some(img) = img {
                out.push((d, img));
            }
        }
        Ok(out)
    }

    fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The pool bottom's receiver map.
    fn receiver(&self) -> &'static Dump {
        &RECEIVER
    }
}
