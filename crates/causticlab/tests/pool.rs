//! `causticlab` on pool scenes (Trendall & Stewart 2000): the render's flags and files with
//! validation on, `reference` (the f64 passes and `--direct` Eq. 2) against the render, and bad
//! input. (The Table 1 config's quick run is in tests/bench_papers.rs.)

mod common;

use caustics::image_io::read_exr;
use common::{causticlab, find_channel, scene, scratch, workspace, Run};
use serde_json::Value;
use std::path::Path;

fn assert_clean(r: &Run) {
    assert_eq!(r.code, Some(0), "{}", r.describe());
    assert!(r.stderr.contains("validation: no warnings or errors reported"), "{}", r.describe());
}

fn assert_input_error(r: &Run, needles: &[&str]) {
    assert_eq!(r.code, Some(2), "{}", r.describe());
    for n in needles {
        assert!(r.stderr.contains(n), "stderr lacks {n:?}: {}", r.describe());
    }
}

/// The mean of R of the receiver map's main layer (E / E_flat) over texels with E_flat > 0.
fn receiver(dir: &Path) -> (Vec<f64>, Vec<f64>) {
    let img = read_exr(&dir.join("receiver.exr")).expect("receiver.exr");
    let r = find_channel(&img, "R").expect("R");
    let e0 = find_channel(&img, "E0").expect("E0");
    let n = img.width * img.height;
    let get = |c: (usize, usize)| {
        (0..n).map(|i| img.layers[c.0].sample(img.width, i % img.width, i / img.width, c.1) as f64).collect()
    };
    (get(r), get(e0))
}

#[test]
fn every_precision_renders_the_pool_with_its_dumps_and_no_validation_message() {
    for precision in ["unorm8", "float", "f64"] {
        let out = scratch(&format!("pool-{precision}"));
        let r = causticlab(&[
            "--validate",
            "render",
            "--scene",
            &scene("pool_oblique"),
            "--technique",
            "pool-convolution",
            "--precision",
            precision,
            "--dump",
            "all",
            "--out",
            &out.display().to_string(),
        ]);
        assert_clean(&r);
        for f in [
            "final.exr",
            "final.png",
            "receiver.exr",
            "receiver.png",
            "timings.json",
            "height_field.exr",
            "pass6_convolutions.exr",
        ] {
            assert!(out.join(f).is_file(), "{precision}: {f} missing\n{}", r.describe());
        }
        // Only the pool's buffers: no shadow map, no photon buffer.
        assert!(!out.join("shadow_map.exr").exists() && !out.join("photon_buffer.exr").exists());
        let img = read_exr(&out.join("receiver.exr")).expect("receiver.exr");
        assert_eq!((img.width, img.height), (256, 256));
        let timings: Value = serde_json::from_str(&std::fs::read_to_string(out.join("timings.json")).expect("timings"))
            .expect("timings.json");
        let passes: Vec<&str> =
            timings["passes"].as_array().expect("passes").iter().filter_map(|p| p["name"].as_str()).collect();
        for p in ["pool.height_field", "pool.pass1_normals", "pool.pass6_convolution", "pool.receiver", "pool.view"] {
            assert!(passes.contains(&p), "{precision}: no pass {p}: {passes:?}");
        }
    }
}

