//! Progressive accumulation's curves on the front (issue 53 item 5, `[front.curves]`), from
//! synthetic tables: a front written beside a table of curves copies them into its JSON, says per
//! error level when each curve first reaches it, and draws them; a table of curves that measures
//! something else (another reference, scene file, output size, lights, lighting, Fresnel
//! setting, device, validation, path, timed passes, or a busy cell) is
//! named in the front's table with the reason, and nothing is drawn; `bench explain` draws the
//! curves of a front measured before its config asked for them; and the config's keys are
//! checked.

mod common;
use bench::config::Config;
use bench::progressive::Point;
use bench::results::Results;
use common::{cell, exact, loaded_config, results};
use std::path::Path;

const FRONT: &str = r#"
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
label = "Caustic map"
kind = "pass_host_ms"
passes = ["receiver_positions.*", "photon_trace.*", "splat*"]

[[metric]]
label = "rel. RMSE"
kind = "rel_rmse"

[layout]
rows = ["technique"]
columns = ["photons", "metric"]

[quality]
reference_photons = 65536

[front]
x = "Caustic map"
y = "rel. RMSE"
levels = [0.5, 0.2, 0.1, 0.05]
"#;

const CURVES: &str = "\n[front.curves]\ntable = \"progressive\"\nx = \"Caustic map\"\ny = \"rel. RMSE\"\n";

const PROGRESSIVE: &str = r#"
[table]
paper = "Synthetic"
number = "T"
caption = "Synthetic curves."

[matrix]
scenes = ["../scenes/sphere_on_plane.toml"]
photons = [256]

[[technique]]
label = "progressive"
technique = "photon-trace"
progressive = true

[[metric]]
label = "16 frames"
kind = "progressive_rel_rmse"
frames = 16
passes = ["receiver_positions.*", "photon_trace.*", "splat*"]

[layout]
rows = ["technique"]
columns = ["metric"]

[quality]
reference_photons = 65536
"#;

/// The front: cheap 256² (2 ms, 0.30) and sharp 512² (8 ms, 0.12), neither below 0.1.
fn front(text: &str) -> (Config, Results) {
    let config: Config = toml::from_str(text).expect("the front config parses");
    let cells = [("cheap", 0, 256, 2.0, 0.30), ("sharp", 1, 512, 8.0, 0.12)]
        .iter()
        .enumerate()
        .map(|(i, &(label, t, photons, ms, rmse))| {
            let mut c = cell(i, t, label, photons, &[ms; 5]);
            c.metrics.clear();
            c.metrics.insert("Caustic map".into(), exact("pass_host_ms", ms));
            c.metrics.insert("rel. RMSE".into(), exact("rel_rmse", rmse));
            c
        })
        .collect();
    let mut r = results(&config, text, cells);
    r.config.name = "front".into();
    (config, r)
}

/// The curve: 10 ms a frame; below 0.2 at frame 3 (30 ms), below 0.1 first at frame 16 (160 ms),
/// never below 0.05.
fn curve_points() -> Vec<Point> {
    [(1, 0.30), (2, 0.21), (3, 0.17), (4, 0.15), (8, 0.105), (16, 0.08)]
        .iter()
        .map(|&(frames, rel_rmse)| Point { frames, ms: 10.0 * f64::from(frames), rel_rmse })
        .collect()
}

fn progressive(text: &str) -> Results {
    let config: Config = toml::from_str(text).expect("the curves' config parses");
    let mut c = cell(0, 0, "progressive", 256, &[1.0; 3]);
    c.progressive = curve_points();
    let mut r = results(&config, text, vec![c]);
    r.config.name = "progressive".into();
    r
}

/// Writes `curves` (if any) and then the front into `root`'s device folder; the front's table.
fn write(root: &Path, front_text: &str, curves: Option<&Results>) -> (Results, String) {
    let (config, r) = front(front_text);
    let dir = bench::run::device_dir(root, &r);
    if let Some(t) = curves {
        std::fs::create_dir_all(&dir).expect("the device folder");
        let gz = bench::results::gzip(&bench::results::to_json(t).expect("json")).expect("gzip");
        std::fs::write(dir.join("progressive.json.gz"), gz).expect("write");
    }
    let out = bench::run::write_table(&config, &r, &dir, root).expect("front written");
    let written = bench::results::read(&dir.join("front.json.gz"), "front").expect("the front's json");
    (written, out.markdown)
}

