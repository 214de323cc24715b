//! `causticlab view` driven by `--script` under Xvfb on lavapipe, with Khronos validation
//! (`--validate`: any message is exit code 3): its screenshots against the headless `render` of
//! the same settings, a setting changed as the panel changes it, a resize, the dump key, the A/B
//! toggle and split view, a clean Esc exit, and a broken shader edit that leaves the last good
//! pipeline running until it is fixed. `scripts/setup.sh` installs Xvfb (`xvfb-run`).

mod common;

use common::{causticlab, scratch, workspace, Run};
use std::path::{Path, PathBuf};
use std::process::Command;

/// `sphere_on_plane` at 96 × 96 pixels (small enough for lavapipe), beside the original.
fn small_scene(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(workspace().join("scenes/sphere_on_plane.toml")).expect("the scene");
    let edited = text.replace("resolution = [512, 512]", "resolution = [96, 96]");
    assert_ne!(edited, text, "the scene's camera resolution line moved");
    let path = dir.join("sphere_small.toml");
    std::fs::write(&path, edited).expect("writing the scene");
    path
}

/// One X server at a time: `xvfb-run -a` picks a free display number, and two started at once
/// can pick the same one.
static XVFB: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn xvfb() -> std::sync::MutexGuard<'static, ()> {
    XVFB.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// `causticlab --validate view ARGS` in a fresh X server, with `env` set (not yet started).
fn view_command(args: &[&str], env: &[(&str, &Path)]) -> Command {
    let mut cmd = Command::new("xvfb-run");
    cmd.args(["-a", "-s", "-screen 0 640x480x24", env!("CARGO_BIN_EXE_causticlab"), "--validate", "view"])
        .args(args)
        .current_dir(workspace())
        .env_remove("VK_LOADER_DEBUG");
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd
}

fn run_of(out: std::process::Output) -> Run {
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// Runs `causticlab --validate view ARGS` in a fresh X server.
fn view(args: &[&str], env: &[(&str, &Path)]) -> Run {
    let _one = xvfb();
    run_of(view_command(args, env).output().expect("running xvfb-run (scripts/setup.sh installs the xvfb package)"))
}

fn clean(run: &Run) {
    assert_eq!(run.code, Some(0), "{}", run.describe());
    assert!(run.stderr.contains("validation: no warnings or errors reported"), "{}", run.describe());
}

fn script(dir: &Path, lines: &str) -> String {
    let path = dir.join("script.txt");
    std::fs::write(&path, lines).expect("writing the script");
    path.display().to_string()
}

/// Width, height and RGB bytes of a PNG.
fn png(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    ));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgb, "{}", path.display());
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// The largest difference of any channel of two PNGs of the same size, in 8-bit codes, over the
/// columns `columns` (all: `0..u32::MAX`).
fn png_diff(a: &Path, b: &Path, columns: std::ops::Range<u32>) -> u8 {
    let (wa, ha, pa) = png(a);
    let (wb, hb, pb) = png(b);
    assert_eq!((wa, ha), (wb, hb), "{} and {}", a.display(), b.display());
    let mut most = 0u8;
    for (i, (x, y)) in pa.chunks_exact(3).zip(pb.chunks_exact(3)).enumerate() {
        if columns.contains(&(i as u32 % wa)) {
            for c in 0..3 {
                most = most.max(x[c].abs_diff(y[c]));
            }
        }
    }
    most
}

fn headless(scene: &Path, out: &Path, flags: &[&str]) {
    let s = scene.display().to_string();
    let o = out.display().to_string();
    let mut args = vec!["render", "--scene", &s, "--out", &o, "--validate"];
    args.extend(flags);
    let run = causticlab(&args);
    assert_eq!(run.code, Some(0), "{}", run.describe());
}

