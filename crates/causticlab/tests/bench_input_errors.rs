//! Bad bench input: config errors naming the file, key and line, results over a file, a
//! missing plot font, a metric whose passes match nothing; no partial output.

mod common;

use common::bench::*;
use common::{scratch, workspace};

#[test]
fn config_errors_name_the_file_and_key() {
    let dir = scratch("bench-errors");
    let cases: Vec<(&str, String, &str)> = vec![
        ("syntax.toml", "[table\npaper = 1".into(), "syntax.toml"),
        ("unknown_key.toml", SMALL.replace("[run]", "[run]\nwarmup = 3"), "warmup"),
        ("absurd_photons.toml", SMALL.replace("photons = [80, 128]", "photons = [80, 100000]"), "matrix.photons"),
        ("zero_frames.toml", SMALL.replace("measured_frames = 1", "measured_frames = 0"), "run.measured_frames"),
        ("missing_scene.toml", SMALL.replace("sphere_oblique.toml", "nowhere.toml"), "nowhere.toml"),
        ("bad_kind.toml", SMALL.replace("kind = \"splats_drawn\"", "kind = \"splats\""), "metric[1].kind"),
        ("unplaced_axis.toml", SMALL.replace("rows = [\"scene\", \"photons\"]", "rows = [\"photons\"]"), "scene"),
        (
            "bad_technique.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"quads\""),
            "technique[1].technique",
        ),
        (
            "bad_copy.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"shah-vertex\"\nphoton_copy = \"32-to-32\""),
            "photon_copy",
        ),
        (
            "copy_and_compute_splat.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"shah\"\nphoton_copy = \"32-to-32\"\nsplat_path = \"compute\""),
            "compute splat",
        ),
        (
            "bad_splat_path.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"shah\"\nsplat_path = \"scatter\""),
            "splat_path",
        ),
        (
            "bad_paper.toml",
            format!("{SMALL}\n[[paper]]\nscene = \"sphere_on_plane\"\ntechnique = \"points\"\nphotons = 80\nvalues = {{ bogus = 1.0 }}\n"),
            "paper[0].values",
        ),
        ("negative_budget.toml", SMALL.replace("time_budget_s = 0", "time_budget_s = -1.0"), "run.time_budget_s"),
        (
            "front_unknown_x.toml",
            format!("{SMALL}\n[front]\nx = [\"splat ms\", \"frame ms\"]\ny = \"splats\"\nlevels = [0.1]\n"),
            "front.x",
        ),
        (
            "flip_orbit.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"flip\"").replace("[run]", "[run]\ncamera_path = \"orbit\""),
            "run.camera_path",
        ),
        (
            "flip_level.toml",
            format!("{}\n[quality]\nfinal_level = 9\n", SMALL.replace("kind = \"splats_drawn\"", "kind = \"flip\"")),
            "quality.final_level",
        ),
        (
            "flip_pool.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"flip\"").replace("sphere_oblique.toml", "pool.toml"),
            "key `matrix.scenes`: scene `",
        ),
        (
            "front_two_errors_one_list.toml",
            format!("{SMALL}\n[front]\nx = \"splat ms\"\ny = [\"splats\", \"photons\"]\nlevels = [0.1]\n"),
            "front.levels",
        ),
        (
            "host_ms_without_passes.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"pass_host_ms\""),
            "metric[1].passes",
        ),
        (
            "quick_scene_elsewhere.toml",
            format!("{SMALL}\n[quick]\nscenes = [\"SCENES/sphere_on_plane.toml\", \"SCENES/pool.toml\"]\n"),
            "quick.scenes",
        ),
        ("quick_no_scene.toml", format!("{SMALL}\n[quick]\nscenes = []\n"), "quick.scenes"),
        ("few_max_frames.toml", SMALL.replace("[run]", "[run]\nmax_frames = 0"), "run.max_frames"),
        (
            "bytes_on_a_count.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"splats_drawn\"\nbytes_per_photon = 32"),
            "metric[1].bytes_per_photon",
        ),
        (
            "technique_axis_typo.toml",
            format!("{SMALL}\n[plausibility]\nwork_grows_with = [\"techniques\"]\n"),
            "plausibility.work_grows_with[0]",
        ),
        (
            "temporal_still.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"temporal_change\""),
            "metric[1].kind",
        ),
        ("pose_still.toml", SMALL.replace("kind = \"splats_drawn\"", "kind = \"pose_ms\""), "metric[1].kind"),
        ("builds_still.toml", SMALL.replace("kind = \"splats_drawn\"", "kind = \"blas_builds\""), "metric[1].kind"),
        (
            "pose_one_frame.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"pose_ms\"").replace("[run]", "[run]\nobject_path = \"orbit\""),
            "run.measured_frames",
        ),
        (
            "pose_static_lighting.toml",
            SMALL
                .replace("kind = \"splats_drawn\"", "kind = \"tlas_builds\"")
                .replace("[run]", "[run]\nobject_path = \"orbit\"")
                .replace("measured_frames = 1", "measured_frames = 2")
                .replace("[matrix]", "[matrix]\nlighting = [\"static\", \"dynamic\"]"),
            "matrix.lighting",
        ),
        (
            "moving_objects_compute.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"photon-trace\"\nmoving_objects = \"rebuild\""),
            "moving_objects",
        ),
        (
            "temporal_one_frame.toml",
            SMALL
                .replace("kind = \"splats_drawn\"", "kind = \"temporal_change\"")
                .replace("[run]", "[run]\nlight_path = \"orbit\""),
            "run.measured_frames",
        ),
        (
            "temporal_static_lighting.toml",
            SMALL
                .replace("kind = \"splats_drawn\"", "kind = \"temporal_change\"")
                .replace("[run]", "[run]\nobject_path = \"orbit\"")
                .replace("[matrix]", "[matrix]\nlighting = [\"static\", \"dynamic\"]"),
            "matrix.lighting",
        ),
        (
            "temporal_timed.toml",
            SMALL
                .replace("kind = \"splats_drawn\"", "kind = \"temporal_change\"")
                .replace("[run]", "[run]\nlight_path = \"orbit\"")
                .replace("measured_frames = 1", "measured_frames = 2"),
            "metric[2].kind",
        ),
        (
            "progressive_nowhere.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"progressive_rel_rmse\""),
            "`frames` or `after_ms`",
        ),
        (
            "progressive_both.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"progressive_rel_rmse\"\nframes = 4\nafter_ms = 100"),
            "not both",
        ),
        (
            "progressive_ms_at_a_time.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"progressive_ms\"\nafter_ms = 100"),
            "metric[1].after_ms",
        ),
        (
            "progressive_too_many_frames.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"progressive_rel_rmse\"\nframes = 100000"),
            "metric[1].frames",
        ),
        (
            "frames_without_a_curve.toml",
            SMALL.replace("kind = \"splats_drawn\"", "kind = \"splats_drawn\"\nframes = 4"),
            "metric[1].frames",
        ),
        (
            "progressive_moving_light.toml",
            SMALL
                .replace("kind = \"splats_drawn\"", "kind = \"progressive_rel_rmse\"\nframes = 4")
                .replace("[run]", "[run]\nlight_path = \"orbit\""),
            "run.light_path",
        ),
        (
            "progressive_static_lighting.toml",
            SMALL
                .replace("kind = \"splats_drawn\"", "kind = \"progressive_rel_rmse\"\nframes = 4")
                .replace("[matrix]", "[matrix]\nlighting = [\"static\", \"dynamic\"]"),
            "matrix.lighting",
        ),
        (
            "progressive_alpha_without_progressive.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"photon-trace\"\nprogressive_alpha = 0.5"),
            "technique[1].progressive_alpha",
        ),
        (
            "differentials_progressive.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"photon-trace\"\ndifferentials = true\nprogressive = true"),
            "technique[1].differentials`",
        ),
        (
            "differentials_splat_radius.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"photon-trace\"\ndifferentials = true\nsplat_radius = 3.0"),
            "technique[1].splat_radius`",
        ),
        (
            "bad_pick.toml",
            format!("{SMALL}\n[[layout.column]]\ntechnique = \"quads\"\nmetric = \"photons\"\n"),
            "layout.column[0].technique",
        ),
        (
            "pick_missing_axis.toml",
            format!("{SMALL}\n[[layout.column]]\ntechnique = \"shah\"\n"),
            "layout.column[0]",
        ),
        (
            "pick_unknown_key.toml",
            format!("{SMALL}\n[[layout.column]]\ntechnique = \"shah\"\nmetric = \"photons\"\ncolour = \"red\"\n"),
            "colour",
        ),
        (
            "bad_compare_metric.toml",
            SMALL.replace("columns = [\"technique\", \"metric\"]", "columns = [\"technique\", \"metric\"]\ncompare = { axis = \"technique\", baseline = \"points\", metrics = [\"fps\"] }"),
            "layout.compare.metrics[0]",
        ),
        (
            "nan_paper_value.toml",
            format!("{SMALL}\n[[paper]]\nscene = \"sphere_on_plane\"\ntechnique = \"points\"\nphotons = 80\nvalues = {{ photons = nan }}\n"),
            "paper[0].values.photons",
        ),
        (
            "infinite_paper_value.toml",
            format!("{SMALL}\n[[paper]]\nscene = \"sphere_on_plane\"\ntechnique = \"points\"\nphotons = 80\nvalues = {{ photons = inf }}\n"),
            "paper[0].values.photons",
        ),
        (
            "negative_paper_value.toml",
            format!("{SMALL}\n[[paper]]\nscene = \"sphere_on_plane\"\ntechnique = \"points\"\nphotons = 80\nvalues = {{ photons = -3.5 }}\n"),
            "paper[0].values.photons",
        ),
        (
            "empty_not_comparable.toml",
            format!("{SMALL}\n[[paper]]\nscene = \"sphere_on_plane\"\ntechnique = \"points\"\nphotons = 80\nnot_comparable = \" \"\nvalues = {{ photons = 1.0 }}\n"),
            "paper[0].not_comparable",
        ),
        (
            "caustics_photons.toml",
            SMALL.replacen("[[technique]]", "[caustics]\nphotons = 256\n\n[[technique]]", 1),
            "caustics.photons",
        ),
        (
            "caustics_owned.toml",
            SMALL.replacen("[[technique]]", "[caustics]\ncluster = \"last\"\n\n[[technique]]", 1),
            "caustics.cluster",
        ),
        (
            "caustics_bad_fov.toml",
            SMALL.replacen("[[technique]]", "[caustics]\nphoton_view = \"fixed-fov\"\nphoton_fov = 200.0\n\n[[technique]]", 1),
            "photon_fov",
        ),
        (
            // 8192² eye images need 7680 MiB, beyond lavapipe's 2048 MiB heap: refused before
            // the first cell runs, though the 64² cells would fit.
            "beyond_memory.toml",
            SMALL
                .replace("resolution = [[64, 64]]", "resolution = [[64, 64], [8192, 8192]]")
                .replace("rows = [\"scene\", \"photons\"]", "rows = [\"scene\", \"photons\", \"resolution\"]"),
            "key `camera.resolution`: the frame's images need at least 7",
        ),
        (
            "bad_radius.toml",
            SMALL.replace("technique = \"shah\"", "technique = \"shah\"\nsplat_radius = 500.0"),
            "splat_radius",
        ),
    ];
    for (name, text, needle) in cases {
        let cfg = config_file(&dir, name, &text);
        let root = dir.join(format!("results-{name}"));
        let r = bench(&[cfg.as_os_str(), "--results".as_ref(), root.as_os_str()]);
        assert_eq!(r.code, Some(2), "{name}: {}", r.describe());
        assert!(
            r.stderr.contains(name) && r.stderr.contains(needle),
            "{name}: message lacks `{needle}`:\n{}",
            r.stderr
        );
        assert!(!r.stderr.contains("panicked"), "{name}: {}", r.describe());
        assert!(!root.exists(), "{name}: a failed config wrote results");
    }
    // Bad command-line selections.
    let cfg = config_file(&dir, "small.toml", SMALL);
    for (args, needle) in [
        (vec!["--filter", "photons=77"], "photons"),
        (vec!["--filter", "colour=red"], "colour"),
        (vec!["--shard", "3/2"], "--shard"),
    ] {
        let scratch_results = dir.join("results-selections");
        let mut all: Vec<&std::ffi::OsStr> = vec![cfg.as_os_str(), "--results".as_ref(), scratch_results.as_os_str()];
        all.extend(args.iter().map(std::ffi::OsStr::new));
        let r = bench(&all);
        assert_eq!(r.code, Some(2), "{args:?}: {}", r.describe());
        assert!(r.stderr.contains(needle), "{args:?}: {}", r.stderr);
    }
    let r = bench(&["no_such_config.toml".as_ref()]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    assert!(r.stderr.contains("no_such_config.toml"), "{}", r.stderr);
}

