//! `causticlab view`: a window on a scene, rendering throughput frames of the chosen technique
//! continuously (vsync off unless `--vsync`), with an egui panel to change every setting of the
//! technique, A/B and split view against a second technique (`--compare`), an orbit or fly
//! camera, a light to drag, the animation paths to play, a per-pass GPU timing graph, keys to
//! save the frame and dump its buffers, and shader hot reload. `--script` and `--exit-after`
//! drive it without a person (the tests run it under Xvfb on lavapipe).

mod camera;
mod keys;
mod panel;
mod reload;
mod script;
mod session;
mod settings;
mod window;

use crate::cli::{GlobalOpts, ViewArgs};
use anyhow::{bail, Context as _, Result};
use caustics::render;
use caustics::scene::Scene;
use keys::Command;
use session::{Session, Shown};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use vkcore::{Context, Overlay, PresentOptions, Presenter, ShaderCompiler, ValidationLog};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::EventLoop;
use winit::keyboard::{Key, NamedKey};
use winit::platform::pump_events::{EventLoopExtPumpEvents, PumpStatus};
use winit::raw_window_handle::{HasDisplayHandle, HasWindowHandle};

/// `--size`: `N` or `WxH`.
fn parse_size(s: &str) -> Result<(u32, u32)> {
    let bad = || caustics::input_error!("--size: `{s}`: expected N or WxH, each 8..=8192");
    let (w, h) = match s.split_once(['x', 'X']) {
        Some((w, h)) => (w.trim().parse::<u32>().map_err(|_| bad())?, h.trim().parse::<u32>().map_err(|_| bad())?),
        None => {
            let n = s.trim().parse::<u32>().map_err(|_| bad())?;
            (n, n)
        }
    };
    if !(8..=8192).contains(&w) || !(8..=8192).contains(&h) {
        return Err(bad().into());
    }
    Ok((w, h))
}

pub fn run(g: &GlobalOpts, args: &ViewArgs, validation: &mut Option<Arc<ValidationLog>>) -> Result<()> {
    let opts = crate::context_options(g)?;
    // Every input is checked before a window opens.
    let mut scene = Scene::load(&args.scene)?;
    crate::cli::apply_caustic_flags(&args.caustics, &mut scene.caustics, &args.scene)?;
    if let Some(s) = &args.size {
        (scene.camera.width, scene.camera.height) = parse_size(s)?;
    }
    if let Some(t) = args.compare {
        settings::with_technique(&scene.caustics, t)
            .validate_combination(&format!("--compare {t}"), "caustics.")
            .context("--compare")?;
    }
    let dumps = crate::cmd_render::parse_dumps(args.dump.as_deref())?;
    let steps = match &args.script {
        Some(p) => script::load(p)?,
        None => vec![],
    };
    caustics::image_io::check_output_dir(&args.out).context("--out")?;

    let mut event_loop = EventLoop::new().map_err(|e| {
        anyhow::anyhow!(
            "cannot open a window ({e}): `causticlab view` needs a display (X11, or Wayland through XWayland); \
             without one, run it under Xvfb: xvfb-run -a causticlab view ..."
        )
    })?;
    let size = (scene.camera.width, scene.camera.height);
    let mut handler = window::Handler::new(format!("causticlab view · {}", args.scene.display()), size);
    let deadline = Instant::now() + Duration::from_secs(10);
    while handler.window.is_none() && handler.error.is_none() {
        if let PumpStatus::Exit(code) = event_loop.pump_app_events(Some(Duration::from_millis(10)), &mut handler) {
            bail!("the window's event loop ended (code {code}) before the window opened");
        }
        if Instant::now() > deadline {
            bail!("the window did not open within 10 s");
        }
    }
    if let Some(e) = handler.error.take() {
        bail!("cannot create the window: {e}");
    }
    let window = handler.window.clone().context("the window")?;
    let display = window.display_handle().map_err(|e| anyhow::anyhow!("the window's display: {e}"))?.as_raw();
    let handle = window.window_handle().map_err(|e| anyhow::anyhow!("the window's handle: {e}"))?.as_raw();
    let (ctx, surface) =
        Context::with_window(&opts, display, handle).context("opening the Vulkan device for the window")?;
    *validation = Some(ctx.validation_log());
    render::check_device(&ctx, &scene)?;
    let shaders = ShaderCompiler::new(&render::shader_root()).context("creating the shader compiler")?;
    // Render at the size the window got (a window manager may give another).
    let got = window.inner_size();
    (scene.camera.width, scene.camera.height) = (got.width.max(1), got.height.max(1));
    let mut presenter = Presenter::new(&ctx, surface, (got.width, got.height), PresentOptions { vsync: args.vsync })?;
    let every_pass = args.pass_timing.every_pass(ctx.info().is_software);
    let session = Session::new(&ctx, &shaders, scene, args.compare, dumps, args.out.clone(), every_pass)?;
    let mut viewer = Viewer {
        session,
        mode: camera::Mode::Orbit,
        show_panel: true,
        panel: panel::PanelState::new(format!("{} ({})", ctx.info().name, ctx.info().driver_info)),
        watcher: (!args.no_hot_reload).then(|| reload::Watcher::new(shaders.root())),
        exit: false,
        frame_ms: vec![],
    };
    let result = viewer.run(&mut event_loop, &mut handler, &window, &mut presenter, steps, args.exit_after);
    // Whatever happened, nothing may be in flight when the renderers and the presenter go.
    let finished = viewer.session.finish();
    let idle = ctx.wait_idle();
    result?;
    finished?;
    idle?;
    viewer.summary(&args.scene);
    Ok(())
}