#[test]
fn screenshots_equal_the_headless_render_of_each_technique() {
    let dir = scratch("view-techniques");
    let scene = small_scene(&dir);
    let d = dir.display();
    let s = script(
        &dir,
        &format!(
            "10 screenshot {d}/shah\n10 set technique hcm\n20 screenshot {d}/hcm\n20 set technique adaptive\n\
             30 screenshot {d}/adaptive\n30 exit\n"
        ),
    );
    let run = view(&["--scene", &scene.display().to_string(), "--technique", "shah", "--script", &s], &[]);
    clean(&run);
    for t in ["shah", "hcm", "adaptive"] {
        let reference = dir.join(format!("render-{t}"));
        headless(&scene, &reference, &["--technique", t]);
        let shot = dir.join(t);
        let diff = png_diff(&shot.join("final.png"), &reference.join("final.png"), 0..u32::MAX);
        assert!(diff <= 1, "{t}: the viewer's final.png differs from render's by {diff}/255");
        // What the window shows (the GPU's tone map) is the same picture.
        let diff = png_diff(&shot.join("display.png"), &reference.join("final.png"), 0..u32::MAX);
        assert!(diff <= 1, "{t}: the window's image differs from render's final.png by {diff}/255");
    }
    // The techniques differ from each other (the switch happened).
    assert!(png_diff(&dir.join("shah/final.png"), &dir.join("hcm/final.png"), 0..u32::MAX) > 8);
    assert!(run.stdout.contains("30 frames"), "{}", run.describe());
}

#[test]
fn a_setting_set_as_the_panel_sets_it_reaches_the_renderer() {
    let dir = scratch("view-setting");
    let scene = small_scene(&dir);
    let d = dir.display();
    let s = script(&dir, &format!("3 set photons 128\n6 dump {d}/dump photon_buffer\n6 screenshot {d}/shot\n6 exit\n"));
    let run = view(&["--scene", &scene.display().to_string(), "--technique", "shah", "--script", &s], &[]);
    clean(&run);
    let buffer = caustics::image_io::read_exr(&dir.join("dump/photon_buffer.exr")).expect("the dump");
    assert_eq!((buffer.width, buffer.height), (128, 128), "the photon buffer follows `photons`");
    let reference = dir.join("render");
    headless(&scene, &reference, &["--technique", "shah", "--photons", "128"]);
    assert!(png_diff(&dir.join("shot/final.png"), &reference.join("final.png"), 0..u32::MAX) <= 1);
    // A refused value names the key and ends a script with an input error.
    let bad = script(&dir, "2 set photons 3\n4 exit\n");
    let run = view(&["--scene", &scene.display().to_string(), "--technique", "shah", "--script", &bad], &[]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains("script.txt:1") && run.stderr.contains("photons"), "{}", run.describe());
}

#[test]
fn a_resize_renders_at_the_new_size() {
    let dir = scratch("view-resize");
    let scene = small_scene(&dir);
    let d = dir.display();
    let s = script(&dir, &format!("3 resize 120 72\n12 screenshot {d}/shot\n12 exit\n"));
    let run = view(&["--scene", &scene.display().to_string(), "--technique", "shah", "--script", &s], &[]);
    clean(&run);
    for f in ["final.png", "display.png"] {
        let (w, h, _) = png(&dir.join("shot").join(f));
        assert_eq!((w, h), (120, 72), "{f}");
    }
    assert!(run.stdout.contains("on 120x72"), "{}", run.describe());
}

