//! The viewer's egui panel: the technique's settings (rows generated from the settings table,
//! `settings.rs`), which technique is shown (A, B or split), the camera mode, the animation,
//! a per-pass GPU timing graph over the last frames, the save, dump and reload buttons, and the
//! last error. It changes nothing itself: it returns what the user asked for, which the viewer
//! applies (as it applies keys and `--script` lines).

use super::camera::Mode;
use super::keys::{self, Command};
use super::session::{FrameTimes, Session, Shown, HISTORY};
use super::settings::{self, Kind, Setting};
use caustics::scene::CausticSettings;
use egui::{Color32, Stroke};
use std::collections::HashMap;

/// What the user asked for through the panel.
#[derive(Debug, Clone, PartialEq)]
pub enum Request {
    /// A `[caustics]` key and its new value.
    Set(String, String),
    Command(Command),
    Show(Shown),
    CameraMode(Mode),
    /// Which paths animate: light, camera, objects.
    Animate(bool, bool, bool),
}

/// What the panel keeps between frames.
#[derive(Default)]
pub struct PanelState {
    /// Text fields being edited, by key (applied on Enter).
    edits: HashMap<String, String>,
    /// The settings rows and the settings they were made from (made again when those change,
    /// not every frame).
    rows: Option<(CausticSettings, Vec<Setting>)>,
    /// Frames per second over the last second (wall clock).
    pub fps: f64,
    pub device: String,
}

impl PanelState {
    /// The panel of the viewer on `device` (its name and driver).
    pub fn new(device: String) -> PanelState {
        PanelState { edits: HashMap::new(), rows: None, fps: 0.0, device }
    }
}

/// Colours of the graph's passes, by the pass's place in the legend.
const PALETTE: [Color32; 8] = [
    Color32::from_rgb(230, 159, 0),
    Color32::from_rgb(86, 180, 233),
    Color32::from_rgb(0, 158, 115),
    Color32::from_rgb(240, 228, 66),
    Color32::from_rgb(0, 114, 178),
    Color32::from_rgb(213, 94, 0),
    Color32::from_rgb(204, 121, 167),
    Color32::from_rgb(160, 160, 160),
];

/// Each pass's mean GPU ms over `history`, largest first.
pub fn pass_means(history: &std::collections::VecDeque<FrameTimes>) -> Vec<(String, f64)> {
    let mut sums: Vec<(String, f64, usize)> = vec![];
    for f in history {
        for (name, ms) in &f.passes {
            match sums.iter_mut().find(|(n, _, _)| n == name) {
                Some(s) => {
                    s.1 += ms;
                    s.2 += 1;
                }
                None => sums.push((name.clone(), *ms, 1)),
            }
        }
    }
    let mut means: Vec<(String, f64)> = sums.into_iter().map(|(n, s, c)| (n, s / c.max(1) as f64)).collect();
    means.sort_by(|a, b| b.1.total_cmp(&a.1));
    means
}

/// Draws the panel into `ui`; returns the requests.
pub fn show(ui: &mut egui::Ui, state: &mut PanelState, session: &Session, mode: Mode) -> Vec<Request> {
    let mut out = vec![];
    egui::Panel::left("causticlab panel").resizable(true).default_size(320.0).show(ui, |ui| {
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.heading("causticlab view");
            ui.label(&state.device);
            let gpu = session.history.back().map(|f| f.total_ms()).unwrap_or(0.0);
            ui.label(format!(
                "{:.1} fps · GPU {:.2} ms/frame · {}x{}",
                state.fps, gpu, session.scene.camera.width, session.scene.camera.height
            ));
            if let Some(e) = &session.error {
                ui.colored_label(Color32::from_rgb(255, 110, 110), e);
            }
            ui.separator();
            view_section(ui, session, &mut out);
            ui.separator();
            egui::CollapsingHeader::new("Technique settings")
                .default_open(true)
                .show(ui, |ui| settings_section(ui, state, session, &mut out));
            ui.collapsing("Camera, light, animation", |ui| scene_section(ui, session, mode, &mut out));
            egui::CollapsingHeader::new("GPU time per pass")
                .default_open(true)
                .show(ui, |ui| timing_section(ui, session, &mut out));
            ui.separator();
            ui.horizontal(|ui| {
                for (label, command) in
                    [("Save (S)", Command::Save), ("Dump (D)", Command::Dump), ("Reload (R)", Command::ReloadShaders)]
                {
                    if ui.button(label).clicked() {
                        out.push(Request::Command(command));
                    }
                }
            });
            for line in session.log.iter().rev().take(3) {
                ui.small(line);
            }
            ui.collapsing("Keys", |ui| {
                for (key, what) in keys::help() {
                    ui.label(format!("{key}: {what}"));
                }
            });
        });
    });
    out
}

