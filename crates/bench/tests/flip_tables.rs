//! The `flip` metric in the tables (issue 51 item 3), from synthetic cells: the header states
//! the reference final image, the size and the pixels per degree the FLIP was computed at; the
//! front of a config with two error metrics has a section per error metric and time, each with
//! its own levels, and a panel of each error metric side by side in every row of its plot; and
//! a front whose levels do not say which error metric they are for is refused.

mod common;
use bench::config::Config;
use bench::final_flip::{FinalFlip, ReferenceFinal};
use bench::results::Results;
use common::{cell, exact, results};

const CONFIG: &str = r#"
[table]
paper = "Synthetic"
number = "F"
caption = "Synthetic front."

[matrix]
scenes = ["../scenes/sphere_on_plane.toml"]
photons = [256, 512]

[[technique]]
label = "cheap"
technique = "wd-points"

[[technique]]
label = "sharp"
technique = "hcm"

[[metric]]
label = "Gather"
kind = "pass_ms"
passes = ["splat.*"]

[[metric]]
label = "rel. RMSE"
kind = "rel_rmse"

[[metric]]
label = "FLIP"
kind = "flip"

[layout]
rows = ["technique"]
columns = ["photons", "metric"]

[front]
x = "Gather"
y = ["rel. RMSE", "FLIP"]
levels = { "rel. RMSE" = [0.2], "FLIP" = [0.05, 0.02] }
"#;

/// Four cells: `cheap` is faster; at 512² `sharp` has the lower RMSE but `cheap` the lower FLIP.
fn synthetic() -> (Config, Results) {
    let config: Config = toml::from_str(CONFIG).expect("the test config parses");
    let reference =
        ReferenceFinal { level: 1, caustic_map_resolution: 512, photons: 2048, frames: 2, splat_radius: 1.5, seed: 1 };
    let rows = [
        ("cheap", 0, 256, 2.0, 0.30, 0.040),
        ("cheap", 0, 512, 3.0, 0.15, 0.00947),
        ("sharp", 1, 256, 5.0, 0.12, 0.030),
        ("sharp", 1, 512, 8.0, 0.10, 0.025),
    ];
    let cells = rows
        .iter()
        .enumerate()
        .map(|(i, &(label, t, photons, ms, rmse, flip))| {
            let mut c = cell(i, t, label, photons, &[ms; 5]);
            c.metrics.insert("rel. RMSE".into(), exact("rel_rmse", rmse));
            c.metrics.insert("FLIP".into(), exact("flip", flip));
            c.final_flip = Some(FinalFlip {
                mean: flip,
                ppd: caustics::flip::default_ppd(),
                width: 512,
                height: 512,
                start_exposure: -3.0,
                stop_exposure: 2.5,
                exposure_count: 6,
                reference,
            });
            c
        })
        .collect();
    let r = results(&config, CONFIG, cells);
    (config, r)
}

#[test]
fn the_header_states_the_reference_the_size_and_the_pixels_per_degree() {
    let (config, r) = synthetic();
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    let line = md.lines().find(|l| l.starts_with("- **FLIP:**")).unwrap_or_else(|| panic!("no FLIP line in\n{md}"));
    for needle in [
        "level 1: a 512² caustic map of 2 × 2048² exact photons",
        "512×512 pixels (sphere_on_plane)",
        "67.02 pixels per degree",
    ] {
        assert!(line.contains(needle), "`{needle}` not in {line}");
    }
    // The column prints three significant digits (`{:.4}` would print 0.0095).
    assert!(md.contains(" 0.00947 |") && md.contains(" 0.0250 |"), "{md}");
    // Without a FLIP, no line.
    let mut none = r.clone();
    none.cells.iter_mut().for_each(|c| c.final_flip = None);
    assert!(!bench::report::markdown(&config, &none, std::path::Path::new("results")).contains("**FLIP:**"));
}

#[test]
fn the_front_has_a_section_and_a_panel_per_error_metric() {
    let (config, r) = synthetic();
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    let section = |y: &str| -> &str {
        let s = md.split(&format!("## {y} against Gather\n")).nth(1).unwrap_or_else(|| panic!("no {y} front in\n{md}"));
        s.split("\n## ").next().unwrap_or_default()
    };
    // rel. RMSE at most 0.2: cheap 512² (3 ms) is the cheapest; its front runs cheap 256² ->
    // cheap 512² -> sharp 256² -> sharp 512².
    assert!(section("rel. RMSE").contains("| 0.2 | cheap | 512² | 3.00 | 0.1500 |"), "{}", section("rel. RMSE"));
    // FLIP at most 0.02: only cheap 512²; at most 0.05 the cheapest is cheap 256². The FLIP
    // front skips sharp 512², which cheap 512² beats on both.
    let flip = section("FLIP");
    assert!(flip.contains("| 0.05 | cheap | 256² | 2.00 | 0.0400 |"), "{flip}");
    assert!(flip.contains("| 0.02 | cheap | 512² | 3.00 | 0.00947 |"), "{flip}");
    assert!(flip.contains("Front: cheap 256² (2.00, 0.0400) → cheap 512² (3.00, 0.00947)."), "{flip}");
    assert!(!flip.contains("| 0.2 |"), "the RMSE's levels in the FLIP section:\n{flip}");
    // The plot: both panels in the row, the wider drawing.
    let spec = config.front.as_ref().expect("a front");
    let plot = bench::front_plot::render(&config, &r, spec).expect("the plot");
    for caption in ["sphere_on_plane: rel. RMSE against Gather", "sphere_on_plane: FLIP against Gather"] {
        assert!(plot.svg.contains(caption), "no panel `{caption}`");
    }
    assert!(plot.svg.contains("width=\"1800\""), "{}", &plot.svg[..200]);
    assert!(plot.png.starts_with(b"\x89PNG"));
}

#[test]
fn front_levels_must_say_which_error_metric_they_are_for() {
    // Parsed as the bench parses (validation included), from a file beside the shipped scenes.
    let dir = std::env::temp_dir().join(format!("flip-tables-{}", std::process::id()));
    let configs = dir.join("configs");
    std::fs::create_dir_all(&configs).expect("a scratch folder");
    let scenes = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let text = CONFIG.replace("../scenes", &scenes.display().to_string());
    for (name, levels, needle) in [
        ("list.toml", "levels = [0.1]", "give their levels as a table"),
        (
            "unknown.toml",
            "levels = { \"rel. RMSE\" = [0.2], \"FLIP\" = [0.05], \"PSNR\" = [30.0] }",
            "`PSNR` is not one of front.y",
        ),
        ("missing.toml", "levels = { \"rel. RMSE\" = [0.2] }", "levels above 0 for `FLIP`"),
    ] {
        let bad = text.replace("levels = { \"rel. RMSE\" = [0.2], \"FLIP\" = [0.05, 0.02] }", levels);
        let msg = common::load_error(&configs.join(name), &bad);
        assert!(msg.contains("key `front.levels`") && msg.contains(needle), "{name}: {msg}");
    }
    let ok = configs.join("ok.toml");
    std::fs::write(&ok, &text).expect("a config");
    bench::LoadedConfig::load(&ok).expect("levels per error metric");
    let _ = std::fs::remove_dir_all(&dir);
}