#[test]
fn the_dump_key_writes_the_declared_buffers() {
    let dir = scratch("view-dump");
    let scene = small_scene(&dir);
    let out = dir.join("out");
    let s = script(&dir, "4 key d\n6 exit\n");
    let args = [
        "--scene",
        &scene.display().to_string(),
        "--technique",
        "shah",
        "--dump",
        "receiver,shadow_map,photon_buffer",
        "--out",
        &out.display().to_string(),
        "--script",
        &s,
    ];
    let run = view(&args, &[]);
    clean(&run);
    let mut written: Vec<String> = std::fs::read_dir(out.join("dumps"))
        .expect("the dumps folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    assert_eq!(written, ["photon_buffer.exr", "receiver.exr", "shadow_map.exr"]);
    // The same buffers as render's.
    let reference = dir.join("render");
    headless(&scene, &reference, &["--technique", "shah", "--dump", "receiver"]);
    let diff = causticlab(&[
        "diff",
        &out.join("dumps/receiver.exr").display().to_string(),
        &reference.join("receiver.exr").display().to_string(),
        "--tolerance",
        "0.001",
    ]);
    assert_eq!(diff.code, Some(0), "{}", diff.describe());
}

#[test]
fn the_ab_toggle_and_split_view_show_both_techniques() {
    let dir = scratch("view-ab");
    let scene = small_scene(&dir);
    let d = dir.display();
    let s = script(
        &dir,
        &format!("5 screenshot {d}/a\n5 key tab\n10 screenshot {d}/b\n10 key v\n15 screenshot {d}/split\n15 exit\n"),
    );
    let args = ["--scene", &scene.display().to_string(), "--technique", "shah", "--compare", "hcm", "--script", &s];
    let run = view(&args, &[]);
    clean(&run);
    for (shot, t) in [("a", "shah"), ("b", "hcm")] {
        let reference = dir.join(format!("render-{t}"));
        headless(&scene, &reference, &["--technique", t]);
        assert!(png_diff(&dir.join(shot).join("final.png"), &reference.join("final.png"), 0..u32::MAX) <= 1, "{t}");
    }
    assert!(png_diff(&dir.join("a/final.png"), &dir.join("b/final.png"), 0..u32::MAX) > 8, "A and B differ");
    // Split: A left of the divider (column 48 of 96), B right of it.
    let split = dir.join("split/display.png");
    assert!(png_diff(&split, &dir.join("a/display.png"), 0..48) <= 1);
    assert!(png_diff(&split, &dir.join("b/display.png"), 49..96) <= 1);
}

#[test]
fn escape_exits_cleanly() {
    let dir = scratch("view-escape");
    let scene = small_scene(&dir);
    let s = script(&dir, "5 key escape\n500 exit\n");
    let run = view(&["--scene", &scene.display().to_string(), "--technique", "shah", "--script", &s], &[]);
    clean(&run);
    assert!(run.stdout.contains(": 5 frames"), "{}", run.describe());
    // --exit-after alone, too.
    let run = view(&["--scene", &scene.display().to_string(), "--exit-after", "3"], &[]);
    clean(&run);
    assert!(run.stdout.contains(": 3 frames"), "{}", run.describe());
}

/// What the exit summary says was timed: `passes` (every pass) or `frames` (whole frames).
fn timed(run: &Run) -> &'static str {
    match (run.stdout.contains("whole frames timed"), run.stdout.contains(" passes timed, summed")) {
        (true, false) => "frames",
        (false, true) => "passes",
        _ => "unclear",
    }
}

#[test]
fn the_t_key_switches_between_timing_every_pass_and_whole_frames() {
    let dir = scratch("view-timing");
    let scene = small_scene(&dir).display().to_string();
    let frames = view(&["--scene", &scene, "--exit-after", "3", "--pass-timing", "frame"], &[]);
    clean(&frames);
    assert_eq!(timed(&frames), "frames", "{}", frames.describe());
    let s = script(&dir, "2 key t\n6 exit\n");
    let switched = view(&["--scene", &scene, "--pass-timing", "frame", "--script", &s], &[]);
    clean(&switched);
    assert_eq!(timed(&switched), "passes", "{}", switched.describe());
    let passes = view(&["--scene", &scene, "--exit-after", "3", "--pass-timing", "pass"], &[]);
    clean(&passes);
    assert_eq!(timed(&passes), "passes", "{}", passes.describe());
    // `auto`, the default: whole frames on lavapipe (a software device), every pass on a GPU.
    let auto = view(&["--scene", &scene, "--exit-after", "3"], &[]);
    clean(&auto);
    let want = if auto.stdout.contains("llvmpipe") { "frames" } else { "passes" };
    assert_eq!(timed(&auto), want, "{}", auto.describe());
}