#[test]
fn the_front_says_when_each_curve_reaches_each_level_and_draws_it() {
    let root = caustics::scratch::ScratchDir::new("causticlab", "front-curves");
    let (r, md) = write(&root, &format!("{FRONT}{CURVES}"), Some(&progressive(PROGRESSIVE)));
    let fc = r.front_curves.as_ref().expect("the curves kept in the front's JSON");
    assert_eq!(fc.missing, None);
    assert_eq!(fc.curves.len(), 1);
    assert_eq!(fc.curves[0].points, curve_points());
    assert_eq!(fc.curves[0].scene, "sphere_on_plane");
    // Neither cell reaches 0.1; the curve does at its 16th frame, 160 ms.
    for row in [
        "| 0.5 | 10.0 (1 frame, 0.3000) |",
        "| 0.2 | 30.0 (3 frames, 0.1700) |",
        "| 0.1 | 160.0 (16 frames, 0.0800) |",
        "| 0.05 | (not reached) |",
        "| (end) | 160.0 (16 frames, 0.0800) |",
        "| 0.1 | (none reaches it) | | | |",
    ] {
        assert!(md.contains(row), "no `{row}` in\n{md}");
    }
    assert!(md.contains("Progressive accumulation (`progressive`, commit"), "{md}");
    // The plot names the curves' table and technique in its legend, and draws the line in the
    // first curve colour (black), which no technique has.
    let (config, _) = front(&format!("{FRONT}{CURVES}"));
    let plot = bench::front_plot::render(&config, &r, config.front.as_ref().expect("a front")).expect("the plot");
    assert!(plot.svg.contains("curves of progressive"), "no legend entry");
    let line = "stroke=\"#000000\" stroke-width=\"2\"";
    assert!(plot.svg.contains(line), "no curve drawn");
    // The same front without the curves draws no black line.
    let mut bare = r.clone();
    bare.front_curves = None;
    let plot = bench::front_plot::render(&config, &bare, config.front.as_ref().expect("a front")).expect("the plot");
    assert!(!plot.svg.contains(line) && !plot.svg.contains("curves of"), "a curve drawn without one");
}

/// A change to the curves' table.
type Change = Box<dyn Fn(&mut Results)>;

#[test]
fn a_table_that_measures_something_else_is_named_and_not_drawn() {
    let cases: Vec<(&str, Change, &str)> = vec![
        (
            "reference",
            Box::new(|r| r.config.toml = r.config.toml.replace("65536", "262144")),
            "reference of 262144 photons",
        ),
        ("resolution", Box::new(|r| r.cells[0].cell.resolution = [64, 64]), "has another output 64x64 than"),
        (
            "fresnel",
            Box::new(|r| r.cells[0].caustics = serde_json::json!({ "fresnel": true })),
            "`progressive` has another fresnel true than the front's `cheap` cell",
        ),
        (
            "scene file",
            Box::new(|r| r.cells[0].cell.scene = "../elsewhere/sphere_on_plane.toml".into()),
            "another scene file ../elsewhere/sphere_on_plane.toml",
        ),
        ("lights", Box::new(|r| r.cells[0].cell.lights = 2), "another lights 2 with dynamic lighting"),
        ("lighting", Box::new(|r| r.cells[0].cell.lighting = "static".into()), "with static lighting"),
        ("busy", Box::new(|r| r.cells[0].busy = true), "its `progressive` cell ran on a busy machine"),
        ("validation", Box::new(|r| r.run.validation = true), "its run had validation on, the front's off"),
        ("paths", Box::new(|r| r.run.light_path = "orbit".into()), "its light, camera and object paths are [\"orbit\""),
        ("device", Box::new(|r| r.meta.device_slug = "another-gpu".into()), "measured on another-gpu"),
        ("quick", Box::new(|r| r.run.quick = true), "(--quick)"),
        (
            "passes",
            Box::new(|r| r.config.toml = r.config.toml.replace("\"splat*\"]", "\"splat*\", \"composite\"]")),
            "passes `composite`, which `Caustic map` does not name",
        ),
        (
            "scene",
            Box::new(|r| r.cells[0].cell.scene = "../scenes/ring_cardioid.toml".into()),
            "no curve of a scene the front has",
        ),
    ];
    for (name, change, needle) in cases {
        let root = caustics::scratch::ScratchDir::new("causticlab", &format!("front-curves-{name}"));
        let mut t = progressive(PROGRESSIVE);
        change(&mut t);
        let (r, md) = write(&root, &format!("{FRONT}{CURVES}"), Some(&t));
        let fc = r.front_curves.as_ref().expect("the outcome kept");
        let why = fc.missing.as_deref().unwrap_or_else(|| panic!("{name}: drawn"));
        assert!(why.contains(needle), "{name}: {why}");
        assert!(fc.curves.is_empty(), "{name}");
        assert!(md.contains("No progressive curves drawn:") && md.contains(needle), "{name}: {md}");
        assert!(!md.contains("Progressive accumulation ("), "{name}: a curve's table printed");
    }
    // No table of curves in the folder, or a technique it does not have.
    let root = caustics::scratch::ScratchDir::new("causticlab", "front-curves-none");
    let (r, _) = write(&root, &format!("{FRONT}{CURVES}"), None);
    assert!(r.front_curves.and_then(|c| c.missing).is_some_and(|m| m.contains("no table `progressive`")));
    let named = format!("{FRONT}{CURVES}techniques = [\"alpha 1\"]\n");
    let (r, _) = write(&root, &named, Some(&progressive(PROGRESSIVE)));
    assert!(r.front_curves.and_then(|c| c.missing).is_some_and(|m| m.contains("no technique `alpha 1`")));
    // A named technique is drawn, the other one not.
    let mut two = progressive(PROGRESSIVE);
    let mut other = two.cells[0].clone();
    other.cell.index = 1;
    other.cell.technique = 1;
    other.cell.technique_label = "alpha 1".into();
    two.cells.push(other);
    two.config.toml = PROGRESSIVE
        .replace("[[metric]]", "[[technique]]\nlabel = \"alpha 1\"\ntechnique = \"photon-trace\"\n\n[[metric]]");
    let (r, md) = write(&root, &named, Some(&two));
    let drawn: Vec<String> = r.front_curves.expect("curves").curves.iter().map(|c| c.technique.clone()).collect();
    assert_eq!(drawn, ["alpha 1"]);
    assert!(md.contains("| rel. RMSE at most | alpha 1 |"), "{md}");
    // A config without [front.curves] keeps nothing.
    let (r, md) = write(&root, FRONT, Some(&progressive(PROGRESSIVE)));
    assert!(r.front_curves.is_none() && !md.contains("Progressive accumulation"));
}