/// The viewer's loop state besides the session.
struct Viewer<'c> {
    session: Session<'c>,
    mode: camera::Mode,
    show_panel: bool,
    panel: panel::PanelState,
    watcher: Option<reload::Watcher>,
    exit: bool,
    /// Wall-clock milliseconds of every frame shown.
    frame_ms: Vec<f64>,
}

/// What the mouse and the held keys are doing.
#[derive(Default)]
struct Input {
    left: bool,
    ctrl: bool,
    cursor: Option<(f64, f64)>,
    /// Arrow keys and Page Up/Down held (fly mode): right, up, forward.
    fly: [f32; 3],
}

impl<'c> Viewer<'c> {
    fn run(
        &mut self,
        event_loop: &mut EventLoop<()>,
        handler: &mut window::Handler,
        window: &winit::window::Window,
        presenter: &mut Presenter,
        steps: Vec<script::Step>,
        exit_after: Option<u32>,
    ) -> Result<()> {
        let egui_ctx = egui::Context::default();
        let mut egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            None,
        );
        let mut input = Input::default();
        let mut steps = steps.into_iter().peekable();
        let mut shown: u32 = 0;
        let mut second = (Instant::now(), 0u32);
        let mut last = Instant::now();
        loop {
            if let PumpStatus::Exit(_) = event_loop.pump_app_events(Some(Duration::ZERO), handler) {
                break;
            }
            let mut commands = vec![];
            let mut resized = None;
            for event in handler.events.drain(..) {
                let consumed = egui_state.on_window_event(window, &event).consumed && self.show_panel;
                match &event {
                    WindowEvent::CloseRequested => self.exit = true,
                    WindowEvent::Resized(s) => resized = Some((s.width, s.height)),
                    WindowEvent::ModifiersChanged(m) => input.ctrl = m.state().control_key(),
                    WindowEvent::KeyboardInput { event: k, .. } => {
                        let down = k.state == ElementState::Pressed;
                        let axis = match &k.logical_key {
                            Key::Named(NamedKey::ArrowRight) => Some((0, 1.0)),
                            Key::Named(NamedKey::ArrowLeft) => Some((0, -1.0)),
                            Key::Named(NamedKey::PageUp) => Some((1, 1.0)),
                            Key::Named(NamedKey::PageDown) => Some((1, -1.0)),
                            Key::Named(NamedKey::ArrowUp) => Some((2, 1.0)),
                            Key::Named(NamedKey::ArrowDown) => Some((2, -1.0)),
                            _ => None,
                        };
                        if let Some((i, sign)) = axis {
                            input.fly[i] = if down && !consumed { sign } else { 0.0 };
                        } else if down && !k.repeat && !consumed {
                            if let Some(c) = keys::name_of(&k.logical_key).and_then(|n| keys::command(&n)) {
                                commands.push(c);
                            }
                        }
                    }
                    WindowEvent::MouseInput { state, button: MouseButton::Left, .. } => {
                        input.left = *state == ElementState::Pressed && !consumed;
                    }
                    WindowEvent::CursorMoved { position, .. } => {
                        let (x, y) = (position.x, position.y);
                        if let (true, Some((px, py))) = (input.left, input.cursor) {
                            let (dx, dy) = ((x - px) as f32, (y - py) as f32);
                            let s = &mut self.session;
                            if input.ctrl {
                                let pivot = caustics::techniques::uniforms::specular_bounds(&s.scene)
                                    .map(|(c, _)| c)
                                    .unwrap_or(s.scene.camera.target);
                                camera::drag_light(&mut s.scene, pivot, dx, dy);
                            } else {
                                camera::drag(&mut s.scene.camera, self.mode, dx, dy);
                            }
                            s.moved();
                        }
                        input.cursor = Some((x, y));
                    }
                    WindowEvent::MouseWheel { delta, .. } if !consumed => {
                        let steps = match delta {
                            MouseScrollDelta::LineDelta(_, y) => *y,
                            MouseScrollDelta::PixelDelta(p) => (p.y / 50.0) as f32,
                        };
                        camera::dolly(&mut self.session.scene.camera, steps);
                        self.session.moved();
                    }
                    _ => {}
                }
            }
            if self.mode == camera::Mode::Fly && input.fly != [0.0; 3] {
                camera::fly(&mut self.session.scene.camera, input.fly[0] * 0.2, input.fly[1] * 0.2, input.fly[2] * 0.2);
                self.session.moved();
            }
            while let Some(step) = steps.next_if(|s| s.frame <= shown) {
                self.script_step(&step, window, &mut commands, &mut resized)
                    .with_context(|| format!("--script {}", step.origin))?;
            }
            if exit_after.is_some_and(|n| shown >= n) {
                self.exit = true;
            }
            for c in commands {
                self.command(c);
            }
            if self.exit {
                break;
            }
            let changed = self.watcher.as_mut().map(|w| w.changed()).unwrap_or_default();
            if !changed.is_empty() {
                self.reload(&changed);
            }
            if let Some(size) = resized {
                presenter.resize(size);
                let _ = self.session.resize(size);
            }
            let raw = egui_state.take_egui_input(window);
            let mut requests = vec![];
            let mut full = egui_ctx.run_ui(raw, |ui| {
                if self.show_panel {
                    requests = panel::show(ui, &mut self.panel, &self.session, self.mode);
                }
            });
            egui_state.handle_platform_output(window, full.platform_output);
            let primitives = egui_ctx.tessellate(full.shapes, full.pixels_per_point);
            for r in requests {
                self.request(r);
            }
            let mut textures = std::mem::take(&mut full.textures_delta);
            let shown_frame = self.session.frame().and_then(|_| {
                let overlay =
                    Overlay { textures: &textures, primitives: &primitives, pixels_per_point: full.pixels_per_point };
                Ok(presenter.present(&self.session.display.target.image, &overlay)?)
            });
            // The presenter keeps what it has not uploaded yet: these deltas are handled.
            textures.clear();
            shown_frame?;
            shown += 1;
            let now = Instant::now();
            self.frame_ms.push((now - last).as_secs_f64() * 1e3);
            last = now;
            second.1 += 1;
            if second.0.elapsed() >= Duration::from_secs(1) {
                self.panel.fps = second.1 as f64 / second.0.elapsed().as_secs_f64();
                second = (Instant::now(), 0);
            }
        }
        Ok(())
    }

    /// One `--script` line; its errors end the run (a script is a test).
    fn script_step(
        &mut self,
        step: &script::Step,
        window: &winit::window::Window,
        commands: &mut Vec<Command>,
        resized: &mut Option<(u32, u32)>,
    ) -> Result<()> {
        match &step.action {
            script::Action::Key(name) => commands.extend(keys::command(name)),
            script::Action::Set(key, value) => self.session.set(key, value)?,
            script::Action::Screenshot(dir) => {
                for f in self.session.screenshot(dir)? {
                    println!("wrote {}", f.display());
                }
            }
            script::Action::Dump(dir, names) => {
                for f in self.session.dump(dir, names.as_deref())? {
                    println!("wrote {}", f.display());
                }
            }
            script::Action::Resize(w, h) => {
                // Some platforms resize at once (and send no event), others later.
                if let Some(s) = window.request_inner_size(winit::dpi::PhysicalSize::new(*w, *h)) {
                    *resized = Some((s.width, s.height));
                }
            }
            script::Action::Reload => self.reload_now(),
            script::Action::Await(path) => {
                let deadline = Instant::now() + Duration::from_secs(60);
                while !path.exists() {
                    if Instant::now() > deadline {
                        bail!("{} did not appear within a minute", path.display());
                    }
                    std::thread::sleep(Duration::from_millis(20));
                }
            }
            script::Action::Exit => self.exit = true,
        }
        Ok(())
    }

    /// Rebuilds what changed shaders feed (`files`); a failure is shown in the panel and on
    /// stderr, and the last good pipelines keep running.
    fn reload(&mut self, files: &[String]) {
        match self.session.reload(files) {
            Ok(Some(line)) => eprintln!("view: {line}"),
            Ok(None) => {}
            Err(e) => eprintln!("view: the edited shaders do not build; the last good pipelines keep running:\n{e:#}"),
        }
    }

    /// Looks for edited shaders now.
    fn reload_now(&mut self) {
        let changed = self.watcher.as_mut().map(|w| w.changed_now()).unwrap_or_default();
        if !changed.is_empty() {
            self.reload(&changed);
        }
    }

    fn command(&mut self, c: Command) {
        let s = &mut self.session;
        match c {
            Command::Exit => self.exit = true,
            Command::Save => {
                let out = s.out.clone();
                let r = s.screenshot(&out);
                s.error = r.err().map(|e| format!("save: {e:#}"));
            }
            Command::Dump => {
                let dir: PathBuf = s.out.join("dumps");
                let r = s.dump(&dir, None);
                s.error = r.err().map(|e| format!("dump: {e:#}"));
            }
            Command::ToggleAb | Command::ToggleSplit if s.compare.is_none() => {
                s.error = Some("A/B and split view need a second technique: start with --compare TECHNIQUE".into());
            }
            Command::ToggleAb => s.shown = if s.shown == Shown::A { Shown::B } else { Shown::A },
            Command::ToggleSplit => s.shown = if s.shown == Shown::Split { Shown::A } else { Shown::Split },
            Command::PlayPause => s.playing = !s.playing,
            Command::ReloadShaders => {
                let all = reload::all_files(&render::shader_root());
                self.reload(&all);
            }
            Command::CameraMode => {
                self.mode = match self.mode {
                    camera::Mode::Orbit => camera::Mode::Fly,
                    camera::Mode::Fly => camera::Mode::Orbit,
                }
            }
            Command::TogglePanel => self.show_panel = !self.show_panel,
            Command::TogglePassTiming => {
                let on = !s.pass_timestamps();
                // An error is kept for the panel by the session.
                let _ = s.set_pass_timestamps(on);
            }
        }
    }

    fn request(&mut self, r: panel::Request) {
        match r {
            panel::Request::Set(key, value) => {
                // A refused value stays in the panel as the error.
                let _ = self.session.set(&key, &value);
            }
            panel::Request::Command(c) => self.command(c),
            panel::Request::Show(shown) => self.session.shown = shown,
            panel::Request::CameraMode(m) => self.mode = m,
            panel::Request::Animate(light, camera, object) => {
                let a = &mut self.session.animation;
                (a.light, a.camera, a.object) = (light, camera, object);
                self.session.moved();
            }
        }
    }

    /// Frames shown and their wall-clock time after the first ten (warm-up), and the GPU time
    /// per frame of the last frames (sum of the passes).
    fn summary(&self, scene: &std::path::Path) {
        let warm: Vec<f64> = self.frame_ms.iter().skip(10).copied().collect();
        let wall = match warm.len() {
            0 => "wall not measured (10 frames or fewer: all warm-up)".to_string(),
            n => format!("wall {:.3} ms a frame (mean after the first 10)", warm.iter().sum::<f64>() / n as f64),
        };
        let mut gpu: Vec<f64> = self.session.history.iter().map(|f| f.total_ms()).collect();
        gpu.sort_by(f64::total_cmp);
        let median = gpu.get(gpu.len() / 2).copied().unwrap_or(f64::NAN);
        let timed = match self.session.history.back() {
            Some(f) if self.session.pass_timestamps() => format!("{} passes timed, summed", f.passes.len()),
            _ => "whole frames timed".to_string(),
        };
        println!(
            "view: {} on {}x{} on {}, technique `{}`: {} frames; {wall}; \
             GPU {median:.3} ms a frame (median of the last {}, {timed})",
            scene.display(),
            self.session.scene.camera.width,
            self.session.scene.camera.height,
            self.panel.device,
            self.session.shown_settings().technique,
            self.frame_ms.len(),
            gpu.len(),
        );
    }
}