fn view_section(ui: &mut egui::Ui, session: &Session, out: &mut Vec<Request>) {
    let a = session.scene.caustics.technique;
    match session.compare {
        Some(b) => {
            ui.horizontal(|ui| {
                for (label, shown) in
                    [(format!("A: {a}"), Shown::A), (format!("B: {b}"), Shown::B), ("A | B".into(), Shown::Split)]
                {
                    if ui.radio(session.shown == shown, label).clicked() && session.shown != shown {
                        out.push(Request::Show(shown));
                    }
                }
            });
        }
        None => {
            ui.label(format!("technique {a} (--compare T adds a second for A/B and split view)"));
        }
    }
}

fn settings_section(ui: &mut egui::Ui, state: &mut PanelState, session: &Session, out: &mut Vec<Request>) {
    let current = &session.scene.caustics;
    if state.rows.as_ref().is_none_or(|(made_from, _)| made_from != current) {
        state.rows = Some((current.clone(), settings::rows(current)));
    }
    let Some((_, rows)) = &state.rows else { return };
    for row in rows {
        ui.horizontal(|ui| {
            let label = ui.label(&row.key);
            if !row.help.is_empty() {
                label.on_hover_text(&row.help);
            }
            match &row.kind {
                Kind::Bool => {
                    let mut on = row.shown() == "true";
                    if ui.checkbox(&mut on, "").changed() {
                        out.push(Request::Set(row.key.clone(), on.to_string()));
                    }
                }
                Kind::Choice(choices) => {
                    let current = row.shown();
                    let selected =
                        if current.is_empty() { "(the technique's own)".to_string() } else { current.clone() };
                    egui::ComboBox::from_id_salt(&row.key).selected_text(selected).show_ui(ui, |ui| {
                        for c in choices {
                            if ui.selectable_label(*c == current, c).clicked() && *c != current {
                                out.push(Request::Set(row.key.clone(), c.clone()));
                            }
                        }
                    });
                }
                Kind::Text => {
                    let text = state.edits.entry(row.key.clone()).or_insert_with(|| row.shown());
                    let response = ui.text_edit_singleline(text);
                    if response.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                        out.push(Request::Set(row.key.clone(), text.clone()));
                    }
                    if !response.has_focus() && !response.lost_focus() {
                        // Not being edited: follow the value in effect.
                        *text = row.shown();
                    }
                }
            }
        });
    }
}

fn scene_section(ui: &mut egui::Ui, session: &Session, mode: Mode, out: &mut Vec<Request>) {
    ui.horizontal(|ui| {
        ui.label("camera");
        for m in [Mode::Orbit, Mode::Fly] {
            if ui.radio(mode == m, m.name()).clicked() && mode != m {
                out.push(Request::CameraMode(m));
            }
        }
    });
    let c = &session.scene.camera;
    ui.small(format!(
        "eye ({:.2}, {:.2}, {:.2}) target ({:.2}, {:.2}, {:.2})",
        c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z
    ));
    if let Some(l) = session.scene.lights.first() {
        ui.small(format!(
            "light ({:.2}, {:.2}, {:.2}); Ctrl + drag moves it",
            l.position.x, l.position.y, l.position.z
        ));
    }
    let anim = &session.animation;
    let (mut light, mut camera, mut object) = (anim.light, anim.camera, anim.object);
    ui.horizontal(|ui| {
        ui.label("animate");
        let a = ui.checkbox(&mut light, "light").changed();
        let b = ui.checkbox(&mut camera, "camera").changed();
        let c = ui.checkbox(&mut object, "objects").changed();
        if a || b || c {
            out.push(Request::Animate(light, camera, object));
        }
    });
    ui.horizontal(|ui| {
        let label = if session.playing { "Pause (Space)" } else { "Play (Space)" };
        if ui.button(label).clicked() {
            out.push(Request::Command(Command::PlayPause));
        }
        ui.label(format!("frame {} of {}", session.animation_frame, anim.period_frames));
    });
}