/// Copies `from` into `to`, recursively.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("mkdir");
    for e in std::fs::read_dir(from).expect("read_dir") {
        let e = e.expect("entry");
        let target = to.join(e.file_name());
        if e.file_type().expect("type").is_dir() {
            copy_tree(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).expect("copy");
        }
    }
}

#[test]
fn a_broken_shader_edit_keeps_the_last_pipeline_until_it_is_fixed() {
    let dir = scratch("view-reload");
    let scene = small_scene(&dir);
    let shaders = dir.join("shaders_glsl");
    copy_tree(&workspace().join("shaders_glsl"), &shaders);
    let composite = shaders.join("eye/composite.comp");
    let original = std::fs::read_to_string(&composite).expect("composite.comp");
    let store = "imageStore(final_image, p, vec4(s.a > 0.5 ? s.rgb : b.rgb, 1.0));";
    assert!(original.contains(store), "composite.comp changed: update this test");
    let d = dir.display();
    let s = script(
        &dir,
        &format!(
            "3 key r\n4 screenshot {d}/before\n4 await {d}/broken\n5 reload\n8 screenshot {d}/while-broken\n\
             8 await {d}/fixed\n9 reload\n12 screenshot {d}/after\n12 exit\n"
        ),
    );
    let scene_arg = scene.display().to_string();
    let one = xvfb();
    let child = view_command(
        &["--scene", &scene_arg, "--technique", "shah", "--script", &s],
        &[("CAUSTICLAB_SHADERS", &shaders)],
    )
    .stdout(std::process::Stdio::piped())
    .stderr(std::process::Stdio::piped())
    .spawn()
    .expect("xvfb-run");
    let wait_for = |p: &Path| {
        let t = std::time::Instant::now();
        while !p.exists() {
            assert!(t.elapsed().as_secs() < 120, "{} never appeared", p.display());
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
    };
    wait_for(&dir.join("before/final.exr"));
    // Line 13 now names an identifier that does not exist.
    std::fs::write(&composite, original.replace(store, &store.replace("final_image, p", "final_imagex, p")))
        .expect("breaking composite.comp");
    std::fs::write(dir.join("broken"), "").expect("signal");
    wait_for(&dir.join("while-broken/final.exr"));
    // Fixed, and changed: the whole image at half its radiance.
    std::fs::write(
        &composite,
        original.replace(store, &store.replace("vec4(s.a", "vec4(0.5 * (s.a").replace("b.rgb,", "b.rgb),")),
    )
    .expect("fixing composite.comp");
    std::fs::write(dir.join("fixed"), "").expect("signal");
    let out = child.wait_with_output().expect("the viewer");
    drop(one);
    let run = run_of(out);
    clean(&run);
    assert!(run.stderr.contains("eye/composite.comp:13:") && run.stderr.contains("final_imagex"), "{}", run.describe());
    assert!(run.stderr.contains("last good pipelines keep running"), "{}", run.describe());
    // R rebuilds everything from source: the SPIR-V comes out as it was, so no pipeline is
    // made again; the fixed edit makes only the one pipeline that runs composite.comp.
    assert!(run.stderr.contains(": no pipeline changed"), "{}", run.describe());
    assert!(
        run.stderr.contains("view: reloaded shaders (eye/composite.comp): rebuilt 1 pipeline (`composite`)"),
        "{}",
        run.describe()
    );
    let read = |shot: &str| caustics::image_io::read_exr(&dir.join(shot).join("final.exr")).expect(shot);
    let (before, broken, after) = (read("before"), read("while-broken"), read("after"));
    assert_eq!(before.layers[0].data, broken.layers[0].data, "the last good pipeline kept running");
    let halved: Vec<f32> = before.layers[0].data.iter().map(|v| 0.5 * v).collect();
    let most = after.layers[0].data.iter().zip(&halved).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
    assert!(most < 1e-5, "the fixed shader runs: after = before / 2 within {most}");
}