#[test]
fn config_unknown_keys_name_their_path_and_line() {
    let dir = scratch("bench-key-paths");
    let cases = [
        (
            "nested.toml",
            SMALL.replace("measured_frames = 1", "measurd_frames = 1"),
            "run.measurd_frames",
            "measurd_frames",
        ),
        (
            "array_of_tables.toml",
            SMALL.replace("technique = \"wd-points\"", "technique = \"wd-points\"\nclustr = \"all\""),
            "technique[0].clustr",
            "clustr =",
        ),
    ];
    for (name, text, key, line_of) in cases {
        let cfg = config_file(&dir, name, &text);
        let line = text.lines().position(|l| l.starts_with(line_of)).expect("the bad key is in the config") + 1;
        let root = dir.join(format!("results-{name}"));
        let r = bench(&[cfg.as_os_str(), "--results".as_ref(), root.as_os_str()]);
        assert_eq!(r.code, Some(2), "{name}: {}", r.describe());
        let want = format!("{}: key `{key}` (line {line}): unknown field", cfg.display());
        assert!(r.stderr.contains(&want), "{name}: stderr lacks `{want}`:\n{}", r.stderr);
        assert!(!r.stderr.contains("TOML parse error"), "{name}: toml's raw message:\n{}", r.stderr);
        assert!(!root.exists(), "{name}: a failed config wrote results");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn results_over_a_regular_file_fails_before_the_device_is_opened() {
    let dir = scratch("bench-results-file");
    let cfg = config_file(&dir, "small.toml", SMALL);
    let file = dir.join("results");
    std::fs::write(&file, b"keep me").expect("writing a file where --results points");
    let part = dir.join("small.shard-0-of-2.json");
    // The device named does not exist: only a check made before opening it reports the path.
    let runs = [
        vec!["--device".as_ref(), "no-such-gpu".as_ref(), cfg.as_os_str(), "--results".as_ref(), file.as_os_str()],
        vec!["merge".as_ref(), part.as_os_str(), "--results".as_ref(), file.as_os_str()],
    ];
    for args in runs {
        let r = bench(&args);
        assert_eq!(r.code, Some(2), "{args:?}: {}", r.describe());
        for needle in ["--results", &file.display().to_string(), "not a directory"] {
            assert!(r.stderr.contains(needle), "{args:?}: stderr lacks `{needle}`\n{}", r.describe());
        }
        assert!(!r.stderr.contains("no-such-gpu"), "{args:?}: the device was opened first\n{}", r.describe());
    }
    assert_eq!(std::fs::read(&file).expect("the file is still there"), b"keep me");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_plot_font_fails_before_any_cell_runs() {
    let dir = scratch("bench-font");
    let cfg = config_file(&dir, "small.toml", SMALL);
    let root = dir.join("results");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_causticlab"))
        .args(["bench".as_ref(), cfg.as_os_str(), "--results".as_ref(), root.as_os_str()])
        .env("CAUSTICLAB_FONT", "/nonexistent/plot-font.ttf")
        .current_dir(workspace())
        .output()
        .expect("spawning causticlab");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("/nonexistent/plot-font.ttf") && stderr.contains("fonts-dejavu-core"), "{stderr}");
    assert!(!stderr.contains("panicked") && !stderr.contains("cells in"), "{stderr}");
    assert!(!root.exists(), "a run without a font wrote results");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_metric_whose_passes_match_nothing_is_refused_with_the_passes_recorded() {
    let dir = scratch("bench-drift");
    let drifted = SMALL.replace("passes = [\"splat.*\"]", "passes = [\"splat_renamed.*\"]");
    assert_ne!(drifted, SMALL);
    let cfg = config_file(&dir, "drift.toml", &drifted);
    let r = bench(&[cfg.as_os_str(), "--results".as_ref(), dir.join("out").as_os_str()]);
    assert_eq!(r.code, Some(2), "{}", r.describe());
    assert!(
        r.stderr.contains("`splat_renamed.*`")
            && r.stderr.contains("splat.light0")
            && r.stderr.contains("metric[2].passes"),
        "the error names the pattern, the key and the passes recorded: {}",
        r.describe()
    );
    assert!(files_under(&dir.join("out")).iter().all(|f| !f.ends_with("drift.md")), "a refused run wrote its table");
    // Saying why a metric may have no such pass turns the cells into n/a with the reason listed.
    let allowed = drifted.replace(
        "passes = [\"splat_renamed.*\"]",
        "passes = [\"splat_renamed.*\"]\nabsent = \"renamed on purpose (test)\"",
    );
    let cfg = config_file(&dir, "allowed.toml", &allowed);
    let r = bench(&[cfg.as_os_str(), "--results".as_ref(), dir.join("ok").as_os_str()]);
    assert_eq!(r.code, Some(0), "{}", r.describe());
    let md = std::fs::read_to_string(device_dir(&dir.join("ok")).join("allowed.md")).expect("table");
    assert!(md.contains("renamed on purpose (test)"), "{md}");
}

#[test]
fn bench_explain_names_a_missing_table_and_a_table_of_another_config() {
    let dir = scratch("bench-explain-errors");
    let missing = dir.join("nowhere.json");
    let front = workspace().join("bench_configs/front.toml");
    // Any committed photon_trace_rate table (whatever its device folder is called).
    let other = std::fs::read_dir(workspace().join("results"))
        .expect("results/")
        .flatten()
        .map(|e| e.path().join("photon_trace_rate.json.gz"))
        .find(|p| p.exists())
        .expect("a committed photon_trace_rate.json.gz under results/");
    let root = dir.join("results");
    for (table, needle) in
        [(&missing, missing.display().to_string()), (&other, "the table of `photon_trace_rate`".into())]
    {
        let r =
            bench(&["explain".as_ref(), front.as_os_str(), table.as_os_str(), "--results".as_ref(), root.as_os_str()]);
        assert_eq!(r.code, Some(2), "{}", r.describe());
        assert!(r.stderr.contains(&needle), "stderr lacks `{needle}`\n{}", r.describe());
        assert!(!root.exists(), "a refused explain wrote results");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
