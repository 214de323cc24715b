//! Shards that merge into the unsharded table, and a run that fails half-way leaving the
//! previous table untouched.

mod common;

use common::bench::*;
use common::{causticlab, scratch, workspace};
use serde_json::Value;

#[test]
fn shards_merge_into_the_unsharded_table() {
    let dir = scratch("bench-shards");
    let cfg = config_file(&dir, "small.toml", SMALL);
    let whole = dir.join("whole");
    let sharded = dir.join("sharded");
    let r = bench(&[cfg.as_os_str(), "--results".as_ref(), whole.as_os_str()]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    let mut parts = vec![];
    for i in 1..=3 {
        let shard = format!("{i}/3");
        let r =
            bench(&[cfg.as_os_str(), "--shard".as_ref(), shard.as_ref(), "--results".as_ref(), sharded.as_os_str()]);
        assert_eq!(r.code, Some(0), "{}", r.describe());
        let part = device_dir(&sharded).join("parts").join(format!("small.shard-{i}-of-3.json"));
        assert!(part.is_file(), "{}", r.describe());
        parts.push(part);
    }
    // A shard alone is not a table.
    assert!(!device_dir(&sharded).join("small.md").exists(), "a shard wrote the full table");
    // Missing and duplicated cells are refused.
    let r = bench(&["merge".as_ref(), parts[0].as_os_str(), "--results".as_ref(), sharded.as_os_str()]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    assert!(r.stderr.contains("missing"), "{}", r.describe());
    // With --partial (a GPU suite cut off by its budget) they are marked `not run` instead.
    let partial = dir.join("partial");
    let r = bench(&[
        "merge".as_ref(),
        "--partial".as_ref(),
        parts[0].as_os_str(),
        "--results".as_ref(),
        partial.as_os_str(),
    ]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    let shard1 = json(&parts[0]);
    let have: Vec<u64> =
        shard1["cells"].as_array().expect("cells").iter().filter_map(|c| c["cell"]["index"].as_u64()).collect();
    let merged = json(&device_dir(&partial).join("small.json.gz"));
    let not_run: Vec<u64> =
        merged["run"]["not_run"].as_array().expect("run.not_run").iter().filter_map(|i| i.as_u64()).collect();
    assert_eq!(have.len() + not_run.len(), 8, "{have:?} {not_run:?}");
    assert!(not_run.iter().all(|i| !have.contains(i) && *i % 3 != 0), "shard 1/3 has the cells 0, 3, 6: {not_run:?}");
    let md = std::fs::read_to_string(device_dir(&partial).join("small.md")).expect("small.md");
    assert!(md.contains(&format!("**Partial table: {} of 8 cells were not run", not_run.len())), "{md}");
    let rows_not_run = md.lines().filter(|l| l.starts_with('|') && l.contains("not run")).count();
    assert!(rows_not_run > 0, "no table entry reads `not run`:\n{md}");
    let r = bench(&[
        "merge".as_ref(),
        parts[0].as_os_str(),
        parts[0].as_os_str(),
        "--results".as_ref(),
        sharded.as_os_str(),
    ]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    let mut args: Vec<&std::ffi::OsStr> = vec!["merge".as_ref()];
    args.extend(parts.iter().map(|p| p.as_os_str()));
    args.extend(["--results".as_ref(), sharded.as_os_str()]);
    let r = bench(&args);
    assert_eq!(r.code, Some(0), "{}", r.describe());

    let (a, b) = (device_dir(&whole), device_dir(&sharded));
    assert_eq!(csv_without_timings(&a.join("small.csv")), csv_without_timings(&b.join("small.csv")));
    let (ja, jb) = (json(&a.join("small.json.gz")), json(&b.join("small.json.gz")));
    let cells = |j: &Value| j["cells"].as_array().cloned().unwrap_or_default();
    assert_eq!(cells(&ja).len(), 8);
    for (x, y) in cells(&ja).iter().zip(cells(&jb).iter()) {
        assert_eq!(x["cell"], y["cell"]);
        assert_eq!(x["caustics"], y["caustics"]);
        for m in ["photons", "splats"] {
            assert_eq!(x["metrics"][m], y["metrics"][m], "{m} of {}", x["cell"]);
        }
    }
    // Counts are exact: 80² photons per light, splats padded to whole instances of 1024.
    let first = &cells(&ja)[0];
    assert_eq!(metric(first, "photons"), Some(6400.0));
    assert_eq!(metric(first, "splats"), Some(7168.0));

    // A complete result merged alone re-renders its table: the same JSON, CSV and Markdown,
    // byte for byte (floats re-read exactly), which is how a report change regenerates tables;
    // but for the Markdown's Regenerate line, which names the results folder it is written under.
    let again = dir.join("again");
    let r = bench(&["merge".as_ref(), a.join("small.json.gz").as_os_str(), "--results".as_ref(), again.as_os_str()]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    for f in ["small.json.gz", "small.csv", "small.md"] {
        let read = |d: &std::path::Path| std::fs::read(d.join(f)).unwrap_or_default();
        let (first, second) = (read(&a), read(&device_dir(&again)));
        assert!(!first.is_empty() && !second.is_empty(), "{f} missing");
        if f.ends_with(".md") {
            let (first, second) = (String::from_utf8_lossy(&first), String::from_utf8_lossy(&second));
            let regenerate = |md: &str, root: &std::path::Path| {
                let line = md.lines().find(|l| l.starts_with("Regenerate:")).unwrap_or_default().to_string();
                assert!(line.contains(&format!("--results {}`", root.display())), "{line}");
                md.replace(&line, "")
            };
            assert_eq!(regenerate(&first, &whole), regenerate(&second, &again), "{f} changed when re-merged");
        } else {
            assert!(first == second, "{f} changed when re-merged");
        }
    }
}

#[test]
fn an_interrupted_run_leaves_the_previous_table_untouched() {
    use std::io::BufRead;
    let dir = scratch("bench-atomic");
    let root = dir.join("results");
    // A complete earlier table to protect.
    let cfg = config_file(&dir, "small.toml", SMALL);
    let r = bench(&[cfg.as_os_str(), "--results".as_ref(), root.as_os_str()]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    let dev = device_dir(&root);
    let files = ["small.md", "small.json.gz", "small.csv", "small.svg", "small.png"];
    let before: Vec<Vec<u8>> = files.iter().map(|f| std::fs::read(dev.join(f)).expect("table file")).collect();

    // The same sweep again, killed (SIGKILL: no chance to clean up) once two cells are done (the
    // six left take seconds: the kill comes first).
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_causticlab"))
        .args(["bench".as_ref(), cfg.as_os_str(), "--results".as_ref(), root.as_os_str()])
        .current_dir(workspace())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spawning causticlab");
    let stderr = child.stderr.take().expect("stderr");
    let mut seen = String::new();
    for line in std::io::BufReader::new(stderr).lines() {
        let line = line.unwrap_or_default();
        seen.push_str(&line);
        seen.push('\n');
        if line.contains("2/8 cells") {
            break;
        }
    }
    child.kill().expect("killing the run");
    let status = child.wait().expect("waiting for the killed run");
    assert!(!status.success(), "the run finished before it was killed:\n{seen}");
    assert!(seen.contains("2/8 cells"), "never saw the third cell start:\n{seen}");
    for (f, old) in files.iter().zip(&before) {
        assert_eq!(&std::fs::read(dev.join(f)).expect("table file"), old, "{f} was touched by an interrupted run");
    }
    let leftovers: Vec<_> = std::fs::read_dir(&dev)
        .expect("dir")
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");

    // A scene that cannot load fails before any cell runs, naming the missing model.
    let broken = dir.join("configs").join("broken_scene.toml");
    std::fs::write(
        &broken,
        "[camera]\neye = [0, 2, 4]\ntarget = [0, 0, 0]\nfov_y = 40.0\nresolution = [64, 64]\n[[lights]]\ntype = \"point\"\n\
         position = [0, 5, 0]\nintensity = [10, 10, 10]\n[materials.glass]\ntype = \"refractive\"\nior = 1.5\n\
         [[objects]]\nname = \"x\"\nshape = \"obj\"\nfile = \"no_such_model.obj\"\nmaterial = \"glass\"\n",
    )
    .expect("scene");
    let bad = config_file(&dir, "small.toml", &SMALL.replace("SCENES/sphere_oblique.toml", "broken_scene.toml"));
    let r = bench(&[bad.as_os_str(), "--results".as_ref(), root.as_os_str()]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    assert!(r.stderr.contains("no_such_model.obj") && !r.stderr.contains("0/8 cells"), "{}", r.describe());
    // So does a technique the device lacks a feature for (told so with --without-feature).
    let r = causticlab(&[
        "--without-feature".as_ref(),
        "vertex_pipeline_stores_and_atomics".as_ref(),
        "bench".as_ref(),
        config_file(&dir, "small.toml", &SMALL.replace("technique = \"shah\"", "technique = \"shah-vertex\""))
            .as_os_str(),
        "--quick".as_ref(),
        "--results".as_ref(),
        root.as_os_str(),
    ]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    // (No progress line: "0/8 cells" would mean a cell started.)
    assert!(
        r.stderr.contains("vertex_pipeline_stores_and_atomics") && !r.stderr.contains(" cells"),
        "{}",
        r.describe()
    );
    // Timing runs refuse validation and masked features.
    let r =
        causticlab(&["--validate".as_ref(), "bench".as_ref(), cfg.as_os_str(), "--results".as_ref(), root.as_os_str()]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    assert!(r.stderr.contains("--quick"), "{}", r.describe());
    assert_eq!(std::fs::read(dev.join("small.md")).expect("md"), before[0]);
}

#[test]
fn pose_updates_are_timed_and_counted_without_a_timed_frame_metric() {
    // Along an orbit every frame after the first has a pose update: `pose_ms` times each, and the
    // structure counts (which time nothing) still get frames along the path. wd-points builds no
    // acceleration structure, so both counts are 0, not n/a.
    let dir = scratch("bench-poses");
    let text = SMALL
        .replace("[run]", "[run]\nobject_path = \"orbit\"\nperiod_frames = 4")
        .replace("measured_frames = 1", "measured_frames = 3")
        .replace("photons = [80, 128]", "photons = [80]")
        .replace("kind = \"photons_emitted\"", "kind = \"blas_builds\"")
        .replace("kind = \"splats_drawn\"", "kind = \"tlas_builds\"");
    let counts_only = text.replace("kind = \"pass_ms\"\npasses = [\"splat.*\"]", "kind = \"valid_photons\"");
    for (name, cfg_text, timed) in [("counts.toml", &counts_only, false), ("timed.toml", &text, true)] {
        let cfg = config_file(&dir, name, cfg_text);
        let out = dir.join(name);
        let r = bench(&[cfg.as_os_str(), "--results".as_ref(), out.as_os_str()]);
        assert_eq!(r.code, Some(0), "{}", r.describe());
        let json = device_dir(&out).join(name.replace(".toml", ".json.gz"));
        let v: Value = serde_json::from_str(&bench::results::read_text(&json, "table").expect("table")).expect("json");
        for c in v["cells"].as_array().expect("cells") {
            for m in ["photons", "splats"] {
                assert_eq!(c["metrics"][m]["value"].as_f64(), Some(0.0), "{name}: {m} of {}", c["cell"]);
            }
            // Frame 0 is the scene's own pose: a pose update before each measured frame after it
            // (untimed frames keep no times: no pose_ms there).
            let poses = c["pose_ms"].as_array().map_or(0, |p| p.len());
            let frames = c["wall_ms"].as_array().expect("frames").len();
            assert_eq!(poses, if timed { frames - 1 } else { 0 }, "{name}: {frames} frames");
            assert!(!timed || frames >= 3, "{name}: {frames} frames");
        }
    }
}
