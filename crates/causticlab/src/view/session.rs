//! What the viewer keeps between frames: the scene (its camera, light and size as the user
//! moved them, its `[caustics]` as the panel set them), the renderer of that technique and,
//! with `--compare`, of a second one (the same settings but the technique's own), the display
//! image, the animation, and the last few hundred frames' timings. Renderers draw throughput
//! frames with a timestamp pair around every pass; a change of size, settings or shaders
//! builds new ones and keeps the old running when that fails.

use super::settings;
use anyhow::{Context as _, Result};
use caustics::animation::{self, Animation};
use caustics::dump::named_in;
use caustics::image_io::{self, header, OutputDir};
use caustics::render::display::Display;
use caustics::render::{self, FrameMode, FrameStep, Renderer, RendererOptions};
use caustics::scene::{CausticSettings, Scene};
use caustics::techniques::Technique;
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use vkcore::{Context, FrameReport, ShaderCompiler};

/// Which technique the window shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shown {
    A,
    B,
    /// A left of the divider, B right of it.
    Split,
}

/// Frames kept for the timing graph.
pub const HISTORY: usize = 300;

/// One finished frame's GPU time per pass, in milliseconds.
#[derive(Debug, Clone, Default)]
pub struct FrameTimes {
    pub passes: Vec<(String, f64)>,
}

impl FrameTimes {
    pub fn total_ms(&self) -> f64 {
        self.passes.iter().map(|(_, ms)| ms).sum()
    }
}

pub struct Session<'c> {
    ctx: &'c Context,
    shaders: &'c ShaderCompiler,
    /// The scene at rest: the user's camera, light and window size, the panel's settings.
    pub scene: Scene,
    /// The second technique (`--compare`), if any.
    pub compare: Option<Technique>,
    a: Renderer<'c>,
    b: Option<Renderer<'c>>,
    pub display: Display,
    pub shown: Shown,
    /// The divider's place in split view, as a fraction of the width.
    pub split: f32,
    pub animation: Animation,
    pub playing: bool,
    pub animation_frame: u32,
    pose_changed: bool,
    /// The last rebuild for changed shaders failed: rebuild on any change until one succeeds.
    reload_failed: bool,
    /// The last error (a refused setting, a shader that does not compile), shown in the panel.
    pub error: Option<String>,
    /// Status lines (files written), newest last.
    pub log: Vec<String>,
    pub history: VecDeque<FrameTimes>,
    /// Frames submitted.
    pub frames: u64,
    /// `--dump`: the buffers the dump key writes (empty: every buffer of the technique).
    pub dumps: Vec<String>,
    /// `--out`.
    pub out: PathBuf,
    /// A timestamp pair around every pass (the graph), else around the frame.
    pass_timestamps: bool,
}

fn renderer<'c>(
    ctx: &'c Context,
    shaders: &'c ShaderCompiler,
    scene: &Scene,
    pass_timestamps: bool,
) -> Result<Renderer<'c>> {
    let opts = RendererOptions { frame_mode: FrameMode::throughput(), pass_timestamps, ..Default::default() };
    Renderer::new(ctx, shaders, scene, &opts)
}

