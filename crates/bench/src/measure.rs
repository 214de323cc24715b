//! Runs one cell: the scene set up as the cell says, warm-up frames, measured frames along the
//! config's animation, an untimed frame for pipeline statistics, and (when a quality metric
//! asks for it) a comparison of the receiver map with the exact CPU reference.

use crate::config::{LoadedConfig, QuickSpec};
use crate::plan::Cell;
use anyhow::{Context as _, Result};
use caustics::animation::{scene_at, Animation};
use caustics::compare::{compare, Comparison};
use caustics::image_io::ImageF32;
use caustics::reference::{trace_reference, ReferenceOptions};
use caustics::render::{FrameMode, FrameStep, Renderer, RendererOptions};
use caustics::scene::{CausticSettings, Scene};
use caustics::techniques::CopyType;
use glam::{Mat3, Vec3};
use std::collections::HashMap;
use std::time::Instant;
use vkcore::{Context, Counters, FrameReport, ShaderCompiler};

/// What one cell measured in the throughput frame mode.
#[derive(Debug, Clone, Default)]
pub struct ThroughputRun {
    /// Host milliseconds per frame of each timed block (the block's wall time, from its first
    /// frame's start to the next block's, over its frames).
    pub block_ms: Vec<f64>,
    pub block_frames: u32,
    /// GPU milliseconds of each measured frame (its timestamp pair).
    pub gpu_frame_ms: Vec<f64>,
    /// What each measured frame (its pose update, recording and submit) asked of the driver.
    pub counters: Vec<Counters>,
    /// Passes each measured frame recorded.
    pub passes: Vec<usize>,
}

/// What one cell measured.
#[derive(Default)]
pub struct CellRun {
    /// The per-pass frames (empty when no metric of the config is per-pass).
    pub frames: Vec<FrameReport>,
    /// Host wall time of each measured per-pass frame (record, submit, wait), ms.
    pub wall_ms: Vec<f64>,
    /// Host time of the pose update (`Renderer::set_pose`) before each measured per-pass frame
    /// that had one, ms: outside the frame's time.
    pub pose_ms: Vec<f64>,
    /// What each of those pose updates asked of the driver (its acceleration structures built);
    /// kept where the frames themselves are not timed (a config with only the build counts).
    pub pose_counters: Vec<Counters>,
    /// What each measured per-pass frame (pose update included) asked of the driver.
    pub counters: Vec<Counters>,
    pub throughput: Option<ThroughputRun>,
    /// The untimed statistics frame, where the device has pipeline statistics.
    pub stats_frame: Option<FrameReport>,
    pub photons_emitted: u64,
    pub splats_drawn: u64,
    /// `hcm`: per light, the traversal's list sizes from the 16² level down to the splatted list;
    /// `adaptive`: each level's pending clusters, then the splatted photons.
    pub hierarchy_sizes: Option<Vec<Vec<u64>>>,
    /// `adaptive`: the photon storage it allocated, bytes (Wyman & Nichols 2009 Sec. 4.3).
    pub photon_storage: Option<u64>,
    /// `adaptive`: the batches its traversal is split into per light (Sec. 4.3, Fig. 8).
    pub photon_batches: Option<u32>,
    pub quality: Option<Comparison>,
    /// Photons of the last frame that met a specular object and a receiver (read back from the
    /// photon buffer, untimed); `None` without a photon buffer.
    pub valid_photons: Option<u64>,
    /// Lights with caustics in the cell.
    pub lights: u64,
    /// The caustic settings in effect (after the technique entry and `--quick`).
    pub caustics: CausticSettings,
    pub triangles: usize,
    /// The model files the cell's scene loaded, by checksum (docs/scenes.md).
    pub models: Vec<caustics::scene::models::ModelFile>,
    /// Share of the host's CPU time stolen by the hypervisor over the warm-up and measured
    /// frames (see [`crate::steal`]); `None` where the OS does not say.
    pub cpu_steal: Option<f64>,
    /// Cores' worth of CPU time other processes used while the cell ran (see [`crate::steal`]).
    pub other_cores: Option<f64>,
    /// The host speed probe before the cell's frames, ms (see [`crate::host_speed`]).
    pub host_probe_ms: f64,
    /// `wd-quads`: the last frame's depth complexity of the caustic quads, when a metric asks.
    pub depth_complexity: Option<DepthComplexity>,
    /// `temporal_change`: the relative RMS change of the receiver map from one measured frame to
    /// the next (`compare(frame t, frame t - 1).rel_rmse`), one per pair of measured frames.
    pub temporal_changes: Vec<f64>,
    /// Progressive accumulation's curve (`crate::progressive`): every frame after the means
    /// started again, with its accumulated time and error; empty without a progressive metric.
    pub progressive: Vec<crate::progressive::Point>,
    /// `flip`: HDR-FLIP of the last frame's final image against the reference final image.
    pub final_flip: Option<crate::final_flip::FinalFlip>,
}