#[test]
fn the_reference_is_the_f64_render_and_direct_eq_2_differs_where_the_waves_tilt() {
    let render = scratch("pool-render-f64");
    let r = causticlab(&[
        "render",
        "--scene",
        &scene("pool_overhead"),
        "--precision",
        "f64",
        "--dump",
        "receiver",
        "--out",
        &render.display().to_string(),
    ]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    let conv = scratch("pool-ref");
    let r = causticlab(&["reference", "--scene", &scene("pool_overhead"), "--out", &conv.display().to_string()]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    let direct = scratch("pool-ref-direct");
    let r = causticlab(&[
        "reference",
        "--scene",
        &scene("pool_overhead"),
        "--direct",
        "--out",
        &direct.display().to_string(),
    ]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    let record: Value =
        serde_json::from_str(&std::fs::read_to_string(direct.join("reference.json")).expect("json")).expect("json");
    assert_eq!(record["method"].as_str(), Some("Eq. 2, direct"));
    let (a, _) = receiver(&render);
    let (b, _) = receiver(&conv);
    let (c, _) = receiver(&direct);
    assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-6), "the f64 render is the reference");
    // Far from the wave both are flat water; on it they differ (the first-order expansion).
    assert!((c[10] - 1.0).abs() < 1e-9 && (b[10] - 1.0).abs() < 1e-9);
    assert!(b.iter().zip(&c).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) > 0.1);
    // compare reads them like any receiver map.
    let r = causticlab(&[
        "compare",
        &conv.join("receiver.exr").display().to_string(),
        &direct.join("receiver.exr").display().to_string(),
    ]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
}

#[test]
fn bad_pool_input_exits_2_naming_what_is_wrong() {
    let out = scratch("pool-bad");
    let o = out.display().to_string();
    // pool-convolution on a mesh scene, a mesh technique on a pool scene.
    let r =
        causticlab(&["render", "--scene", &scene("sphere_on_plane"), "--technique", "pool-convolution", "--out", &o]);
    assert_input_error(&r, &["sphere_on_plane.toml", "pool-convolution", "[pool]"]);
    let r = causticlab(&["render", "--scene", &scene("pool_overhead"), "--technique", "wd-points", "--out", &o]);
    assert_input_error(&r, &["pool_overhead.toml", "pool-convolution", "wd-points"]);
    // The pool's settings belong to pool-convolution; values are checked.
    let r = causticlab(&["render", "--scene", &scene("sphere_on_plane"), "--precision", "unorm8", "--out", &o]);
    assert_input_error(&r, &["precision", "pool-convolution"]);
    let r = causticlab(&["render", "--scene", &scene("pool_overhead"), "--kernel", "6", "--out", &o]);
    assert_input_error(&r, &["--kernel", "odd"]);
    let r = causticlab(&["render", "--scene", &scene("pool_overhead"), "--precision", "fp16", "--out", &o]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    assert!(r.stderr.contains("unorm8") && r.stderr.contains("float"), "{}", r.describe());
    // A dump of another technique.
    let r = causticlab(&["render", "--scene", &scene("pool_overhead"), "--dump", "shadow_map", "--out", &o]);
    assert_input_error(&r, &["shadow_map", "pool-convolution"]);
    // reference's pool flags on a mesh scene.
    let r = causticlab(&["reference", "--scene", &scene("sphere_on_plane"), "--direct", "--out", &o]);
    assert_input_error(&r, &["--direct", "pool"]);
    // --grid names itself (it once accepted 16-63 and the error named --photons); --threads is bounded.
    let r = causticlab(&["reference", "--scene", &scene("pool_overhead"), "--grid", "32", "--out", &o]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    assert!(r.stderr.contains("--grid") && r.stderr.contains("64..=4096"), "{}", r.describe());
    let r = causticlab(&["reference", "--scene", &scene("pool_overhead"), "--threads", "2000", "--out", &o]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    assert!(r.stderr.contains("--threads") && r.stderr.contains("1024"), "{}", r.describe());
    // An unknown key in [pool].
    let bad = out.join("bad.toml");
    let text = std::fs::read_to_string(workspace().join("scenes/pool_overhead.toml")).expect("scene");
    std::fs::write(&bad, text.replace("depth = 0.3", "depth = 0.3\ndeepness = 2")).expect("write");
    let r =
        causticlab(&["render", "--scene", &bad.display().to_string(), "--out", &out.join("x").display().to_string()]);
    assert_input_error(&r, &["bad.toml", "pool.deepness"]);
    assert!(!out.join("x").exists(), "no output on bad input");
}