#[test]
fn bench_explain_draws_the_curves_of_a_front_measured_before_it_asked_for_them() {
    let root = caustics::scratch::ScratchDir::new("causticlab", "front-curves-explain");
    let (before, _) = write(&root, FRONT, Some(&progressive(PROGRESSIVE)));
    assert!(before.front_curves.is_none());
    let dir = bench::run::device_dir(&root, &before);
    let json = dir.join("front.json.gz");
    let mut loaded = loaded_config(&root, &format!("{FRONT}{CURVES}"));
    loaded.name = "front".into();
    let out = bench::explain::explain(&loaded, &json, &root, "abc1234").expect("a new [front] is explained");
    assert!(out.markdown.contains("| 0.1 | 160.0 (16 frames, 0.0800) |"), "{}", out.markdown);
    let after = bench::results::read(&json, "front").expect("json");
    assert_eq!(after.cells, before.cells, "no cell changed");
    assert!(after.front_curves.is_some_and(|c| c.curves.len() == 1));
    // Anything but [front] changed is still refused.
    let mut other =
        loaded_config(&root, &format!("{FRONT}{CURVES}").replace("photons = [256, 512]", "photons = [256]"));
    other.name = "front".into();
    let Err(err) = bench::explain::explain(&other, &json, &root, "abc1234") else { panic!("a new matrix accepted") };
    assert!(format!("{err:#}").contains("run the table again"), "{err:#}");
}

