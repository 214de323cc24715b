//! Host time per frame of the frame loop in both frame modes (`caustics::gpu::frame_mode`):
//! `sphere_on_plane` with `wd-points` at 256² photons, its own camera, no validation. A
//! per-pass frame is recorded, submitted and waited for; a throughput frame is recorded and
//! submitted, the ring waiting for the frame two before it (so in steady state the time per
//! iteration is the time per frame). It then times 20 more frames on the host and reads the GPU
//! time the timestamps saw for them: the sum of every pass (per-pass), the frame's pair
//! (throughput).
//! Run with `bash scripts/criterion.sh` on an otherwise idle machine.

use caustics::render::{FrameMode, FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::path::PathBuf;
use std::time::Duration;
use vkcore::{Context, ContextOptions, ShaderCompiler};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        return f64::NAN;
    }
    v[v.len() / 2]
}

fn frame_loop(c: &mut Criterion) {
    let ctx =
        Context::new(&ContextOptions { device: std::env::var("CAUSTICLAB_TEST_DEVICE").ok(), ..Default::default() })
            .expect("a Vulkan device");
    let shaders = ShaderCompiler::new(&caustics::render::shader_root()).expect("shaderc");
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    let mut scene = Scene::load(&p).expect("shipped scene");
    scene.caustics.technique = "wd-points".parse().expect("technique");
    scene.caustics.photons = 256;
    scene.receiver_map = None;
    let mut g = c.benchmark_group("frame_loop");
    g.sample_size(10).warm_up_time(Duration::from_secs(2)).measurement_time(Duration::from_secs(8));
    g.throughput(Throughput::Elements(1));
    for mode in [FrameMode::PerPass, FrameMode::throughput()] {
        let opts = RendererOptions { frame_mode: mode, ..Default::default() };
        let mut r = Renderer::new(&ctx, &shaders, &scene, &opts).expect("renderer");
        let step = FrameStep::default();
        let frame = |r: &mut Renderer| match mode {
            FrameMode::PerPass => vec![r.frame(step).expect("frame")],
            FrameMode::Throughput { .. } => r.submit(step).expect("submit"),
        };
        for _ in 0..3 {
            frame(&mut r);
        }
        g.bench_function(format!("{}/sphere_on_plane/wd-points/256", mode.name()), |b| {
            b.iter(|| frame(&mut r));
        });
        // Twenty more frames, timed on the host and by the GPU, to read the two against each
        // other (the same frames, unlike criterion's samples above).
        let mut reports = vec![];
        let mut host = vec![];
        for _ in 0..20 {
            let t = std::time::Instant::now();
            reports.extend(frame(&mut r));
            host.push(t.elapsed().as_secs_f64() * 1e3);
        }
        reports.extend(r.finish().expect("finish"));
        let gpu: Vec<f64> = reports
            .iter()
            .filter_map(|f| match mode {
                FrameMode::PerPass => f.total_ms(),
                FrameMode::Throughput { .. } => f.frame_gpu_ms,
            })
            .collect();
        let what = match mode {
            FrameMode::PerPass => "sum of the passes' timestamps",
            FrameMode::Throughput { .. } => "the frame's timestamp pair",
        };
        eprintln!(
            "frame_loop: {} mode, 20 frames: host ms per frame median {:.1}; GPU ms per frame ({what}) median {:.1}",
            mode.name(),
            median(host),
            median(gpu)
        );
    }
    g.finish();
}

criterion_group!(benches, frame_loop);
criterion_main!(benches);