impl CellRun {
    /// The mean of [`CellRun::temporal_changes`] (`None` with fewer than two measured frames).
    pub fn temporal_change(&self) -> Option<f64> {
        let n = self.temporal_changes.len();
        (n > 0).then(|| self.temporal_changes.iter().sum::<f64>() / n as f64)
    }
}

/// The caustic quads' depth complexity (Wyman & Davis 2006 Fig. 6): how many of their fragments
/// each pixel of their target received (the alpha of the eye's caustic in eye space, of each
/// light's caustic-map layer in light space: `shaders_glsl/wyman_davis2006/quads.frag`).
#[derive(Debug, Clone, Default)]
pub struct DepthComplexity {
    /// The fragment counts of the pixels that received any, ascending.
    pub covered: Vec<f32>,
    /// The target's pixels (every light's layer).
    pub pixels: usize,
}

impl DepthComplexity {
    /// From a dump whose layers carry the counts in their fourth channel.
    pub fn of(img: &ImageF32) -> Result<DepthComplexity> {
        let mut covered = vec![];
        let mut pixels = 0;
        for layer in &img.layers {
            let n = layer.channels.len();
            anyhow::ensure!(n == 4, "depth complexity: layer {:?} has {n} channels, not 4", layer.name);
            covered.extend(layer.data.chunks_exact(4).map(|p| p[3]).filter(|&c| c > 0.0));
            pixels += layer.data.len() / 4;
        }
        covered.sort_by(f32::total_cmp);
        Ok(DepthComplexity { covered, pixels })
    }

    /// The count below which a share `q` of the covered pixels lie (nearest rank).
    pub fn percentile(&self, q: f64) -> Option<f64> {
        let n = self.covered.len();
        let rank = ((q * n as f64).ceil() as usize).clamp(1, n.max(1));
        self.covered.get(rank - 1).map(|&c| c as f64)
    }

    pub fn mean(&self) -> Option<f64> {
        (!self.covered.is_empty())
            .then(|| self.covered.iter().map(|&c| c as f64).sum::<f64>() / self.covered.len() as f64)
    }

    /// The share of the target's pixels that received any fragment.
    pub fn coverage(&self) -> Option<f64> {
        (self.pixels > 0).then(|| self.covered.len() as f64 / self.pixels as f64)
    }
}

/// Runs cells on one device, keeping CPU references between cells of the same scene.
pub struct Runner<'a> {
    pub ctx: &'a Context,
    pub shaders: &'a ShaderCompiler,
    pub config: &'a LoadedConfig,
    pub quick: Option<&'a QuickSpec>,
    references: HashMap<String, ImageF32>,
    final_references: crate::final_flip::References,
}

impl<'a> Runner<'a> {
    pub fn new(
        ctx: &'a Context,
        shaders: &'a ShaderCompiler,
        config: &'a LoadedConfig,
        quick: Option<&'a QuickSpec>,
    ) -> Self {
        Runner { ctx, shaders, config, quick, references: HashMap::new(), final_references: Default::default() }
    }

    pub fn needs_flip(&self) -> bool {
        self.config.config.metrics.iter().any(|m| crate::config::is_flip_metric(&m.kind))
    }

    /// The reference final image's refinement (`[quality] final_level`; a quick run's small one).
    pub fn final_refinement(&self) -> Result<caustics::final_reference::Refinement> {
        crate::final_flip::refinement(self.config.config.quality.final_level, self.quick.is_some())
    }

    fn needs_quality(&self) -> bool {
        self.config.config.metrics.iter().any(|m| crate::config::is_quality_metric(&m.kind))
    }

    fn needs_progressive(&self) -> bool {
        self.config.config.metrics.iter().any(|m| crate::progressive::is_progressive_metric(&m.kind))
    }

    fn needs_temporal(&self) -> bool {
        self.config.config.metrics.iter().any(|m| crate::config::is_temporal_metric(&m.kind))
    }

    /// Whether a cell reads its receiver map (a validation instrument, not part of any
    /// technique): for the CPU reference or for the frame-to-frame change.
    fn needs_receiver_map(&self) -> bool {
        self.needs_quality() || self.needs_temporal() || self.needs_progressive()
    }

    fn needs_depth_complexity(&self) -> bool {
        self.config.config.metrics.iter().any(|m| crate::config::is_depth_complexity_metric(&m.kind))
    }

    fn needs_valid_photons(&self) -> bool {
        self.config.config.metrics.iter().any(|m| m.kind == "valid_photons" || m.kind == "valid_fraction")
    }