impl<'c> Session<'c> {
    pub fn new(
        ctx: &'c Context,
        shaders: &'c ShaderCompiler,
        scene: Scene,
        compare: Option<Technique>,
        dumps: Vec<String>,
        out: PathBuf,
        pass_timestamps: bool,
    ) -> Result<Session<'c>> {
        let size = (scene.camera.width, scene.camera.height);
        let a = renderer(ctx, shaders, &scene, pass_timestamps)?;
        let mut session = Session {
            ctx,
            shaders,
            display: Display::new(ctx, shaders, size)?,
            scene,
            compare,
            a,
            b: None,
            shown: Shown::A,
            split: 0.5,
            animation: Animation { light: true, camera: false, object: false, period_frames: 360 },
            playing: false,
            animation_frame: 0,
            pose_changed: false,
            reload_failed: false,
            error: None,
            log: vec![],
            history: VecDeque::new(),
            frames: 0,
            dumps,
            out,
            pass_timestamps,
        };
        if let Some(s) = session.scene_b(&session.scene) {
            session.b = Some(renderer(ctx, shaders, &s, pass_timestamps).context("--compare")?);
        }
        Ok(session)
    }

    /// `scene` with the second technique (its own settings back to their defaults).
    fn scene_b(&self, scene: &Scene) -> Option<Scene> {
        let t = self.compare?;
        let mut s = scene.clone();
        s.caustics = settings::with_technique(&scene.caustics, t);
        Some(s)
    }

    /// The scene at the animation's current frame.
    fn posed(&self, scene: &Scene) -> Scene {
        animation::scene_at(scene, &self.animation, self.animation_frame)
    }

    /// The settings of the technique shown (B's when B alone is shown).
    pub fn shown_settings(&self) -> CausticSettings {
        match (self.shown, self.scene_b(&self.scene)) {
            (Shown::B, Some(b)) => b.caustics,
            _ => self.scene.caustics.clone(),
        }
    }

    /// The camera or light moved: the renderers take the new pose at the next frame.
    pub fn moved(&mut self) {
        self.pose_changed = true;
    }

    /// Builds renderers for `scene` (and its B), replacing the running ones only when every
    /// one was built.
    fn rebuild(&mut self, scene: Scene) -> Result<()> {
        self.finish()?;
        // The presenter's copy of the display image may still run: the old display image and
        // renderers go only once the device is idle.
        self.ctx.wait_idle()?;
        let posed = self.posed(&scene);
        let a = renderer(self.ctx, self.shaders, &posed, self.pass_timestamps)?;
        let b = match self.scene_b(&posed) {
            Some(s) => {
                Some(renderer(self.ctx, self.shaders, &s, self.pass_timestamps).context("the --compare technique")?)
            }
            None => None,
        };
        self.a = a;
        self.b = b;
        self.scene = scene;
        self.pose_changed = false;
        Ok(())
    }

    /// Whether every pass is timed (else whole frames).
    pub fn pass_timestamps(&self) -> bool {
        self.pass_timestamps
    }

    /// Times every pass (`on`, the graph) or whole frames: new renderers; on an error the running
    /// ones stay, with the timing they had.
    pub fn set_pass_timestamps(&mut self, on: bool) -> Result<()> {
        let was = std::mem::replace(&mut self.pass_timestamps, on);
        let result = self.rebuild(self.scene.clone());
        match &result {
            Ok(()) => {
                self.history.clear();
                self.log.push(format!("timing {}", if on { "every pass" } else { "whole frames" }));
            }
            Err(_) => self.pass_timestamps = was,
        }
        self.note(result.as_ref().err());
        result
    }

    /// Sets `[caustics]` key `key` to `value` (as the panel and `--script` `set` do): checked,
    /// then new renderers; on an error the running ones stay and the error is kept for the
    /// panel (and returned).
    pub fn set(&mut self, key: &str, value: &str) -> Result<()> {
        let result = settings::apply(&self.scene.caustics, key, value).and_then(|c| {
            let mut scene = self.scene.clone();
            scene.caustics = c;
            self.rebuild(scene)
        });
        self.note(result.as_ref().err());
        result
    }

    /// The window's new size: render at it.
    pub fn resize(&mut self, size: (u32, u32)) -> Result<()> {
        let size = (size.0.max(1), size.1.max(1));
        if size == (self.scene.camera.width, self.scene.camera.height) {
            return Ok(());
        }
        let mut scene = self.scene.clone();
        scene.camera.width = size.0;
        scene.camera.height = size.1;
        let result = self.rebuild(scene).and_then(|_| self.display.resize(self.ctx, size));
        self.note(result.as_ref().err());
        result
    }

    /// Shader files changed (root-relative paths): the compiler forgets what was made from
    /// them and, where a running pipeline was, the renderers are built again beside the running
    /// ones. A pipeline whose SPIR-V the edit left as it was is the running one, shared
    /// (`vkcore`'s shared pipelines): only the pipelines that use the edited files are made.
    /// Returns the line it logs, which names them and the time taken (`None`: nothing was
    /// built); an error (`file:line: message`) leaves the running pipelines in place.
    pub fn reload(&mut self, changed: &[String]) -> Result<Option<String>> {
        let forgotten = self.shaders.forget(changed);
        if forgotten == 0 && !self.reload_failed {
            return Ok(None);
        }
        let mark = self.ctx.pipelines_made();
        let start = std::time::Instant::now();
        let size = self.display.size();
        let result = Display::new(self.ctx, self.shaders, size).and_then(|d| {
            self.rebuild(self.scene.clone())?;
            self.display = d;
            Ok(())
        });
        self.reload_failed = result.is_err();
        self.note(result.as_ref().err());
        result?;
        let line = format!(
            "reloaded shaders ({}): {} in {:.0} ms",
            files(changed),
            rebuilt(&self.ctx.pipelines_made_since(mark)),
            start.elapsed().as_secs_f64() * 1e3
        );
        self.log.push(line.clone());
        Ok(Some(line))
    }

    fn note(&mut self, err: Option<&anyhow::Error>) {
        self.error = err.map(|e| format!("{e:#}"));
    }

    /// Renders one frame of what is shown into the display image (submitted, not waited for);
    /// the timings of frames that finished go to the history.
    pub fn frame(&mut self) -> Result<()> {
        if self.playing {
            self.animation_frame = (self.animation_frame + 1) % self.animation.period_frames.max(1);
            self.pose_changed = true;
        }
        if self.pose_changed {
            let posed = self.posed(&self.scene);
            let posed_b = self.scene_b(&posed);
            if let (Some(b), Some(s)) = (self.b.as_mut(), posed_b) {
                b.set_pose(&s)?;
            }
            self.a.set_pose(&posed)?;
            self.pose_changed = false;
        }
        let step = FrameStep::default();
        let exposure = self.scene.render.exposure;
        let display = &self.display;
        let shown = if self.b.is_none() { Shown::A } else { self.shown };
        let mut reports = vec![];
        match (shown, self.b.as_mut()) {
            (Shown::B, Some(b)) => {
                reports.extend(b.submit_with(step, &mut |f, own| display.record(f, own, None, exposure))?);
            }
            (Shown::Split, Some(b)) => {
                // B's frame first; A's frame then draws both halves (the tracker orders the reads).
                let _ = b.submit(step)?;
                let split = (self.split.clamp(0.0, 1.0) * display.size().0 as f32) as u32;
                let b_view = b.final_view();
                reports.extend(
                    self.a.submit_with(step, &mut |f, own| display.record(f, own, Some((b_view, split)), exposure))?,
                );
            }
            _ => {
                reports.extend(self.a.submit_with(step, &mut |f, own| display.record(f, own, None, exposure))?);
            }
        }
        self.frames += 1;
        self.record(reports);
        Ok(())
    }

    fn record(&mut self, reports: Vec<FrameReport>) {
        for r in reports {
            let mut passes: Vec<(String, f64)> =
                r.passes.iter().filter_map(|p| p.gpu_ms.map(|ms| (p.name.clone(), ms))).collect();
            if passes.is_empty() {
                // Timed per frame (`--pass-timing frame`, T): the frame is one bar.
                passes.extend(r.frame_gpu_ms.map(|ms| ("frame".to_string(), ms)));
            }
            self.history.push_back(FrameTimes { passes });
            while self.history.len() > HISTORY {
                self.history.pop_front();
            }
        }
    }

    /// Waits for every frame in flight.
    pub fn finish(&mut self) -> Result<()> {
        let mut reports = self.a.finish()?;
        if let Some(b) = self.b.as_mut() {
            b.finish()?;
        }
        if self.shown == Shown::B && self.b.is_some() {
            reports.clear();
        }
        self.record(reports);
        Ok(())
    }

    /// The renderer of what is shown (A in split view).
    fn shown_renderer(&mut self) -> &mut Renderer<'c> {
        match (self.shown, self.b.as_mut()) {
            (Shown::B, Some(b)) => b,
            _ => &mut self.a,
        }
    }

    /// What every file written here says in its EXR header.
    fn header(&self, settings: &CausticSettings) -> Vec<(&'static str, String)> {
        let info = self.ctx.info();
        vec![
            (header::TECHNIQUE, settings.technique.to_string()),
            (header::PHOTON_BUFFER, format!("{0}x{0}", settings.photons)),
            (header::COMMIT, bench::meta::commit()),
            (header::DEVICE, format!("{} ({})", info.name, info.driver_info)),
            (header::SCENE, self.scene.path.display().to_string()),
            (header::WRITER, "causticlab view".to_string()),
        ]
    }

    /// final.exr and final.png of the current frame, as `render` writes them, and display.png
    /// (the window's image without its panel), into `dir`.
    pub fn screenshot(&mut self, dir: &Path) -> Result<Vec<PathBuf>> {
        let out = OutputDir::create(dir)?;
        self.finish()?;
        let settings = self.shown_settings();
        let header = self.header(&settings);
        let image = self.shown_renderer().final_image()?;
        let mut files = crate::cmd_render::write_final_images(&out, &image, &header, self.scene.render.exposure)?;
        let (dw, dh, display) = self.display.read_rgb8(self.ctx)?;
        image_io::write_rgb8_png(&out.path("display.png"), dw, dh, &display)?;
        files.push("display.png".to_string());
        let written: Vec<PathBuf> = files.iter().map(|f| out.final_dir().join(f)).collect();
        out.commit()?;
        self.log.extend(written.iter().map(|p| format!("wrote {}", p.display())));
        Ok(written)
    }

    /// The named buffers of the current frame (`all`, a list, or None: `--dump`'s, else every
    /// buffer of the technique shown) as `render --dump` writes them, into `dir`.
    pub fn dump(&mut self, dir: &Path, names: Option<&str>) -> Result<Vec<PathBuf>> {
        let settings = self.shown_settings();
        let own = render::dumps_for(&settings);
        let wanted: Vec<String> = match names {
            Some(list) => crate::cmd_render::parse_dumps(Some(list))?,
            None if !self.dumps.is_empty() => self.dumps.clone(),
            None => own.iter().map(|d| d.name.to_string()).collect(),
        };
        let wanted: Vec<String> = wanted.into_iter().filter(|n| named_in(&own, n).is_some()).collect();
        let out = OutputDir::create(dir)?;
        self.finish()?;
        let header = self.header(&settings);
        let images = self.shown_renderer().dumps(&wanted)?;
        let mut written = vec![];
        for (dump, image) in &images {
            let file = format!("{}.exr", dump.name);
            image_io::write_exr_with(&out.path(&file), image, &dump.header(&header))?;
            written.push(out.final_dir().join(file));
        }
        out.commit()?;
        self.log.push(format!("wrote {} buffer(s) into {}", written.len(), dir.display()));
        Ok(written)
    }
}

/// "rebuilt 2 pipelines (`a`, `b`)", or that none was.
fn rebuilt(pipelines: &[String]) -> String {
    match pipelines {
        [] => "no pipeline changed".into(),
        [one] => format!("rebuilt 1 pipeline (`{one}`)"),
        many => format!(
            "rebuilt {} pipelines ({})",
            many.len(),
            many.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
        ),
    }
}

/// The edited files, by name up to three, else how many.
fn files(files: &[String]) -> String {
    match files.len() {
        0..=3 => files.join(", "),
        n => format!("{n} files ({}, ...)", files[..2].join(", ")),
    }
}