#[test]
fn front_curves_must_name_a_front_axis_of_the_right_kind() {
    let dir = caustics::scratch::ScratchDir::new("causticlab", "front-curves-keys");
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let with =
        |curves: &str| format!("{FRONT}\n[front.curves]\n{curves}").replace("../scenes", &scenes.display().to_string());
    // A second error metric, so that front.curves.y can name one of front.y of the wrong kind.
    let two_errors = |curves: &str| {
        with(curves).replace(
            "[front]\nx = \"Caustic map\"\ny = \"rel. RMSE\"\nlevels = [0.5, 0.2, 0.1, 0.05]",
            "[[metric]]\nlabel = \"flux\"\nkind = \"flux_ratio\"\n\n[front]\nx = \"Caustic map\"\ny = [\"rel. RMSE\", \"flux\"]\nlevels = { \"rel. RMSE\" = [0.2], \"flux\" = [1.1] }",
        )
    };
    for (name, bad, needle) in [
        (
            "x.toml",
            with("table = \"progressive\"\nx = \"Frame\"\ny = \"rel. RMSE\"\n"),
            "key `front.curves.x`: `Frame` is not one of front.x",
        ),
        (
            "y.toml",
            two_errors("table = \"progressive\"\nx = \"Caustic map\"\ny = \"flux\"\n"),
            "key `front.curves.y`: `flux` is not a `rel_rmse` metric",
        ),
        (
            "kind.toml",
            with("table = \"progressive\"\nx = \"Caustic map\"\ny = \"rel. RMSE\"\n")
                .replace("kind = \"pass_host_ms\"", "kind = \"pass_ms\""),
            "key `front.curves.x`: `Caustic map` is not a `pass_host_ms` metric",
        ),
        (
            "table.toml",
            with("table = \"../progressive.json\"\nx = \"Caustic map\"\ny = \"rel. RMSE\"\n"),
            "key `front.curves.table`",
        ),
        (
            "unknown.toml",
            with("table = \"progressive\"\nx = \"Caustic map\"\ny = \"rel. RMSE\"\ncolour = \"red\"\n"),
            "colour",
        ),
    ] {
        let msg = common::load_error(&dir.join(name), &bad);
        assert!(msg.contains(needle), "{name}: {msg}");
    }
    let ok = dir.join("ok.toml");
    std::fs::write(&ok, format!("{FRONT}{CURVES}").replace("../scenes", &scenes.display().to_string()))
        .expect("a config");
    bench::LoadedConfig::load(&ok).expect("a front with curves");
}

#[test]
fn the_shipped_front_and_its_curves_table_measure_the_same_thing() {
    // F1 draws T4's curves: the two configs must keep the same reference, output sizes, Fresnel
    // setting and timed passes, full size and --quick, or the front would draw none.
    let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../bench_configs");
    let f1 = bench::LoadedConfig::load(&configs.join("front.toml")).expect("front.toml");
    let spec = f1.config.front.as_ref().and_then(|f| f.curves.clone()).expect("front.toml has [front.curves]");
    let curves = bench::LoadedConfig::load(&configs.join(format!("{}.toml", spec.table))).expect("the curves' config");
    for quick in [false, true] {
        bench::front_curves::agree(&f1.config, &spec, &curves.config, quick)
            .unwrap_or_else(|why| panic!("quick {quick}: {why}"));
    }
    // What agree holds, each broken in turn.
    let (c, _) = front(&format!("{FRONT}{CURVES}"));
    let spec = c.front.as_ref().and_then(|f| f.curves.clone()).expect("curves");
    let other = |text: &str| -> Config { toml::from_str(text).expect("parses") };
    bench::front_curves::agree(&c, &spec, &other(PROGRESSIVE), false).expect("the synthetic pair agrees");
    for (name, text, needle) in [
        (
            "fresnel",
            PROGRESSIVE.replace("progressive = true\n", "progressive = true\nfresnel = false\n"),
            "`progressive` has fresnel = false, the front's `cheap` fresnel = true",
        ),
        (
            "resolution",
            PROGRESSIVE.replace("photons = [256]\n", "photons = [256]\nresolution = [[64, 64]]\n"),
            "its output sizes are [[64, 64]]",
        ),
        (
            "reference",
            PROGRESSIVE.replace("reference_photons = 65536", "reference_photons = 65537"),
            "reference of 65537 photons",
        ),
        ("scenes", PROGRESSIVE.replace("sphere_on_plane", "ring_cardioid"), "no curve of a scene the front has"),
        (
            "whole frames",
            PROGRESSIVE.replace("passes = [\"receiver_positions.*\", \"photon_trace.*\", \"splat*\"]\n", ""),
            "time whole frames",
        ),
    ] {
        let why = bench::front_curves::agree(&c, &spec, &other(&text), false)
            .err()
            .unwrap_or_else(|| panic!("{name}: agreed"));
        assert!(why.contains(needle), "{name}: {why}");
    }
    // Under --quick the [quick] reference and output sizes are compared.
    let quick_ref = format!("{PROGRESSIVE}\n[quick]\nreference_photons = 4096\n");
    bench::front_curves::agree(&c, &spec, &other(&quick_ref), false).expect("the full-size reference agrees");
    let why = bench::front_curves::agree(&c, &spec, &other(&quick_ref), true).expect_err("the quick one differs");
    assert!(why.contains("reference of 4096 photons"), "{why}");
}