    /// The scene of `cell`: technique settings, photons, lights and output size applied.
    pub fn cell_scene(&self, cell: &Cell) -> Result<Scene> {
        Ok(self.cell_scene_and_shared(cell)?.0)
    }

    /// The scene of `cell`, and the caustic settings every technique of the config shares on it:
    /// the scene file's with the config's `[caustics]` (the reference final image's).
    pub fn cell_scene_and_shared(&self, cell: &Cell) -> Result<(Scene, CausticSettings)> {
        let path = self.config.scene_path(&cell.scene);
        let mut scene = Scene::load(&path)
            .with_context(|| format!("{}: key `matrix.scenes`: loading {}", self.config.path.display(), cell.scene))?;
        let t = &self.config.config.techniques[cell.technique];
        self.config.config.caustics.apply(&mut scene.caustics);
        let shared = scene.caustics.clone();
        t.settings.apply(&mut scene.caustics);
        scene.caustics.photons = cell.photons;
        if let Some(q) = self.quick {
            scene.caustics.caustic_map_resolution = scene.caustics.caustic_map_resolution.min(q.caustic_map_resolution);
            scene.render.shadow_map_resolution = scene.render.shadow_map_resolution.min(256);
            if let Some(r) = &mut scene.receiver_map {
                r.resolution = r.resolution.min(128);
            }
        }
        if cell.lights > 0 {
            set_light_count(&mut scene, cell.lights as usize)
                .with_context(|| format!("{}: key `matrix.lights`", self.config.path.display()))?;
        }
        if cell.resolution != [0, 0] {
            scene.camera.width = cell.resolution[0];
            scene.camera.height = cell.resolution[1];
        }
        if !self.needs_receiver_map() {
            // The receiver map is a validation instrument, not part of any technique. But its
            // rectangle frames the light-space caustic map (`techniques::uniforms`): a `flip`
            // cell keeps the scene's, so that its final image and the reference's are those
            // `causticlab render` and `reference --final` make of the scene.
            if !self.needs_flip() {
                scene.receiver_map = None;
            }
        } else if scene.receiver_map.is_none() {
            anyhow::bail!(caustics::input_error!(
                "{}: a quality, temporal_change or progressive metric needs a [receiver_map] in scene {}",
                self.config.path.display(),
                path.display()
            ));
        }
        let (file, key) = (self.config.path.display().to_string(), format!("technique[{}].", cell.technique));
        scene.caustics.validate(&file, &key)?;
        scene.caustics.validate_combination(&format!("{file} with scene {}", path.display()), &key)?;
        if cell.lighting == "static" && scene.lights.len() > 1 {
            // The photon buffer is shared between lights: reusing it needs one light.
            anyhow::bail!(caustics::input_error!(
                "{}: key `matrix.lighting`: static lighting reuses the photon buffer, which holds one light, \
                 but {} has {} lights",
                self.config.path.display(),
                path.display(),
                scene.lights.len()
            ));
        }
        Ok((scene, shared))
    }