fn timing_section(ui: &mut egui::Ui, session: &Session, out: &mut Vec<Request>) {
    let mut every_pass = session.pass_timestamps();
    let toggle = ui
        .checkbox(&mut every_pass, "time every pass (T)")
        .on_hover_text("else whole frames; on a software device each timestamp flushes the rasterizer");
    if toggle.changed() {
        out.push(Request::Command(Command::TogglePassTiming));
    }
    let means = pass_means(&session.history);
    let colour = |name: &str| {
        let i = means.iter().position(|(n, _)| n == name).unwrap_or(PALETTE.len() - 1);
        PALETTE[i.min(PALETTE.len() - 1)]
    };
    let height = 120.0;
    let (rect, _) = ui.allocate_exact_size(egui::vec2(ui.available_width(), height), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, Color32::from_gray(24));
    // The scale: the 95th percentile of the frames' totals (a warm-up or rebuild spike is cut).
    let mut totals: Vec<f64> = session.history.iter().map(|f| f.total_ms()).collect();
    totals.sort_by(f64::total_cmp);
    let most = totals.get(totals.len() * 95 / 100).copied().unwrap_or(0.0).max(1e-3);
    let bar = rect.width() / HISTORY as f32;
    let start = HISTORY.saturating_sub(session.history.len());
    for (i, f) in session.history.iter().enumerate() {
        let x = rect.left() + (start + i) as f32 * bar;
        let mut y = rect.bottom();
        // Largest passes at the bottom, in the legend's order.
        for (name, _) in &means {
            let Some((_, ms)) = f.passes.iter().find(|(n, _)| n == name) else { continue };
            let h = ((*ms / most) as f32 * (height - 4.0)).min((y - rect.top()).max(0.0));
            painter.line_segment([egui::pos2(x, y), egui::pos2(x, y - h)], Stroke::new(bar.max(1.0), colour(name)));
            y -= h;
        }
    }
    painter.text(
        rect.left_top() + egui::vec2(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        format!("{most:.2} ms"),
        egui::FontId::monospace(11.0),
        Color32::LIGHT_GRAY,
    );
    for (name, ms) in means.iter().take(12) {
        ui.horizontal(|ui| {
            ui.colored_label(colour(name), "■");
            ui.monospace(format!("{ms:>8.3} ms  {name}"));
        });
    }
}

#[cfg(test)]
mod tests {
    //! The panel's widgets clicked as a person clicks them: pointer events at the place the
    //! widget's text was drawn, through egui, on a session over lavapipe (or the default device).
    use super::*;
    use caustics::techniques::Technique;
    use egui::{Event, Pos2, Rect};

    /// Every text drawn in `shapes` (nested ones too) and where, on the screen.
    fn texts(shapes: &[egui::epaint::ClippedShape]) -> Vec<(String, Rect)> {
        fn walk(s: &egui::Shape, out: &mut Vec<(String, Rect)>) {
            match s {
                egui::Shape::Text(t) => {
                    out.push((t.galley.text().to_string(), t.galley.rect.translate(t.pos.to_vec2())))
                }
                egui::Shape::Vec(v) => v.iter().for_each(|s| walk(s, out)),
                _ => {}
            }
        }
        let mut out = vec![];
        for c in shapes {
            walk(&c.shape, &mut out);
        }
        out
    }

    /// One panel frame with `events`: the requests and the texts drawn.
    fn frame(
        ctx: &egui::Context,
        state: &mut PanelState,
        s: &Session,
        events: Vec<Event>,
    ) -> (Vec<Request>, Vec<(String, Rect)>) {
        let input = egui::RawInput {
            screen_rect: Some(Rect::from_min_size(Pos2::ZERO, egui::vec2(900.0, 1400.0))),
            events,
            ..Default::default()
        };
        let mut requests = vec![];
        let mut out = ctx.run_ui(input, |ui| requests = show(ui, state, s, Mode::Orbit));
        // No renderer here to upload the font textures to.
        out.textures_delta.clear();
        (requests, texts(&out.shapes))
    }

    /// Moves the pointer to `at`, presses and releases the primary button, a frame each; the
    /// requests of the release frame and the texts drawn after it.
    fn click(
        ctx: &egui::Context,
        state: &mut PanelState,
        s: &Session,
        at: Pos2,
    ) -> (Vec<Request>, Vec<(String, Rect)>) {
        let button = |pressed| Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Default::default(),
        };
        frame(ctx, state, s, vec![Event::PointerMoved(at)]);
        frame(ctx, state, s, vec![button(true)]);
        let (requests, _) = frame(ctx, state, s, vec![button(false)]);
        let (_, drawn) = frame(ctx, state, s, vec![]);
        (requests, drawn)
    }

    fn find<'t>(drawn: &'t [(String, Rect)], text: &str) -> Vec<&'t Rect> {
        drawn.iter().filter(|(t, _)| t == text).map(|(_, r)| r).collect()
    }

    #[test]
    fn clicking_the_technique_list_and_the_timing_box_reaches_the_session() {
        let opts = vkcore::ContextOptions::for_tests(vec![]);
        let ctx = vkcore::Context::new(&opts).expect("a Vulkan device (scripts/setup.sh)");
        let shaders = vkcore::ShaderCompiler::new(&caustics::render::shader_root()).expect("shaderc");
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mut scene = caustics::scene::Scene::load(&root.join("scenes/sphere_on_plane.toml")).expect("the scene");
        (scene.camera.width, scene.camera.height) = (48, 48);
        scene.caustics.technique = Technique::Shah;
        let out = std::env::temp_dir().join(format!("causticlab-panel-{}", std::process::id()));
        let session = Session::new(&ctx, &shaders, scene, None, vec![], out, false).expect("a session");
        // The viewer's loop state without its window: its `request` is what the loop gives the
        // panel's requests to.
        let mut viewer = super::super::Viewer {
            session,
            mode: Mode::Orbit,
            show_panel: true,
            panel: PanelState::new("test".into()),
            watcher: None,
            exit: false,
            frame_ms: vec![],
        };
        let egui_ctx = egui::Context::default();
        // Two frames: the first lays out, the second draws at the sizes it found.
        frame(&egui_ctx, &mut viewer.panel, &viewer.session, vec![]);
        let (_, drawn) = frame(&egui_ctx, &mut viewer.panel, &viewer.session, vec![]);

        // The technique row: its list shows `shah` on the label's line. Open it, pick `hcm`.
        let label = *find(&drawn, "technique").first().expect("the technique row's label");
        let current = find(&drawn, "shah")
            .into_iter()
            .find(|r| (r.center().y - label.center().y).abs() < label.height())
            .expect("the technique list beside its label");
        let (requests, opened) = click(&egui_ctx, &mut viewer.panel, &viewer.session, current.center());
        assert!(requests.is_empty(), "opening the list asks for nothing: {requests:?}");
        let before = find(&drawn, "hcm").len();
        let choices = find(&opened, "hcm");
        assert!(choices.len() > before, "the opened list shows `hcm`");
        let hcm = *choices.last().expect("hcm");
        let (requests, _) = click(&egui_ctx, &mut viewer.panel, &viewer.session, hcm.center());
        assert_eq!(requests, vec![Request::Set("technique".into(), "hcm".into())]);
        requests.into_iter().for_each(|r| viewer.request(r));
        assert_eq!(viewer.session.error, None, "the panel's setting was refused");
        assert_eq!(viewer.session.shown_settings().technique, Technique::Hcm, "the running renderer is hcm's");

        // The timing box: unticked (whole frames timed here); a click asks to time every pass.
        assert!(!viewer.session.pass_timestamps(), "whole frames timed before the click");
        let (_, drawn) = frame(&egui_ctx, &mut viewer.panel, &viewer.session, vec![]);
        let tick = *find(&drawn, "time every pass (T)").first().expect("the timing box");
        let (requests, _) = click(&egui_ctx, &mut viewer.panel, &viewer.session, tick.center());
        assert_eq!(requests, vec![Request::Command(Command::TogglePassTiming)]);
        requests.into_iter().for_each(|r| viewer.request(r));
        assert_eq!(viewer.session.error, None, "timing every pass was refused");
        assert!(viewer.session.pass_timestamps(), "the click did not turn per-pass timing on");
        viewer.session.finish().expect("the session's frames");
        drop(viewer);
        let log = ctx.validation_log();
        assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    }
}
