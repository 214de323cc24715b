//! The bench's `flip` column end to end: a cell's FLIP is what `causticlab compare` reports of
//! `causticlab render`'s final image of the same settings against `causticlab reference
//! --final`'s, exposures and all. A config with `flip` alone (no receiver-map metric) keeps the
//! scene's receiver map, whose rectangle frames the caustic map: without it the technique's and
//! the reference's caustic maps cover another region, and the numbers differ. `sphere_on_plane`
//! at 64² pixels, the reference at level 0 (a 256² map, 1024² photons).

mod common;

use common::bench::*;
use common::{causticlab, scratch, workspace};

#[test]
fn a_cells_flip_is_compare_of_its_render_against_reference_final() {
    let dir = scratch("bench-flip");
    let original = std::fs::read_to_string(workspace().join("scenes/sphere_on_plane.toml")).expect("the scene");
    assert!(original.contains("resolution = [512, 512]"), "the camera line moved");
    let scene = dir.join("tiny.toml");
    std::fs::write(&scene, original.replace("resolution = [512, 512]", "resolution = [64, 64]")).expect("a scene");
    let config = format!(
        r#"
[table]
paper = "test"
number = "FLIP"
caption = "flip against compare"

[run]
warmup_frames = 0
measured_frames = 1

[matrix]
scenes = ["{}"]
photons = [64]

[[technique]]
label = "wd-points"
technique = "wd-points"
fresnel = false

[[metric]]
label = "FLIP"
kind = "flip"

[layout]
rows = ["photons"]
columns = ["technique", "metric"]

[quality]
final_level = 0
"#,
        scene.display()
    );
    let cfg = config_file(&dir, "flip.toml", &config);
    let root = dir.join("results");
    // Not quick (a quick run's reference is a smaller one than `reference --final` makes), so
    // without validation (refused outside quick runs); render and reference run with it.
    let r = causticlab(&["bench".as_ref(), cfg.as_os_str(), "--results".as_ref(), root.as_os_str()]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    let results = json(&device_dir(&root).join("flip.json.gz"));
    let cell = &results["cells"][0];
    let bench = metric(cell, "FLIP").expect("a FLIP");

    let (render, reference) = (dir.join("render"), dir.join("reference"));
    let s = scene.as_os_str();
    for args in [
        vec![
            "--validate".as_ref(),
            "render".as_ref(),
            "--scene".as_ref(),
            s,
            "--technique".as_ref(),
            "wd-points".as_ref(),
        ]
        .into_iter()
        .chain(["--photons", "64", "--fresnel", "false", "--out"].map(std::ffi::OsStr::new))
        .chain([render.as_os_str()])
        .collect::<Vec<&std::ffi::OsStr>>(),
        ["--validate", "reference", "--final", "--level", "0", "--fresnel", "false", "--scene"]
            .map(std::ffi::OsStr::new)
            .into_iter()
            .chain([s, "--out".as_ref(), reference.as_os_str()])
            .collect(),
    ] {
        assert_clean(&causticlab(&args));
    }
    let c = causticlab(&[
        "compare".as_ref(),
        render.join("final.exr").as_os_str(),
        reference.join("final.exr").as_os_str(),
        "--json".as_ref(),
    ]);
    assert_eq!(c.code, Some(0), "{}", c.describe());
    let compared: serde_json::Value = serde_json::from_str(&c.stdout).expect("compare's JSON");
    let flip = &compared["flip"];
    let want = flip["mean"].as_f64().expect("compare's FLIP");
    println!("bench FLIP {bench}, compare {want}");
    // The JSON keeps 9 significant digits.
    assert!((bench - want).abs() <= 1e-8 * want, "bench {bench}, compare {want}");
    let record = &cell["final_flip"];
    for key in ["start_exposure", "stop_exposure", "ppd"] {
        let (a, b) = (record[key].as_f64().unwrap_or(f64::NAN), flip[key].as_f64().unwrap_or(f64::NAN));
        assert!((a - b).abs() <= 1e-7 * b.abs().max(1.0), "{key}: bench {a}, compare {b}");
    }
    assert_eq!((record["width"].as_u64(), record["height"].as_u64()), (Some(64), Some(64)));
    assert_eq!(record["reference"]["level"].as_u64(), Some(0));
}