    pub fn run(&mut self, cell: &Cell) -> Result<CellRun> {
        let c = &self.config.config;
        let (scene, shared) = self.cell_scene_and_shared(cell)?;
        let t = &c.techniques[cell.technique];
        let copy = CopyType::parse(&t.photon_copy).flatten();
        let per_pass_timing = c.metrics.iter().any(|m| !m.throughput() && crate::results::is_timing(&m.kind));
        let throughput = c.metrics.iter().any(|m| m.throughput());
        let opts = RendererOptions { photon_copy: copy, frame_mode: FrameMode::PerPass, pass_timestamps: false };
        let mut renderer = Renderer::new(self.ctx, self.shaders, &scene, &opts)?;
        let static_lighting = cell.lighting == "static";
        let anim = Animation {
            light: c.run.light_path == "orbit" && !static_lighting,
            camera: c.run.camera_path == "orbit",
            object: c.run.object_path == "orbit" && !static_lighting,
            period_frames: c.run.period_frames,
        };
        let mut plan = c.frame_plan(self.quick.is_some());
        // Untimed frames along an animation for a quality or temporal metric: the warm-up
        // frames (which fill a temporal filter's history), then exactly `measured_frames`.
        // The acceleration structures' build counts likewise read the pose updates between frames.
        let counts_poses = c.metrics.iter().any(|m| crate::config::is_pose_count(&m.kind));
        let along_animation = !per_pass_timing && !anim.is_static() && (self.needs_receiver_map() || counts_poses);
        if along_animation {
            plan = crate::config::FramePlan { max: plan.min, budget_s: 0.0, ..plan };
        } else if !per_pass_timing {
            // Only counts and quality come from per-pass frames: one frame, no warm-up.
            plan = crate::config::FramePlan { warmup: 0, min: 1, max: 1, budget_s: 0.0 };
        }
        let step = FrameStep {
            reuse_photons: static_lighting,
            pipeline_statistics: false,
            host_pass_times: c.host_pass_times(),
        };
        if static_lighting {
            // Static lighting renders its photon buffer once, before any frame is timed.
            renderer.frame(FrameStep::default())?;
        }
        let mut frames = vec![];
        let mut wall_ms = vec![];
        let mut pose_ms = vec![];
        let mut pose_counters = vec![];
        let mut counters = vec![];
        // temporal_change: the last measured frame's receiver map, and each frame's change from it.
        let temporal = self.needs_temporal();
        let mut last_receiver: Option<ImageF32> = None;
        let mut temporal_changes = vec![];
        let host_probe_ms = crate::host_speed::probe_ms();
        let cpu_before = crate::steal::sample();
        // Warm-up frames, then measured frames until the plan is met: at least `min` frames
        // and `budget_s` seconds of them (pose updates included), at most `max`.
        let mut measuring_since = None;
        let mut f = 0u32;
        loop {
            if f >= plan.warmup {
                let since = *measuring_since.get_or_insert_with(Instant::now);
                let n = frames.len() as u32;
                if plan.done(n, since.elapsed().as_secs_f64()) && whole_loops(&anim, n, plan.max) {
                    break;
                }
            }
            let before = self.ctx.counters();
            let mut posed = None;
            if f > 0 && !anim.is_static() {
                let pose = scene_at(&scene, &anim, f);
                let start = Instant::now();
                renderer.set_pose(&pose)?;
                posed = Some((start.elapsed().as_secs_f64() * 1e3, self.ctx.counters().since(&before)));
            }
            let start = Instant::now();
            let report = renderer.frame(step)?;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            if f >= plan.warmup {
                if let Some((ms, c)) = posed {
                    pose_ms.push(ms);
                    pose_counters.push(c);
                }
                frames.push(report);
                wall_ms.push(ms);
                counters.push(self.ctx.counters().since(&before));
                if temporal {
                    // Read back after the frame's time was taken (validation refuses timed
                    // per-pass metrics beside temporal_change).
                    let map = renderer.receiver_map()?.context("the render has no receiver map")?;
                    if let Some(last) = &last_receiver {
                        temporal_changes.push(compare(&map, last)?.0.rel_rmse);
                    }
                    last_receiver = Some(map);
                }
            }
            f += 1;
        }
        let cpu_steal = cpu_before.zip(crate::steal::sample()).and_then(|(a, b)| crate::steal::fraction(a, b));
        // The pose of the last frame rendered, which the quality metrics compare: frame 0's (the
        // scene's own) unless the light or the objects move (the camera does not change the
        // receiver map).
        let last_pose = (f > 1 && (anim.light || anim.object)).then(|| f - 1);
        // Before the statistics frame, which would add a frame in the same pose (to a temporal
        // filter's history too).
        // A progressive technique's quality and final image are its first frame's (the means
        // started again): its frames so far depend on the time budget. Its curve is the
        // progressive metrics'.
        if (self.needs_quality() || self.needs_flip()) && renderer.caustics().is_some_and(|c| c.progressive()) {
            renderer.restart_accumulation();
            renderer.frame(step)?;
        }
        let quality =
            if self.needs_quality() { Some(self.quality(&mut renderer, &scene, &anim, last_pose)?) } else { None };
        // Validated: the progressive metrics' light and objects stay still.
        let progressive =
            if self.needs_progressive() { self.progressive_curve(&mut renderer, &scene, &anim, step)? } else { vec![] };
        // The last frame's final image (paths are static with a flip metric: validated).
        let final_flip = if self.needs_flip() {
            let ours = renderer.final_image()?;
            let r = self.final_refinement()?;
            let reference_scene = crate::final_flip::reference_scene(&scene, &shared)?;
            let reference = self.final_references.get(self.ctx, self.shaders, &reference_scene, &r)?;
            Some(crate::final_flip::flip_of(&ours, reference, crate::final_flip::ReferenceFinal::of(&r))?)
        } else {
            None
        };
        let stats_frame = if per_pass_timing && self.ctx.info().has(vkcore::Feature::PipelineStatisticsQuery) {
            Some(renderer.frame(FrameStep { pipeline_statistics: true, ..step })?)
        } else {
            None
        };
        let valid_photons = if self.needs_valid_photons() { renderer.valid_photons(None)? } else { None };
        let depth_complexity = if self.needs_depth_complexity() {
            // Eye-space quads count into the eye's caustic, light-space ones into the caustic map.
            let dump = match renderer.read_dump(&caustics::techniques::wyman_davis2006::settings::EYE_CAUSTIC)? {
                Some(img) => Some(img),
                None => renderer.read_dump(&caustics::techniques::shared::settings::CAUSTIC_MAP)?,
            };
            let img = dump.context("depth complexity: the technique has neither an eye_caustic nor a caustic_map")?;
            Some(DepthComplexity::of(&img)?)
        } else {
            None
        };
        let caustics = renderer.caustics();
        let hierarchy_sizes = caustics.map(|c| c.list_sizes(self.ctx)).transpose()?.flatten();
        let adaptive = caustics.and_then(|c| c.adaptive());
        let (photon_storage, photon_batches) =
            (adaptive.map(|a| a.photon_storage_bytes()), adaptive.map(|a| a.plan().batches));
        let (photons_emitted, splats_drawn) = (renderer.photons_emitted(), renderer.splats_drawn()?);
        let throughput = if throughput {
            // One renderer at a time: the per-pass one's buffers go before the ring's are made.
            drop(renderer);
            let opts = RendererOptions { frame_mode: FrameMode::throughput(), ..opts };
            let scene = without_instruments(&scene);
            let mut renderer = Renderer::new(self.ctx, self.shaders, &scene, &opts)?;
            let t = self.measure_throughput(&mut renderer, &scene, &anim, static_lighting)?;
            Some(t)
        } else {
            None
        };
        let other_cores = cpu_before.zip(crate::steal::sample()).and_then(|(a, b)| crate::steal::other_cores(a, b));
        if !per_pass_timing {
            frames.clear();
            wall_ms.clear();
            pose_ms.clear();
            counters.clear();
        }
        Ok(CellRun {
            frames,
            wall_ms,
            pose_ms,
            pose_counters,
            counters,
            throughput,
            stats_frame,
            photons_emitted,
            splats_drawn,
            hierarchy_sizes,
            photon_storage,
            photon_batches,
            quality,
            valid_photons,
            lights: scene.lights.len() as u64,
            caustics: scene.caustics.clone(),
            triangles: scene.triangle_count(),
            models: scene.models(),
            cpu_steal,
            other_cores,
            host_probe_ms,
            depth_complexity,
            temporal_changes,
            progressive,
            final_flip,
        })
    }

