//! The `causticlab` binary end to end: exit codes and messages for bad input (with no partial
//! output left behind), `devices`, and renders checked against analytic irradiance and shadows.

// `!(error <= bound)` fails a NaN, where `error > bound` would pass it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod common;

use caustics::image_io::read_exr;
use common::*;
use std::sync::OnceLock;

/// Runs `args` + `--out <out>`, expects exit code 2 with every needle in stderr, and that
/// neither `out` nor a staging directory beside it exists afterwards.
fn expect_input_error(args: &[&str], needles: &[&str]) {
    let parent = scratch("bad");
    let out = parent.join("out");
    let mut full: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    full.push("--out".into());
    full.push(out.display().to_string());
    let run = causticlab(&full);
    assert_eq!(run.code, Some(2), "{:?}: expected exit code 2\n{}", args, run.describe());
    for needle in needles {
        assert!(run.stderr.contains(needle), "{:?}: stderr should mention `{needle}`\n{}", args, run.describe());
    }
    assert!(run.stderr.contains("error: "), "{:?}: errors start with `error: `\n{}", args, run.describe());
    assert!(!run.stderr.contains("panicked"), "{:?}: panicked\n{}", args, run.describe());
    assert!(!out.exists(), "{:?}: {} exists after a failed run", args, out.display());
    let leftovers: Vec<_> = std::fs::read_dir(&parent)
        .map(|d| d.filter_map(|e| e.ok()).map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(leftovers.is_empty(), "{:?}: left behind {leftovers:?}", args);
    let _ = std::fs::remove_dir_all(&parent);
}

/// `sphere_on_plane.toml` with `from` replaced by `to`, written as `scene.toml` in a fresh dir.
fn edited_scene(name: &str, from: &str, to: &str) -> Scratch {
    let text = std::fs::read_to_string(scene("sphere_on_plane")).expect("reading sphere_on_plane.toml");
    assert!(text.contains(from), "sphere_on_plane.toml no longer contains {from:?}");
    let path = scratch(name).within("scene.toml");
    std::fs::write(&path, text.replacen(from, to, 1)).expect("writing a temp scene");
    path
}

const SPHERE_OBJECT: &str = "shape = \"icosphere\"\nradius = 0.5\nsubdivisions = 5        # 20480 triangles";

// ---------------------------------------------------------------------------------------------
// Bad input: exit code 2, a message naming the file / key / feature, no output directory.

#[test]
fn missing_scene_file() {
    expect_input_error(&["render", "--scene", "scenes/no_such_scene.toml"], &["no_such_scene.toml"]);
}

/// Writes `sphere_on_plane.toml` with `from` replaced by `to` (plus `extra` files beside it) into
/// a fresh directory, expects an input error naming the scene file and `needles`, cleans up.
fn expect_scene_error(name: &str, from: &str, to: &str, extra: &[(&str, &str)], needles: &[&str]) {
    let path = edited_scene(name, from, to);
    for (file, text) in extra {
        std::fs::write(path.with_file_name(file), text).expect("writing a file beside the temp scene");
    }
    let p = path.display().to_string();
    let mut all = vec![p.as_str()];
    all.extend_from_slice(needles);
    expect_input_error(&["render", "--scene", &p], &all);
    if let Some(dir) = path.parent() {
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn toml_syntax_error() {
    expect_scene_error("syntax", "resolution = [512, 512]", "resolution = [512, 512", &[], &[]);
}

#[test]
fn unknown_scene_key() {
    expect_scene_error("unknown-key", "fov_y = 40.0", "fov_y = 40.0\nfocal_length = 3.0", &[], &["focal_length"]);
}

#[test]
fn missing_obj_model() {
    let to = "shape = \"obj\"\nfile = \"no_such_model.obj\"";
    expect_scene_error("missing-obj", SPHERE_OBJECT, to, &[], &["no_such_model.obj"]);
}

#[test]
fn malformed_obj_model() {
    let to = "shape = \"obj\"\nfile = \"garbage.obj\"";
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\nf 1 2 3\n";
    expect_scene_error("bad-obj", SPHERE_OBJECT, to, &[("garbage.obj", obj)], &["garbage.obj"]);
}

#[test]
fn zero_camera_resolution() {
    let to = "resolution = [0, 512]";
    expect_scene_error("res-zero", "resolution = [512, 512]", to, &[], &["camera.resolution"]);
}

#[test]
fn huge_camera_resolution() {
    let to = "resolution = [100000, 512]";
    expect_scene_error("res-huge", "resolution = [512, 512]", to, &[], &["camera.resolution"]);
}

/// A camera within maxImageDimension2D whose images need more memory than the device has
/// (lavapipe's device-local heap is 2048 MiB; 16384² eye images need 30720 MiB): refused before
/// anything is allocated, naming the key and both amounts.
#[test]
fn camera_beyond_the_device_memory() {
    let to = "resolution = [16384, 16384]";
    let needles = ["key `camera.resolution`", "30720 MiB", "device-local heap"];
    expect_scene_error("res-memory", "resolution = [512, 512]", to, &[], &needles);
}

#[test]
fn unknown_device() {
    let s = scene("sphere_on_plane");
    expect_input_error(&["--device", "no-such-gpu", "render", "--scene", &s], &["no-such-gpu"]);
}

#[test]
fn technique_needing_an_absent_feature() {
    let s = scene("sphere_on_plane");
    expect_input_error(
        &["--without-feature", "shader_output_layer", "render", "--scene", &s],
        &["shader_output_layer"],
    );
}

#[test]
fn compute_splat_without_float_atomics() {
    let s = scene("sphere_on_plane");
    expect_input_error(
        &[
            "--without-feature",
            "buffer_float32_atomic_add",
            "render",
            "--scene",
            &s,
            "--technique",
            "wd-points",
            "--splat-path",
            "compute",
        ],
        &["buffer_float32_atomic_add", "splat_path"],
    );
    expect_input_error(&["render", "--scene", &s, "--splat-path", "scatter"], &["--splat-path", "scatter", "compute"]);
}

#[test]
fn ray_queries_without_acceleration_structures() {
    let s = scene("sphere_on_plane");
    let trace = ["render", "--scene", &s, "--technique", "photon-trace", "--photons", "64", "--trace", "ray-query"];
    let hidden = ["--without-feature", "acceleration_structure"];
    expect_input_error(&[&hidden[..], &trace[..]].concat(), &["acceleration_structure", "ray-query"]);
    expect_input_error(&["render", "--scene", &s, "--trace", "rtx"], &["--trace", "rtx", "ray-query"]);
}

#[test]
fn unknown_technique() {
    let s = scene("sphere_on_plane");
    expect_input_error(&["render", "--scene", &s, "--technique", "photon_magic"], &["photon_magic", "none"]);
}

#[test]
fn unknown_dump_name() {
    let s = scene("sphere_on_plane");
    expect_input_error(&["render", "--scene", &s, "--dump", "receiver,bogus_buffer"], &["bogus_buffer", "shadow_map"]);
}

#[test]
fn receiver_dump_without_a_receiver_map() {
    // A scene without [receiver_map] has no receiver map to dump: said, not skipped silently.
    let table = "[receiver_map]\nplane_y = 0.0\nx_range = [-2.0, 2.0]\nz_range = [-2.0, 2.0]\nresolution = 256\n";
    let file = edited_scene("no_receiver_map", table, "");
    let s = file.display().to_string();
    expect_input_error(&["render", "--scene", &s, "--dump", "receiver"], &["receiver", "[receiver_map]", "scene.toml"]);
}

#[test]
fn caustic_dump_without_a_caustic_technique() {
    expect_input_error(
        &["render", "--scene", &scene("sphere_on_plane"), "--dump", "photon_buffer"],
        &["photon_buffer", "--technique"],
    );
}

/// The pool's technique does not render meshes: the eye renderer's buffers are refused saying
/// so and naming the pool's own, not as a buffer of some other technique.
#[test]
fn mesh_renderer_dumps_on_a_pool_scene() {
    let pool = scene("pool_overhead");
    for n in ["shadow_map", "eye_gbuffer", "refractor_front_faces"] {
        expect_input_error(
            &["render", "--scene", &pool, "--dump", n],
            &[n, "mesh renderer", "pool-convolution", "receiver"],
        );
    }
    expect_input_error(
        &["render", "--scene", &pool, "--dump", "caustic_map"],
        &["caustic_map", "a mesh technique", "pool-convolution", "height_field"],
    );
}

/// A light inside the specular objects' bounding sphere is refused for the light-space
/// techniques, its position written as the scene file writes one.
#[test]
fn a_light_inside_the_refractors_bounds() {
    let file = edited_scene("light_inside", "position = [0.0, 6.0, 0.0]", "position = [0.0, 1.25, 0.0]");
    let s = file.display().to_string();
    expect_input_error(
        &["render", "--scene", &s, "--technique", "shah"],
        &["scene.toml", "light 0 at [0, 1.25, 0]", "inside the bounding sphere"],
    );
}

/// The pool's reference traces no photons: a photon option on a pool scene is refused, naming
/// it, not ignored.
#[test]
fn photon_options_on_a_pool_reference() {
    let pool = scene("pool_overhead");
    for (flag, value) in [("--photons", "5"), ("--seed", "3"), ("--fresnel", "false"), ("--threads", "1")] {
        expect_input_error(&["reference", "--scene", &pool, flag, value], &[flag, "pool scene", "pool_overhead.toml"]);
    }
    expect_input_error(&["reference", "--scene", &pool, "--facet-normals"], &["--facet-normals", "pool scene"]);
}

/// `--dump` that names nothing, and a pool technique's buffer asked of a mesh scene.
#[test]
fn dumps_that_name_nothing_or_a_pool_buffer_on_a_mesh_scene() {
    let s = scene("sphere_on_plane");
    expect_input_error(&["render", "--scene", &s, "--dump", ""], &["--dump", "no buffer named"]);
    expect_input_error(
        &["render", "--scene", &s, "--technique", "shah", "--dump", "height_field"],
        &["height_field", "pool-convolution", "pool scenes", "sphere_on_plane.toml"],
    );
    // On a pool scene with a mesh technique the advice is the technique, not "a mesh scene".
    let pool = scene("pool_overhead");
    expect_input_error(
        &["render", "--scene", &pool, "--technique", "shah", "--dump", "height_field"],
        &["height_field", "add --technique pool-convolution"],
    );
}

/// `adaptive` past 4096² photons needs a memory limit: `--max-level` alone says so under its own
/// name (it sets the photons), not under a `--photons` the user never gave.
#[test]
fn adaptive_levels_past_4096_name_the_memory_limit() {
    let s = scene("sphere_on_plane");
    expect_input_error(
        &["render", "--scene", &s, "--technique", "adaptive", "--max-level", "7"],
        &["--max-level", "8192²", "--photon-memory-limit"],
    );
}

#[test]
fn caustic_setting_out_of_range() {
    expect_input_error(
        &["render", "--scene", &scene("sphere_on_plane"), "--technique", "shah", "--photons", "5000"],
        &["--photons", "4096"],
    );
    // A negative number is a value the flag refuses, not an unknown argument.
    for (flag, value) in [("--photons", "-5"), ("--splat-radius", "-1"), ("--iterations", "-3")] {
        let args = ["render", "--scene", &scene("sphere_on_plane"), "--technique", "shah", flag, value];
        expect_input_error(&args, &[flag, value]);
    }
    let scene_file = edited_scene("iterations", "[receiver_map]", "[caustics]\niterations = 0\n\n[receiver_map]");
    expect_input_error(&["render", "--scene", &scene_file.display().to_string()], &["caustics.iterations"]);
    // Instanced draws need a power-of-two vertex buffer of a sane size.
    for bad in ["1000", "32", "131072"] {
        expect_input_error(
            &["render", "--scene", &scene("sphere_on_plane"), "--technique", "wd-points", "--instance-vertices", bad],
            &["--instance-vertices", "power of two", bad],
        );
    }
}

/// `hcm`'s settings are refused for the other techniques, in the final settings: a scene may set
/// them and leave the technique to `--technique`.
#[test]
fn hierarchy_settings_need_technique_hcm() {
    let s = scene("sphere_on_plane");
    for (flag, value) in [("--cluster", "all"), ("--path", "compute"), ("--splat", "varying-single")] {
        expect_input_error(
            &["render", "--scene", &s, "--technique", "wd-points", flag, value],
            &[&flag[2..], value, "hcm", "wd-points"],
        );
    }
    expect_input_error(
        &["render", "--scene", &s, "--technique", "hcm", "--varying-radius", "beam-area"],
        &["varying_radius", "--varying-radius", "varying-single"],
    );
    let file = edited_scene("hcm-keys", "[receiver_map]", "[caustics]\ncluster = \"last\"\n\n[receiver_map]");
    let f = file.display().to_string();
    expect_input_error(&["render", "--scene", &f, "--technique", "shah"], &[&f, "caustics.cluster", "shah"]);
    let out = scratch("hcm-keys-ok").within("out");
    let run = causticlab(&[
        "render",
        "--scene",
        &f,
        "--technique",
        "hcm",
        "--photons",
        "64",
        "--out",
        &out.display().to_string(),
    ]);
    assert_eq!(run.code, Some(0), "a scene's cluster key with --technique hcm: {}", run.describe());
}

/// `adaptive`'s settings (Wyman & Nichols 2009 Sec. 3.2, 4.3): the photon grid must be 64 × 2^L
/// (beyond 4096² only under a memory limit that can hold its batches), the geometry buffers a
/// sane fraction of the caustic map, `max_level` within range and agreeing with `photons`; its
/// keys are refused for other techniques; `--max-level` alone sets the grid.
#[test]
fn adaptive_settings_are_checked() {
    let s = scene("sphere_on_plane");
    let adaptive = |extra: &[&str]| -> Vec<String> {
        let mut v: Vec<String> =
            ["render", "--scene", &s, "--technique", "adaptive"].iter().map(|x| x.to_string()).collect();
        v.extend(extra.iter().map(|x| x.to_string()));
        v
    };
    let cases: [(&[&str], &[&str]); 8] = [
        (&["--photons", "16384"], &["--photons", "4096", "16384"]),
        (&["--photons", "16384", "--photon-memory-limit", "1"], &["--photon-memory-limit", "at least", "16384²"]),
        (&["--photons", "200"], &["--photons", "64 × 2^L", "200"]),
        (&["--gbuffer-scale", "0"], &["--gbuffer-scale", "(0, 4]"]),
        (&["--gbuffer-scale", "nan"], &["--gbuffer-scale", "(0, 4]"]),
        (&["--gbuffer-scale", "0.001"], &["--gbuffer-scale", "16 to 8192"]),
        (&["--max-level", "9"], &["--max-level", "between 0 and 6", "9"]),
        (&["--photons", "256", "--max-level", "4"], &["--max-level", "1024²", "256"]),
    ];
    for (extra, want) in cases {
        let args = adaptive(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        expect_input_error(&args, want);
    }
    expect_input_error(
        &["render", "--scene", &s, "--technique", "wd-points", "--metric", "max-error"],
        &["metric", "max-error", "adaptive", "wd-points"],
    );
    let out = scratch("adaptive-max-level").within("out");
    let out = out.display().to_string();
    let args = adaptive(&["--max-level", "0", "--caustic-map-resolution", "256", "--out", &out]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let run = causticlab(&args);
    assert_eq!(run.code, Some(0), "--max-level 0 alone: {}", run.describe());
    let timings = std::fs::read_to_string(std::path::Path::new(&out).join("timings.json")).expect("timings.json");
    assert!(timings.contains("\"photons\": 64"), "--max-level 0 should give 64² photons: {timings}");
}

#[test]
fn unknown_feature_name() {
    let s = scene("sphere_on_plane");
    expect_input_error(
        &["render", "--scene", &s, "--without-feature", "warp_drive"],
        &["warp_drive", "transform_feedback", "shader_output_layer"],
    );
}

#[test]
fn usage_errors_exit_2() {
    let s = scene("sphere_on_plane");
    expect_input_error(&["render"], &["--scene"]);
    expect_input_error(&["render", "--scene", &s, "--frames", "0"], &["--frames"]);
}

// ---------------------------------------------------------------------------------------------
// devices

/// `causticlab variants | head -1`: a reader that closes the pipe early ends the program as
/// SIGPIPE would (141), without a panic or a message. The pipe's read end is closed before the
/// program starts, so its first line already meets a closed pipe.
#[test]
fn a_closed_stdout_ends_the_program_quietly() {
    for args in [&["variants"][..], &["dumps"]] {
        let (reader, writer) = std::io::pipe().expect("a pipe");
        drop(reader);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_causticlab"))
            .args(args)
            .current_dir(workspace())
            .stdout(writer)
            .stderr(std::process::Stdio::piped())
            .output()
            .expect("running causticlab");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(141), "{args:?}\n{stderr}");
        assert!(stderr.is_empty(), "{args:?}: said something\n{stderr}");
    }
}

#[test]
fn devices_lists_features() {
    let run = causticlab(&["devices"]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    assert!(run.stdout.contains("[0] "), "no device listed\n{}", run.describe());
    assert!(run.stdout.contains("transform_feedback"), "{}", run.describe());
    assert!(run.stdout.contains("maxImageDimension2D"), "{}", run.describe());
    assert!(run.stdout.contains("[default"), "the default device is marked\n{}", run.describe());
}

#[test]
fn devices_accepts_global_options_after_the_subcommand() {
    let run = causticlab(&["devices", "--device", "0", "--without-feature", "geometry_shader"]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    assert!(run.stdout.contains("selected by --device"), "{}", run.describe());
    assert!(run.stdout.contains("no (--without-feature)"), "{}", run.describe());
}

// ---------------------------------------------------------------------------------------------
// Renders (`--technique none`), shared between tests: one run per scene.

struct Rendered {
    run: Run,
    out: Scratch,
}

/// One render per scene for every test that reads it; held in a static, which is never dropped,
/// so these two folders stay in the temp dir after the run (the only ones that do).
fn render_once(stem: &str) -> Rendered {
    let out = scratch(&format!("render-{stem}")).within("out");
    let s = scene(stem);
    let o = out.display().to_string();
    let run = causticlab(&["render", "--scene", &s, "--out", &o, "--dump", "all", "--validate"]);
    Rendered { run, out }
}

fn rendered(stem: &'static str) -> &'static Rendered {
    static ON_PLANE: OnceLock<Rendered> = OnceLock::new();
    static OBLIQUE: OnceLock<Rendered> = OnceLock::new();
    let cell = match stem {
        "sphere_on_plane" => &ON_PLANE,
        "sphere_oblique" => &OBLIQUE,
        _ => panic!("no cached render for {stem}"),
    };
    let r = cell.get_or_init(|| render_once(stem));
    assert_eq!(r.run.code, Some(0), "render {stem} failed\n{}", r.run.describe());
    let validation: Vec<&str> = r.run.stderr.lines().filter(|l| l.contains("[validation")).collect();
    assert!(validation.is_empty(), "render {stem}: validation messages:\n{}", validation.join("\n"));
    r
}

#[test]
fn render_writes_every_output() {
    let r = rendered("sphere_on_plane");
    let mut expected: Vec<String> = vec!["final.exr".into(), "final.png".into(), "timings.json".into()];
    let settings = caustics::scene::CausticSettings::default();
    expected.extend(caustics::render::dumps_for(&settings).iter().map(|n| format!("{n}.exr")));
    for f in &expected {
        assert!(r.out.join(f).is_file(), "{} missing\n{}", f, r.run.describe());
    }
    let finals = read_exr(&r.out.join("final.exr")).expect("reading final.exr");
    assert_eq!((finals.width, finals.height), (512, 512));
    for c in ["R", "G", "B"] {
        assert!(find_channel(&finals, c).is_some(), "final.exr has no {c}");
    }
    let json = std::fs::read_to_string(r.out.join("timings.json")).expect("reading timings.json");
    let t: serde_json::Value = serde_json::from_str(&json).expect("timings.json is JSON");
    assert_eq!(t["technique"], "none");
    assert_eq!(t["frames"], 1);
    assert!(t["device"]["name"].as_str().is_some_and(|n| !n.is_empty()), "{json}");
    assert!(t["passes"].as_array().is_some_and(|p| !p.is_empty()), "no passes timed: {json}");
    // The frame's host wall time beside its passes (one per frame), and the commit measured.
    assert!(t["host_frame_ms"].as_array().is_some_and(|h| h.len() == 1 && h[0].as_f64().is_some()), "{json}");
    assert!(t["commit"].as_str().is_some_and(|c| !c.is_empty()), "{json}");
    assert!(r.run.stdout.contains("(sum of the pass medians)"), "{}", r.run.describe());
    assert!(r.run.stdout.contains("(frame, host wall)"), "{}", r.run.describe());
    // No staging directory is left beside the output.
    let parent = r.out.parent().expect("out has a parent");
    let names: Vec<_> =
        std::fs::read_dir(parent).expect("listing").filter_map(|e| e.ok()).map(|e| e.file_name()).collect();
    assert_eq!(names, vec![std::ffi::OsString::from("out")]);
}

// ---------------------------------------------------------------------------------------------
// The receiver map against analytic irradiance and visibility.

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

const SPHERE_CENTRE: V3 = [0.0, 1.0, 0.0];
const SPHERE_RADIUS: f64 = 0.5;
const INTENSITY: f64 = 100.0;
const RES: u32 = 256;
const TEXEL: f64 = 4.0 / RES as f64;

/// Floor point (x, 0, z) of texel column i, row j.
fn texel_centre(i: f64, j: f64) -> V3 {
    [-2.0 + (i + 0.5) * TEXEL, 0.0, -2.0 + (j + 0.5) * TEXEL]
}

/// Does the segment from `p` to the light pass through the sphere?
fn occluded(p: V3, light: V3) -> bool {
    let d = sub(light, p);
    let t = (dot(sub(SPHERE_CENTRE, p), d) / dot(d, d)).clamp(0.0, 1.0);
    let q = [p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]];
    let e = sub(SPHERE_CENTRE, q);
    dot(e, e) < SPHERE_RADIUS * SPHERE_RADIUS
}

/// True when some point within 3 texels of texel (i, j) has the other visibility.
fn near_shadow_boundary(i: u32, j: u32, light: V3) -> bool {
    let centre = occluded(texel_centre(i as f64, j as f64), light);
    for step in 1..=6 {
        let radius = 0.5 * step as f64;
        for k in 0..48 {
            let a = k as f64 * std::f64::consts::TAU / 48.0;
            let p = texel_centre(i as f64 + radius * a.cos(), j as f64 + radius * a.sin());
            if occluded(p, light) != centre {
                return true;
            }
        }
    }
    false
}

/// Checks receiver.exr of `stem` lit by a point light of 100 W/sr at `light`; returns the
/// (measured, analytic) shadowed area in m^2.
fn check_receiver(stem: &'static str, light: V3) -> (f64, f64) {
    let r = rendered(stem);
    let img = read_exr(&r.out.join("receiver.exr")).expect("reading receiver.exr");
    assert_eq!((img.width, img.height), (RES, RES), "{stem}: receiver size");
    let names: Vec<String> = img.layers.iter().flat_map(|l| l.channels.clone()).collect();
    let chan = |c: &str| {
        find_channel(&img, c).unwrap_or_else(|| panic!("{stem}: receiver.exr has no {c} channel ({names:?})"))
    };
    let (cr, cg, cb, ce0) = (chan("R"), chan("G"), chan("B"), chan("E0"));

    let (mut measured, mut analytic) = (0usize, 0usize);
    let (mut lit_checked, mut shadow_checked) = (0usize, 0usize);
    let mut failures = vec![];
    for j in 0..RES {
        for i in 0..RES {
            let p = texel_centre(i as f64, j as f64);
            let to_light = sub(light, p);
            let dist = dot(to_light, to_light).sqrt();
            let e0 = INTENSITY * (light[1] / dist) / (dist * dist);
            let got_e0 = value(&img, ce0, i, j);
            if !((got_e0 - e0).abs() <= 0.01 * e0) && failures.len() < 10 {
                failures.push(format!("texel ({i}, {j}) at {p:?}: E0 {got_e0}, expected {e0}"));
            }
            let rgb = [value(&img, cr, i, j), value(&img, cg, i, j), value(&img, cb, i, j)];
            let shadow = occluded(p, light);
            analytic += shadow as usize;
            measured += (rgb[0] < 0.5) as usize;
            if near_shadow_boundary(i, j, light) {
                continue;
            }
            let ok = if shadow { rgb.iter().all(|v| *v < 0.01) } else { rgb.iter().all(|v| (v - 1.0).abs() <= 0.01) };
            if shadow {
                shadow_checked += 1;
            } else {
                lit_checked += 1;
            }
            if !ok && failures.len() < 10 {
                let what = if shadow { "shadowed, expected < 0.01" } else { "lit, expected 1.0 +- 1%" };
                failures.push(format!("texel ({i}, {j}) at {p:?}: E/E0 {rgb:?}, {what}"));
            }
        }
    }
    assert!(failures.is_empty(), "{stem}: receiver.exr disagrees with the analytic answer:\n{}", failures.join("\n"));
    assert!(
        shadow_checked > 100 && lit_checked > 10_000,
        "{stem}: {shadow_checked} shadowed, {lit_checked} lit texels checked"
    );
    let texel_area = TEXEL * TEXEL;
    let (measured, analytic) = (measured as f64 * texel_area, analytic as f64 * texel_area);
    assert!(measured > 0.0, "{stem}: no shadow at all");
    assert!(
        (measured - analytic).abs() <= 0.05 * analytic,
        "{stem}: shadow area {measured} m^2, analytic {analytic} m^2"
    );
    (measured, analytic)
}

#[test]
fn receiver_sphere_on_plane_matches_analytic_irradiance_and_shadow() {
    let (measured, _) = check_receiver("sphere_on_plane", [0.0, 6.0, 0.0]);
    // Light straight above: the shadow is a disc of radius h tan(a), sin(a) = r / d.
    let (h, d) = (6.0f64, 5.0f64);
    let radius = h * SPHERE_RADIUS / (d * d - SPHERE_RADIUS * SPHERE_RADIUS).sqrt();
    let disc = std::f64::consts::PI * radius * radius;
    assert!((measured - disc).abs() <= 0.05 * disc, "shadow area {measured} m^2, disc {disc} m^2");
}

#[test]
fn receiver_sphere_oblique_matches_analytic_irradiance_and_shadow() {
    check_receiver("sphere_oblique", [2.0, 5.0, 1.0]);
}

#[test]
fn analytic_helpers_agree_with_geometry() {
    // Straight below the sphere is in shadow, far away is not; the disc edge is ~0.603 m out.
    let light = [0.0, 6.0, 0.0];
    assert!(occluded([0.0, 0.0, 0.0], light));
    assert!(occluded([0.59, 0.0, 0.0], light));
    assert!(!occluded([0.62, 0.0, 0.0], light));
    assert!(!occluded([1.5, 0.0, 1.5], light));
    // Centre texel (128,128) is 1/128 m from the origin: deep inside, far from the edge.
    assert!(!near_shadow_boundary(128, 128, light));
    // Texel whose centre is ~0.60 m out along +x is at the edge.
    let i = ((0.603 + 2.0) / TEXEL - 0.5).round() as u32;
    assert!(near_shadow_boundary(i, 128, light));
}

// ---------------------------------------------------------------------------------------------
// Output paths and compare inputs: input errors before any work.

#[test]
fn out_over_a_regular_file_fails_before_the_device_is_opened() {
    let dir = scratch("out-file");
    let file = dir.join("out");
    std::fs::write(&file, b"keep me").expect("writing a file where --out points");
    let f = file.display().to_string();
    let inside = file.join("sub").display().to_string();
    let s = scene("sphere_on_plane");
    // The device named does not exist: only a check made before opening it reports the path.
    for out in [&f, &inside] {
        for args in [
            vec!["--device", "no-such-gpu", "render", "--scene", &s, "--out", out],
            vec!["reference", "--scene", &s, "--photons", "64", "--out", out],
        ] {
            let run = causticlab(&args);
            assert_eq!(run.code, Some(2), "{args:?}\n{}", run.describe());
            for needle in ["--out", out.as_str(), "not a directory"] {
                assert!(run.stderr.contains(needle), "{args:?}: stderr lacks `{needle}`\n{}", run.describe());
            }
            assert!(!run.stderr.contains("no-such-gpu"), "{args:?}: the device was opened first\n{}", run.describe());
        }
    }
    assert_eq!(std::fs::read(&file).expect("the file is still there"), b"keep me");
    let left: Vec<_> =
        std::fs::read_dir(&dir).expect("scratch").filter_map(|e| e.ok()).map(|e| e.file_name()).collect();
    assert_eq!(left, vec![std::ffi::OsString::from("out")], "nothing staged beside it");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A 2×2 receiver map (main layer E/E0 in R, G, B and E0) at `path`.
fn small_exr(path: &std::path::Path) {
    let data = vec![1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.5, 0.5, 0.5, 1.0];
    let layer = caustics::image_io::Layer::new(None, &["R", "G", "B", "E0"], data);
    let image = caustics::image_io::ImageF32 { width: 2, height: 2, layers: vec![layer] };
    caustics::image_io::write_exr(path, &image).expect("writing a test EXR");
}

#[test]
fn compare_names_a_missing_or_non_exr_input() {
    let dir = scratch("compare-inputs");
    let exr = dir.join("receiver.exr");
    small_exr(&exr);
    let png = dir.join("final.png");
    caustics::image_io::write_png_tonemapped(&png, 1, 1, &[1.0, 1.0, 1.0], 1.0).expect("writing a test PNG");
    let missing = dir.join("missing.exr");
    // An EXR cut short: its magic number and header are there, its pixels are not.
    let bytes = std::fs::read(&exr).expect("the test EXR");
    let cut = dir.join("cut.exr");
    std::fs::write(&cut, &bytes[..bytes.len() - 40]).expect("writing the cut EXR");
    let (e, p, m) = (exr.display().to_string(), png.display().to_string(), missing.display().to_string());
    let c = cut.display().to_string();
    // The real EXR compares: the check does not reject the files causticlab writes.
    let run = causticlab(&["compare", &e, &e]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    for (args, needles) in [
        ([&e, &p], [p.as_str(), "not an OpenEXR file", "receiver.exr"]),
        ([&p, &e], [p.as_str(), "not an OpenEXR file", "receiver.exr"]),
        ([&e, &m], [m.as_str(), "no such file", "error: "]),
        ([&m, &e], [m.as_str(), "no such file", "error: "]),
        ([&e, &c], [c.as_str(), "not a readable OpenEXR file", "error: "]),
    ] {
        let run = causticlab(&["compare", args[0], args[1]]);
        assert_eq!(run.code, Some(2), "{args:?}\n{}", run.describe());
        for needle in needles {
            assert!(run.stderr.contains(needle), "{args:?}: stderr lacks `{needle}`\n{}", run.describe());
        }
        assert!(!run.stderr.contains("file identifier missing"), "{}", run.describe());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn render_help_lists_every_enumerated_value_under_its_group() {
    let run = causticlab(&["render", "--help"]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    for heading in ["Scene:", "Technique (overrides the scene's [caustics]):", "Output:", "Device:"] {
        assert!(run.stdout.contains(heading), "no `{heading}` group in\n{}", run.stdout);
    }
    // Each enumerated flag with the names the enum accepts (read from the enums, not copied).
    use caustics::techniques::{trendall_stewart2000, wyman2008, Intersect, Metric, SplatKernel, SplatPath, Technique};
    let flags: [(&str, &[&str]); 10] = [
        ("--technique", Technique::NAMES),
        ("--splat-kernel", SplatKernel::NAMES),
        ("--intersect", Intersect::NAMES),
        ("--path", caustics::techniques::shared::settings::TraversalPath::NAMES),
        ("--cluster", wyman2008::Cluster::NAMES),
        ("--splat", wyman2008::SplatMode::NAMES),
        ("--varying-radius", wyman2008::VaryingRadius::NAMES),
        ("--splat-path", SplatPath::NAMES),
        ("--precision", trendall_stewart2000::Precision::NAMES),
        ("--metric", Metric::NAMES),
    ];
    for (flag, names) in flags {
        let at = run.stdout.find(&format!("{flag} ")).unwrap_or_else(|| panic!("{flag} missing"));
        let section = &run.stdout[at..];
        let section = &section[..section[2..].find("\n      --").map_or(section.len(), |i| i + 2)];
        assert!(section.contains("Possible values"), "{flag}: {section}");
        for n in names {
            assert!(section.contains(&format!("- {n}:")), "{flag} does not list `{n}`: {section}");
        }
    }
}

#[test]
fn deferred_refraction_without_geometry_shaders() {
    let s = scene("sphere_on_plane");
    expect_input_error(
        &["--without-feature", "geometry_shader", "render", "--scene", &s, "--refraction", "deferred"],
        &["geometry_shader", "refraction `deferred`"],
    );
    expect_input_error(
        &["render", "--scene", &s, "--refraction", "sideways"],
        &["--refraction", "sideways", "deferred"],
    );
    // A buffer of the other refraction.
    expect_input_error(
        &["render", "--scene", &s, "--dump", "refractor_geometry"],
        &["refractor_geometry", "--refraction deferred"],
    );
    expect_input_error(
        &["render", "--scene", &s, "--refraction", "deferred", "--dump", "refractor_back_faces"],
        &["refractor_back_faces", "--refraction forward"],
    );
    // Photon differentials' footprints, without differentials.
    expect_input_error(
        &["render", "--scene", &s, "--technique", "photon-trace", "--dump", "photon_footprints"],
        &["photon_footprints", "--differentials true"],
    );
}

#[test]
fn compare_says_when_the_maps_are_of_other_scenes_or_fresnel_settings() {
    let dir = scratch("compare-mismatch");
    let image = |scene: &str, fresnel: &str, name: &str| {
        let p = dir.join(name);
        let layer = caustics::image_io::Layer::new(None, &["R", "G", "B", "E0"], vec![1.0; 16]);
        let img = caustics::image_io::ImageF32 { width: 2, height: 2, layers: vec![layer] };
        let header = [("causticlab:scene", scene.to_string()), ("causticlab:fresnel", fresnel.to_string())];
        caustics::image_io::write_exr_with(&p, &img, &header).expect("writing a test EXR");
        p.display().to_string()
    };
    let a = image("scenes/sphere_on_plane.toml", "true", "a.exr");
    let same = image("scenes/sphere_on_plane.toml", "true", "same.exr");
    let other = image("scenes/pool.toml", "false", "other.exr");
    let run = causticlab(&["compare", &a, &same]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    assert!(!run.stderr.contains("warning:"), "{}", run.describe());
    let run = causticlab(&["compare", &a, &other]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    for needle in [
        "warning: A is a map of scenes/sphere_on_plane.toml, B of scenes/pool.toml",
        "fresnel true, B with fresnel false",
    ] {
        assert!(run.stderr.contains(needle), "no `{needle}`\n{}", run.describe());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn compare_writes_its_error_image_as_exr_or_png_and_refuses_other_names() {
    let dir = scratch("compare-error-image");
    let (a, b) = (dir.join("a.exr"), dir.join("b.exr"));
    small_exr(&a);
    // B: texel 1 darker than A (A too bright there), the rest equal.
    let data = vec![1.0, 1.0, 1.0, 1.0, 1.5, 1.5, 1.5, 1.0, 1.0, 1.0, 1.0, 1.0, 0.5, 0.5, 0.5, 1.0];
    let layer = caustics::image_io::Layer::new(None, &["R", "G", "B", "E0"], data);
    caustics::image_io::write_exr(&b, &caustics::image_io::ImageF32 { width: 2, height: 2, layers: vec![layer] })
        .expect("writing a test EXR");
    let (sa, sb) = (a.display().to_string(), b.display().to_string());
    let png = dir.join("error.png");
    let run = causticlab(&["compare", &sa, &sb, "--error-image", &png.display().to_string(), "--error-scale", "0.5"]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let (w, h, rgba) = caustics::image_io::read_png_rgba(&png).expect("the PNG error image");
    assert_eq!((w, h), (2, 2));
    // Texel 1: A − B = +0.5 = the scale: saturated red (sRGB-decoded to linear, still 1, 0, 0).
    assert!(rgba[4] > 0.99 && rgba[5] < 0.01 && rgba[6] < 0.01, "texel 1 is not red: {:?}", &rgba[4..8]);
    // Texel 3 (0.5 in both, in the region): no error, white.
    assert!(rgba[12..15].iter().all(|&c| c > 0.99), "texel 3 is not white: {:?}", &rgba[12..16]);
    let exr = dir.join("error.exr");
    let run = causticlab(&["compare", &sa, &sb, "--error-image", &exr.display().to_string()]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let layers = caustics::image_io::read_exr(&exr).expect("the EXR error image");
    assert_eq!(layers.layers[0].channels, ["A", "B", "diff", "in_region"]);
    for bad in [vec!["--error-image", "error.tiff"], vec!["--error-scale", "0"]] {
        let mut args = vec!["compare", &sa, &sb];
        args.extend(bad.iter().copied());
        let run = causticlab(&args);
        assert_eq!(run.code, Some(2), "{bad:?}\n{}", run.describe());
        assert!(run.stderr.contains(bad[0]), "{bad:?}: the error does not name {}\n{}", bad[0], run.describe());
    }
    let _ = std::fs::remove_dir_all(&dir);
}
