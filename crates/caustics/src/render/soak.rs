//! A soak run: many animated throughput frames of one scene, with the process's resident memory,
//! the device memory held through the allocator and the Vulkan objects made so far sampled every
//! so many frames. A real-time loop must hold all three flat once warm (`causticlab soak`,
//! `scripts/soak.sh`, and a short run in the tests).

use super::{FrameMode, FrameStep, Renderer, RendererOptions};
use crate::animation::{scene_at, Animation};
use crate::scene::Scene;
use anyhow::{Context as _, Result};
use std::time::Instant;
use vkcore::{Context, ShaderCompiler};

/// One sample, taken after `frame` frames were submitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoakSample {
    pub frame: u32,
    pub seconds: f64,
    /// The process's resident set (VmRSS), bytes.
    pub resident_bytes: u64,
    /// Device memory in live allocations and in the allocator's blocks, bytes.
    pub device_allocated: u64,
    pub device_reserved: u64,
    /// Vulkan objects created or allocated since the renderer was made.
    pub objects: u64,
}

/// This process's resident set, bytes (Linux `/proc/self/status`); 0 where unknown.
pub fn resident_bytes() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with("VmRSS:"))?;
            line.split_whitespace().nth(1)?.parse::<u64>().ok()
        })
        .map(|kb| kb * 1024)
        .unwrap_or(0)
}

/// Renders `frames` throughput frames of `scene` with the light, the camera and the specular
/// objects orbiting (`period` frames a loop), sampling every `every` frames (and at the end).
pub fn soak(
    ctx: &Context,
    shaders: &ShaderCompiler,
    scene: &Scene,
    frames: u32,
    every: u32,
    period: u32,
) -> Result<Vec<SoakSample>> {
    let opts = RendererOptions { frame_mode: FrameMode::throughput(), ..Default::default() };
    let mut r = Renderer::new(ctx, shaders, scene, &opts)?;
    let anim = Animation { light: true, camera: true, object: true, period_frames: period.max(1) };
    let start = Instant::now();
    let objects_at_start = ctx.counters().objects;
    let sample = |f: u32| {
        let (device_allocated, device_reserved) = ctx.device_memory();
        SoakSample {
            frame: f,
            seconds: start.elapsed().as_secs_f64(),
            resident_bytes: resident_bytes(),
            device_allocated,
            device_reserved,
            objects: ctx.counters().objects - objects_at_start,
        }
    };
    let mut out = vec![];
    for f in 0..frames {
        if f > 0 {
            r.set_pose(&scene_at(scene, &anim, f)).with_context(|| format!("soak frame {f}: pose"))?;
        }
        r.submit(FrameStep::default()).with_context(|| format!("soak frame {f}"))?;
        let done = f + 1;
        if done % every.max(1) == 0 || done == frames {
            out.push(sample(done));
        }
    }
    r.finish()?;
    Ok(out)
}

/// The largest relative spread (max / min - 1) of resident memory, device memory and objects over
/// the samples from frame `after` on: a flat loop keeps each under a percent.
pub fn drift(samples: &[SoakSample], after: u32) -> (f64, f64, u64) {
    let late: Vec<&SoakSample> = samples.iter().filter(|s| s.frame > after).collect();
    let spread = |f: &dyn Fn(&SoakSample) -> u64| {
        let v: Vec<u64> = late.iter().map(|s| f(s)).collect();
        match (v.iter().min(), v.iter().max()) {
            (Some(&lo), Some(&hi)) if lo > 0 => hi as f64 / lo as f64 - 1.0,
            _ => 0.0,
        }
    };
    let objects = match (late.first(), late.last()) {
        (Some(a), Some(b)) => b.objects - a.objects,
        _ => 0,
    };
    (spread(&|s| s.resident_bytes), spread(&|s| s.device_reserved.max(s.device_allocated)), objects)
}