    /// Progressive accumulation's curve (`crate::progressive`): the means started again, then
    /// frame after frame, each timed (its `passes`' host times, or its wall time) and its
    /// receiver map compared with the reference after it (outside the time), until the curve
    /// reaches every progressive metric's frames and time.
    fn progressive_curve(
        &mut self,
        renderer: &mut Renderer,
        scene: &Scene,
        anim: &Animation,
        step: FrameStep,
    ) -> Result<Vec<crate::progressive::Point>> {
        let metrics = &self.config.config.metrics;
        let targets = crate::progressive::targets(metrics);
        let passes = crate::progressive::timed_passes(metrics);
        let step = FrameStep { host_pass_times: !passes.is_empty(), reuse_photons: false, ..step };
        renderer.restart_accumulation();
        let mut curve: Vec<crate::progressive::Point> = vec![];
        let mut ms = 0.0;
        let cap = if self.quick.is_some() { crate::progressive::QUICK_FRAMES } else { crate::progressive::MAX_FRAMES };
        while !crate::progressive::reached(&curve, targets, cap) {
            let start = Instant::now();
            let report = renderer.frame(step)?;
            let wall = start.elapsed().as_secs_f64() * 1e3;
            ms += crate::progressive::frame_time(&passes, &report, wall).with_context(|| {
                format!(
                    "progressive metrics: no pass of a frame matches {passes:?} (passes: {:?})",
                    pass_names(&report)
                )
            })?;
            let rel_rmse = self.quality(renderer, scene, anim, None)?.rel_rmse;
            curve.push(crate::progressive::Point { frames: curve.len() as u32 + 1, ms, rel_rmse });
        }
        Ok(curve)
    }

