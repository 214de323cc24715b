//! Helpers of the `causticlab bench` tests (`tests/bench_*.rs`): quick runs of a shipped
//! config, small configs of their own, and reading what a run wrote.

use super::{causticlab, scratch, workspace, Run, Scratch};
use serde_json::Value;
use std::path::{Path, PathBuf};

pub fn assert_clean(r: &Run) {
    assert_eq!(r.code, Some(0), "{}", r.describe());
    assert!(!r.stderr.contains("[validation"), "validation messages:\n{}", r.describe());
    assert!(r.stderr.contains("validation: no warnings or errors reported"), "{}", r.describe());
}

/// The one device folder under `root` (the run's device slug).
pub fn device_dir(root: &Path) -> PathBuf {
    let dirs: Vec<PathBuf> = std::fs::read_dir(root)
        .expect("results folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    assert_eq!(dirs.len(), 1, "expected one device folder in {}: {dirs:?}", root.display());
    dirs[0].clone()
}

pub fn json(path: &Path) -> Value {
    let text = bench::results::read_text(path, "table").unwrap_or_else(|e| panic!("reading {}: {e:#}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("parsing {}: {e}", path.display()))
}

pub fn quick_run(config: &str) -> (Scratch, Value) {
    let root = scratch("bench-quick");
    let cfg = workspace().join("bench_configs").join(config);
    let r = causticlab(&[
        "--validate".as_ref(),
        "bench".as_ref(),
        cfg.as_os_str(),
        "--quick".as_ref(),
        "--results".as_ref(),
        root.as_os_str(),
    ]);
    assert_clean(&r);
    let dir = device_dir(&root).join("quick");
    let stem = config.trim_end_matches(".toml");
    for ext in ["md", "csv", "json.gz", "svg", "png"] {
        let f = dir.join(format!("{stem}.{ext}"));
        assert!(f.is_file(), "{} missing\n{}", f.display(), r.describe());
    }
    assert!(root.join("README.md").is_file(), "results index missing");
    let results = json(&dir.join(format!("{stem}.json.gz")));
    let cells = results["cells"].as_array().expect("cells").len();
    assert_eq!(results["run"]["total_cells"].as_u64(), Some(cells as u64), "a quick run measures every cell");
    assert!(results["run"]["quick"].as_bool() == Some(true));
    // One CSV row per cell and metric, plus the header.
    let csv = std::fs::read_to_string(dir.join(format!("{stem}.csv"))).expect("csv");
    let metrics = results["cells"][0]["metrics"].as_object().expect("metrics").len();
    assert_eq!(csv.lines().count(), 1 + cells * metrics, "{csv}");
    let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).expect("svg");
    assert!(svg.starts_with("<svg") && svg.contains("<polyline"), "plot without lines");
    let rel = dir.strip_prefix(&*root).expect("the device folder is in the results folder").to_path_buf();
    (root.within(rel), results)
}

pub fn metric(cell: &Value, label: &str) -> Option<f64> {
    cell["metrics"][label]["value"].as_f64()
}

/// Writes `text` as a config next to the shipped ones' scenes (paths like ../scenes/x.toml).
pub fn config_file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let cfg_dir = dir.join("configs");
    std::fs::create_dir_all(&cfg_dir).expect("config folder");
    let p = cfg_dir.join(name);
    let scenes = workspace().join("scenes").display().to_string();
    std::fs::write(&p, text.replace("SCENES", &scenes)).expect("writing a config");
    p
}

pub const SMALL: &str = r#"
[table]
paper = "test"
number = "T"
caption = "shard test"

[run]
warmup_frames = 0
measured_frames = 1
# Exactly one frame a cell: the default 1-second budget made a run of these 8 cells take 37 s
# instead of 4 on a 2-core Xeon, and the tests time nothing.
time_budget_s = 0

[matrix]
scenes = ["SCENES/sphere_on_plane.toml", "SCENES/sphere_oblique.toml"]
photons = [80, 128]
resolution = [[64, 64]]

[[technique]]
label = "points"
technique = "wd-points"

[[technique]]
label = "shah"
technique = "shah"

[[metric]]
label = "photons"
kind = "photons_emitted"

[[metric]]
label = "splats"
kind = "splats_drawn"

[[metric]]
label = "splat ms"
kind = "pass_ms"
passes = ["splat.*"]

[layout]
rows = ["scene", "photons"]
columns = ["technique", "metric"]
"#;

pub fn bench(args: &[&std::ffi::OsStr]) -> Run {
    let mut all: Vec<&std::ffi::OsStr> = vec!["bench".as_ref()];
    all.extend(args);
    if args.first().is_some_and(|a| *a != "merge" && *a != "explain") {
        // Tests run side by side: a busy cell is marked, not measured again.
        all.extend([std::ffi::OsStr::new("--busy-retries"), std::ffi::OsStr::new("0")]);
    }
    causticlab(&all)
}

/// CSV rows with the values of timing metrics blanked (device names may hold commas, so the
/// row is cut after its `kind` field rather than split).
pub fn csv_without_timings(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).expect("csv");
    text.lines()
        .map(|l| match l.find(",pass_ms,") {
            Some(i) => format!("{},timing", &l[..i + ",pass_ms".len()]),
            None => l.to_string(),
        })
        .collect()
}

/// The cell of `r` with this technique label and photon count.
pub fn cell<'a>(r: &'a Value, technique: &str, photons: u64) -> &'a Value {
    r["cells"]
        .as_array()
        .expect("cells")
        .iter()
        .find(|c| c["cell"]["technique_label"] == technique && c["cell"]["photons"].as_u64() == Some(photons))
        .unwrap_or_else(|| panic!("no cell {technique} {photons}"))
}

/// Whether `c` is a cell of `scene`: its file name (`sphere_on_plane.toml`) or stem.
pub fn in_scene(c: &Value, scene: &str) -> bool {
    let path = Path::new(c["cell"]["scene"].as_str().unwrap_or_default());
    path.file_name().is_some_and(|n| n == scene) || path.file_stem().is_some_and(|n| n == scene)
}

/// The cell of `scene` (file name or stem), technique label and photon count.
pub fn cell_in<'a>(r: &'a Value, scene: &str, technique: &str, photons: u64) -> &'a Value {
    r["cells"]
        .as_array()
        .expect("cells")
        .iter()
        .find(|c| in_scene(c, scene) && c["cell"]["technique_label"] == technique && c["cell"]["photons"] == photons)
        .unwrap_or_else(|| panic!("no cell {scene} {technique} {photons}"))
}

/// Every file under `dir` (none if it does not exist).
pub fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = vec![];
    if let Ok(entries) = std::fs::read_dir(dir) {
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                out.extend(files_under(&p));
            } else {
                out.push(p);
            }
        }
    }
    out
}