    /// The throughput frame mode: frames submitted back to back through the renderer's ring,
    /// poses updated between them; after the warm-up (at least one frame per slot, waited for,
    /// then twice as many frames as the ring has slots, untimed), blocks of
    /// `run.block_frames` frames timed on the host from the start of one block to the start of
    /// the next (the ring is full from the warm-up on, so each submit waits for the frame
    /// `slots` before it: the submits are paced by the GPU), until there
    /// are at least `MIN_BLOCKS` blocks, `measured_frames` frames and the time budget, and, along
    /// an animation, whole loops of it.
    fn measure_throughput(
        &self,
        renderer: &mut Renderer,
        scene: &Scene,
        anim: &Animation,
        static_lighting: bool,
    ) -> Result<ThroughputRun> {
        let c = &self.config.config;
        let plan = c.frame_plan(self.quick.is_some());
        let block = c.run.block_frames.max(1);
        let step = FrameStep { reuse_photons: static_lighting, ..FrameStep::default() };
        if static_lighting {
            renderer.frame(FrameStep::default())?;
        }
        let warmup = plan.warmup.max(FrameMode::SLOTS as u32);
        let mut f = 0u32;
        let submit = |renderer: &mut Renderer, f: u32, reports: &mut Vec<FrameReport>| -> Result<Counters> {
            let before = self.ctx.counters();
            if f > 0 && !anim.is_static() {
                renderer.set_pose(&scene_at(scene, anim, f))?;
            }
            reports.extend(renderer.submit(step)?);
            Ok(self.ctx.counters().since(&before))
        };
        let mut reports = vec![];
        while f < warmup {
            submit(renderer, f, &mut reports)?;
            f += 1;
        }
        // Frames in flight carry their time into the next submits: wait for the (cold) warm-up
        // frames, or the first block pays for the warm-up (measured: 1016 ms against 633-689 ms
        // for the blocks after it, beethoven_standin's eye gather on lavapipe). The first
        // frames after that wait are still slow on lavapipe (the ring's eye gather, 512²,
        // static, 10 blocks: the first 831 ms against 485-727 for the nine after it), so two
        // rings' worth of frames go before the first timed block (then 587 and 657 ms against
        // 521-712 in two runs). A quick run's times are not measurements: it goes straight on.
        renderer.finish()?;
        let settle = if self.quick.is_some() { 0 } else { 2 * FrameMode::SLOTS };
        for _ in 0..settle {
            submit(renderer, f, &mut reports)?;
            f += 1;
        }
        let first_measured = f as u64;
        let mut out = ThroughputRun { block_frames: block, ..Default::default() };
        let started = Instant::now();
        let mut block_start = Instant::now();
        loop {
            for _ in 0..block {
                out.counters.push(submit(renderer, f, &mut reports)?);
                f += 1;
            }
            let now = Instant::now();
            out.block_ms.push((now - block_start).as_secs_f64() * 1e3 / block as f64);
            block_start = now;
            let (blocks, frames) = (out.block_ms.len() as u32, out.block_ms.len() as u32 * block);
            let min_blocks = crate::config::min_blocks(self.quick.is_some());
            let enough = blocks >= min_blocks
                && plan.done(frames, started.elapsed().as_secs_f64())
                && whole_loops(anim, frames, plan.max);
            if enough || frames >= plan.max.max(min_blocks * block) {
                break;
            }
        }
        reports.extend(renderer.finish()?);
        let measured_end = first_measured + (out.block_ms.len() as u64) * block as u64;
        let measured = || reports.iter().filter(|r| (first_measured..measured_end).contains(&r.index));
        out.gpu_frame_ms = measured().filter_map(|r| r.frame_gpu_ms).collect();
        out.passes = measured().map(|r| r.passes.len()).collect();
        Ok(out)
    }

    /// The last frame's receiver map against the CPU reference of the same scene and lights, in
    /// the pose of that frame along the animation (`last_pose`, frame 0's when `None`).
    fn quality(
        &mut self,
        renderer: &mut Renderer,
        scene: &Scene,
        anim: &Animation,
        last_pose: Option<u32>,
    ) -> Result<Comparison> {
        let q = &self.config.config.quality;
        let photons = self.quick.map(|k| k.reference_photons).unwrap_or(q.reference_photons);
        // The scene at rest and the pose (the frame, and what moves: a static-lighting cell of
        // the same config keeps its light and objects still along the same frames) decide the
        // posed scene, which is made only to trace a reference not yet kept.
        let pose = last_pose.map(|f| (f, anim.light, anim.object, anim.period_frames));
        let key = format!(
            "{:?}|{:?}|{:?}|{}|{:?}",
            scene.path, scene.lights, scene.receiver_map, scene.caustics.fresnel, pose
        );
        if !self.references.contains_key(&key) {
            let posed = last_pose.map(|f| scene_at(scene, anim, f));
            let scene = posed.as_ref().unwrap_or(scene);
            let opts =
                ReferenceOptions { photons, seed: q.seed, fresnel: scene.caustics.fresnel, ..Default::default() };
            let r = trace_reference(scene, &opts)
                .with_context(|| format!("tracing the CPU reference of {}", scene.path.display()))?;
            self.references.insert(key.clone(), r.image);
        }
        let reference = &self.references[&key];
        let ours = renderer.receiver_map()?.context("the render has no receiver map to compare")?;
        Ok(compare(&ours, reference)?.0)
    }
}

/// `scene` without the validation instruments that a quality metric adds to its frames: the
/// receiver map (whose pass averages the caustic map over each receiver texel, and whose
/// eye-space view the Wyman & Davis techniques render for it) and photon-trace's binning into
/// it. The throughput frames are timed on this scene, so that a quality metric in the same
/// config (the error-against-time front, `front.toml`) does not add the instrument's cost to
/// the time; the quality comes from the per-pass renderer's frame.
fn without_instruments(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    // The receiver map goes, its rectangle stays where it frames the light-space caustic map:
    // the timed frames render the caustic map the quality frames measured (a photon's splat in
    // texels, as photon differentials size it, follows the framing).
    s.caustic_frame = s.receiver_map.take().or(s.caustic_frame);
    if s.caustics.receiver_deposit() {
        s.caustics.deposit = caustics::techniques::photon_trace::settings::Deposit::CausticMap;
    }
    s
}

/// Along an animation, a cell measures whole loops of it (or stops at `max` frames), so that
/// every cell of a config sees the same poses: a camera orbit's cost varies along the loop.
fn whole_loops(anim: &Animation, frames: u32, max: u32) -> bool {
    anim.is_static() || frames >= max || frames.is_multiple_of(anim.period_frames.max(1))
}

/// Keeps the first `n` lights, or adds copies of the last one turned about the vertical axis
/// through the centre of the scene's bounds: with m lights in the scene, the j-th copy
/// (j = 1..=n−m) by 360°·j/(n−m+1).
fn set_light_count(scene: &mut Scene, n: usize) -> Result<()> {
    anyhow::ensure!(!scene.lights.is_empty(), "{}: the scene has no light to copy", scene.path.display());
    if scene.lights.len() >= n {
        scene.lights.truncate(n);
        return Ok(());
    }
    let (lo, hi) = scene.bounds();
    let pivot = 0.5 * (lo + hi);
    let last = scene.lights[scene.lights.len() - 1].clone();
    let have = scene.lights.len();
    for k in have..n {
        let turn = Mat3::from_rotation_y(std::f32::consts::TAU * (k + 1 - have) as f32 / (n + 1 - have) as f32);
        let mut l = last.clone();
        l.position = pivot + turn * (l.position - pivot);
        if let caustics::scene::LightKind::Spot { direction, .. } = &mut l.kind {
            *direction = (turn * *direction).normalize_or(Vec3::NEG_Y);
        }
        scene.lights.push(l);
    }
    Ok(())
}

/// The names of a frame's passes, for messages.
fn pass_names(report: &FrameReport) -> Vec<&str> {
    report.passes.iter().map(|p| p.name.as_str()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shipped(name: &str) -> Scene {
        let p = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes").join(name);
        Scene::load(&p).expect("a shipped scene")
    }

    #[test]
    fn timed_frames_leave_out_the_receiver_map_and_the_binning_into_it() {
        let mut s = shipped("sphere_on_plane.toml");
        s.caustics.technique = "photon-trace".parse().expect("a known name");
        s.caustics.deposit = "receiver-map".parse().expect("a known name");
        assert!(s.receiver_map.is_some() && s.caustics.receiver_deposit());
        let timed = without_instruments(&s);
        assert!(timed.receiver_map.is_none() && !timed.caustics.receiver_deposit());
        // Every other setting is the cell's.
        let mut back = timed.caustics.clone();
        back.deposit = s.caustics.deposit;
        assert_eq!(back, s.caustics);
        let mut shah = shipped("sphere_on_plane.toml");
        shah.caustics.technique = "shah".parse().expect("a known name");
        let timed = without_instruments(&shah);
        assert!(timed.receiver_map.is_none());
        assert_eq!(timed.caustics, shah.caustics);
    }

    /// The timed frames frame the light-space caustic map as the quality frames do: the
    /// receiver rectangle stays (`Scene::caustic_frame`), where dropping it with the receiver
    /// map had widened the map's cone (seen at 39bb57b: photon differentials on the ring, whose
    /// kernels follow the texels, cost 89.5 ms a throughput frame against 133.7 ms of caustic
    /// stages alone in F1).
    #[test]
    fn timed_frames_keep_the_caustic_maps_framing() {
        use caustics::techniques::uniforms::caustic_uniforms;
        for name in ["ring_cardioid.toml", "sphere_oblique.toml"] {
            let mut s = shipped(name);
            s.caustics.technique = "photon-trace".parse().expect("a known name");
            let timed = without_instruments(&s);
            assert!(timed.receiver_map.is_none());
            let (a, b) =
                (caustic_uniforms(&s, &s.caustics).unwrap(), caustic_uniforms(&timed, &timed.caustics).unwrap());
            assert_eq!(a.lights[0].caustic_plane, b.lights[0].caustic_plane, "{name}");
            assert_eq!(a.lights[0].caustic_view_proj, b.lights[0].caustic_view_proj, "{name}");
            // Without the rectangle the cone is another (what the timed frames rendered before).
            let mut bare = s.clone();
            bare.receiver_map = None;
            let c = caustic_uniforms(&bare, &bare.caustics).unwrap();
            assert_ne!(a.lights[0].caustic_plane, c.lights[0].caustic_plane, "{name}");
        }
    }

    #[test]
    fn depth_complexity_counts_the_covered_pixels_of_every_layer() {
        use caustics::image_io::Layer;
        // Two 2x2 layers (two lights): counts 0, 3, 1, 0 and 2, 0, 0, 5 in the fourth channel.
        let layer = |counts: [f32; 4]| {
            let data = counts.iter().flat_map(|&c| [9.0, 9.0, 9.0, c]).collect();
            Layer::new(None, &["R", "G", "B", "photons"], data)
        };
        let img =
            ImageF32 { width: 2, height: 2, layers: vec![layer([0.0, 3.0, 1.0, 0.0]), layer([2.0, 0.0, 0.0, 5.0])] };
        let d = DepthComplexity::of(&img).expect("four channels");
        assert_eq!(d.covered, [1.0, 2.0, 3.0, 5.0]);
        assert_eq!(d.pixels, 8);
        assert_eq!(d.coverage(), Some(0.5));
        assert_eq!(d.mean(), Some(2.75));
        assert_eq!(d.percentile(0.5), Some(2.0));
        assert_eq!(d.percentile(0.9), Some(5.0));
        assert_eq!(d.percentile(0.0), Some(1.0));
        let empty = DepthComplexity { covered: vec![], pixels: 4 };
        assert_eq!((empty.mean(), empty.percentile(0.5), empty.coverage()), (None, None, Some(0.0)));
        // A dump with no pixels has no coverage (not 0/0).
        let nothing = DepthComplexity::of(&ImageF32 { width: 0, height: 0, layers: vec![] }).expect("no layers");
        assert_eq!((nothing.pixels, nothing.coverage()), (0, None));
    }

    #[test]
    fn the_temporal_change_is_the_mean_over_the_pairs_of_frames() {
        let run = |changes: &[f64]| CellRun { temporal_changes: changes.to_vec(), ..CellRun::default() };
        assert_eq!(run(&[0.25, 0.5, 0.0]).temporal_change(), Some(0.25));
        assert_eq!(run(&[0.125]).temporal_change(), Some(0.125));
        // One measured frame has no pair: no value, not a change of 0.
        assert_eq!(run(&[]).temporal_change(), None);
    }

    #[test]
    fn a_moving_frame_count_ends_on_whole_loops_or_at_the_most_frames() {
        let orbit = Animation { light: true, camera: false, object: false, period_frames: 60 };
        assert!(whole_loops(&orbit, 120, 1000) && !whole_loops(&orbit, 90, 1000));
        assert!(whole_loops(&orbit, 90, 90), "the most frames end the cell mid-loop");
        assert!(!whole_loops(&orbit, 90, 91));
        let still = Animation { light: false, ..orbit.clone() };
        assert!(whole_loops(&still, 7, 1000), "a static cell ends anywhere");
        // A period of 0 counts as 1.
        assert!(whole_loops(&Animation { period_frames: 0, ..orbit }, 7, 1000));
    }

    #[test]
    fn more_lights_are_copies_of_the_last_turned_evenly_about_the_scenes_centre() {
        let mut s = shipped("sphere_on_plane.toml");
        assert_eq!(s.lights.len(), 1);
        let direction = Vec3::new(1.0, -1.0, 0.0).normalize();
        s.lights[0].kind = caustics::scene::LightKind::Spot { direction, cone_angle_deg: 30.0, texture: None };
        let (lo, hi) = s.bounds();
        let pivot = 0.5 * (lo + hi);
        let first = s.lights[0].position - pivot;
        set_light_count(&mut s, 3).unwrap();
        assert_eq!(s.lights.len(), 3);
        for (j, l) in s.lights.iter().enumerate() {
            // The j-th turned by 120° j about the vertical axis through the centre of the bounds.
            let turn = Mat3::from_rotation_y(std::f32::consts::TAU * j as f32 / 3.0);
            assert!((l.position - (pivot + turn * first)).length() < 1e-4, "light {j}: {}", l.position);
            let caustics::scene::LightKind::Spot { direction: d, .. } = l.kind else { panic!("a spot") };
            assert!((d - turn * direction).length() < 1e-5 && (d.length() - 1.0).abs() < 1e-6, "light {j}: {d}");
        }
        // Fewer: the first ones kept.
        let kept = s.lights[0].clone();
        set_light_count(&mut s, 1).unwrap();
        assert_eq!(s.lights, [kept]);
        s.lights.clear();
        let err = set_light_count(&mut s, 2).unwrap_err();
        assert!(format!("{err}").contains("no light to copy"), "{err}");
    }
}
