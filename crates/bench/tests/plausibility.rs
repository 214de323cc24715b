//! The plausibility rules (`bench::plausibility`) on synthetic tables: each rule trips on a
//! table that breaks it and stays quiet on one that does not; a finding marks its entry `?` and
//! is listed under the table and kept in the JSON; an explanation in the config lifts the `?`.

mod common;
use bench::config::Config;
use bench::plausibility::{check, Finding};
use bench::results::{CellResult, Results};
use common::{cell, loaded_config, results, value};

const CONFIG: &str = r#"
[table]
paper = "Synthetic"
number = "P"
caption = "Plausibility."

[matrix]
scenes = ["../scenes/sphere_on_plane.toml"]
photons = [1024, 4096]
lighting = ["static", "dynamic"]

[[technique]]
label = "copy"
technique = "wd-points"

[[metric]]
label = "Gather"
kind = "pass_ms"
passes = ["splat.*"]
bytes_per_photon = 32

[[metric]]
label = "Eye"
kind = "pass_ms"
passes = ["composite"]
independent_of = ["photons"]

[layout]
rows = ["photons"]
columns = ["lighting", "metric"]
"#;

const STEADY: f64 = 0.01;

/// Five samples within 1% of `ms`.
fn around(ms: f64) -> [f64; 5] {
    [ms, ms * (1.0 + STEADY), ms * (1.0 - STEADY), ms, ms]
}

/// The four cells (static/dynamic x 1024²/4096²) with Gather and Eye times in ms.
fn table(text: &str, gather: [f64; 4], eye: [f64; 4], bandwidth: Option<f64>) -> (Config, Results) {
    let config: Config = toml::from_str(text).expect("the test config parses");
    let mut cells: Vec<CellResult> = vec![];
    for (i, (lighting, photons)) in
        [("static", 1024), ("dynamic", 1024), ("static", 4096), ("dynamic", 4096)].into_iter().enumerate()
    {
        let mut c = cell(i, 0, "copy", photons, &around(gather[i]));
        c.cell.lighting = lighting.into();
        c.metrics.insert("Eye".into(), value(&around(eye[i])));
        cells.push(c);
    }
    let mut r = results(&config, text, cells);
    r.run.copy_bandwidth_gbs = bandwidth;
    (config, r)
}

fn rules(f: &[Finding]) -> Vec<(String, String, usize)> {
    f.iter().map(|x| (x.rule.clone(), x.metric.clone(), x.cell)).collect()
}

const QUIET_EYE: [f64; 4] = [5.0, 5.1, 5.0, 5.2];

#[test]
fn a_more_photons_faster_is_flagged_and_slower_is_not() {
    // Dynamic: 10 ms at 1024², 5 ms at 4096² (cell 3). Static stays put.
    let (c, r) = table(CONFIG, [8.0, 10.0, 20.0, 5.0], QUIET_EYE, None);
    assert_eq!(rules(&check(&c, &r)), vec![("a".into(), "Gather".into(), 3), ("b".into(), "Gather".into(), 3)]);
    let (c, r) = table(CONFIG, [8.0, 10.0, 20.0, 25.0], QUIET_EYE, None);
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    // Within the spreads and the 1% margin is not a finding: 10 ms, then 9.95 ms.
    let (c, r) = table(CONFIG, [8.0, 10.0, 20.0, 9.95], QUIET_EYE, None);
    assert!(rules(&check(&c, &r)).iter().all(|(rule, _, _)| rule != "a"), "{:?}", check(&c, &r));
}

#[test]
fn b_dynamic_faster_than_static_is_flagged() {
    let (c, r) = table(CONFIG, [12.0, 6.0, 30.0, 35.0], QUIET_EYE, None);
    assert_eq!(rules(&check(&c, &r)), vec![("b".into(), "Gather".into(), 1)]);
    let (c, r) = table(CONFIG, [12.0, 13.0, 30.0, 35.0], QUIET_EYE, None);
    assert!(check(&c, &r).is_empty());
}

#[test]
fn c_a_copy_faster_than_memory_is_flagged_at_every_size() {
    // 4096² x 32 B = 537 MB: in 1 ms that is 537 GB/s, above 15 GB/s; in 50 ms, 10.7 GB/s.
    // 1024² (34 MB, under 64 MiB) may run from caches, up to ten times the bandwidth: in
    // 0.01 ms it moves 3355 GB/s, above 150; in 1 ms 34 GB/s, within it.
    let (c, r) = table(CONFIG, [0.01, 1.0, 1.0, 1.1], QUIET_EYE, Some(15.0));
    let found = check(&c, &r);
    assert_eq!(
        rules(&found),
        vec![("c".into(), "Gather".into(), 0), ("c".into(), "Gather".into(), 2), ("c".into(), "Gather".into(), 3)],
    );
    assert!(found[1].text.contains("GB/s") && !found[1].text.contains("caches"), "{}", found[1].text);
    assert!(found[0].text.contains("ten times it"), "{}", found[0].text);
    let (c, r) = table(CONFIG, [1.0, 1.0, 50.0, 55.0], QUIET_EYE, Some(15.0));
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    // Just inside and just outside the bounds: 537 MB at 15 GB/s x 1.1 takes 32.5 ms; 33.6 MB
    // at 150 GB/s x 1.1 (cached) takes 0.204 ms.
    let (c, r) = table(CONFIG, [0.21, 0.21, 32.8, 32.8], QUIET_EYE, Some(15.0));
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    let (c, r) = table(CONFIG, [0.19, 0.21, 32.3, 32.8], QUIET_EYE, Some(15.0));
    assert_eq!(rules(&check(&c, &r)), vec![("c".into(), "Gather".into(), 0), ("c".into(), "Gather".into(), 2)]);
    // Without a measured bandwidth the rule cannot speak.
    let (c, r) = table(CONFIG, [0.01, 0.01, 1.0, 1.1], QUIET_EYE, None);
    assert!(check(&c, &r).is_empty());
}

#[test]
fn d_a_metric_independent_of_photons_that_varies_2x_is_flagged() {
    let (c, r) = table(CONFIG, [8.0, 10.0, 20.0, 25.0], [5.0, 5.0, 5.0, 12.0], None);
    assert_eq!(rules(&check(&c, &r)), vec![("d".into(), "Eye".into(), 3)]);
    // 1.5x is within the rule; and an independent metric is not held to rule a either.
    let (c, r) = table(CONFIG, [8.0, 10.0, 20.0, 25.0], [5.0, 7.5, 5.0, 5.0], None);
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
}

#[test]
fn findings_mark_the_table_and_an_explanation_lifts_the_mark() {
    let (c, r) = table(CONFIG, [12.0, 6.0, 30.0, 35.0], QUIET_EYE, None);
    let dir = caustics::scratch::ScratchDir::new("causticlab", "plausibility");
    let out = bench::run::write_table(&c, &r, &dir.join("dev"), &dir).expect("table written");
    let md = out.markdown;
    assert!(md.contains("## Plausibility") && md.contains("Implausible (`?`), 1 entries"), "{md}");
    let row = md.lines().find(|l| l.starts_with("| 1024²")).expect("1024 row");
    assert!(row.contains("6.00 ±1%?") || row.contains("?"), "{row}");
    let json: serde_json::Value =
        serde_json::from_str(&bench::results::read_text(&dir.join("dev/synthetic.json.gz"), "table").expect("json"))
            .expect("parses");
    assert_eq!(json["plausibility"][0]["rule"], "b", "{}", json["plausibility"]);

    let explained = format!(
        "{CONFIG}\n[[plausibility.explained]]\nrule = \"b\"\nmetric = \"Gather\"\nphotons = 1024\nwhy = \"measured: the static cell rebuilt its photon buffer (test)\"\n"
    );
    let (c, r) = table(&explained, [12.0, 6.0, 30.0, 35.0], QUIET_EYE, None);
    let found = check(&c, &r);
    assert_eq!(found.len(), 1);
    assert!(found[0].explained.as_deref().is_some_and(|w| w.contains("measured")));
    let out = bench::run::write_table(&c, &r, &dir.join("dev2"), &dir).expect("table written");
    let row = out.markdown.lines().find(|l| l.starts_with("| 1024²")).expect("1024 row").to_string();
    assert!(!row.contains('?'), "an explained finding is not marked: {row}");
    assert!(out.markdown.contains("Explained, 1 entries"), "{}", out.markdown);
}

#[test]
fn bench_explain_applies_explanations_added_after_the_run_and_times_nothing() {
    let (c, r) = table(CONFIG, [12.0, 6.0, 30.0, 35.0], QUIET_EYE, None);
    let dir = caustics::scratch::ScratchDir::new("causticlab", "explain");
    bench::run::write_table(&c, &r, &dir.join("synthetic"), &dir).expect("table written");
    let json = dir.join("synthetic/synthetic.json.gz");
    let read = || -> Results { bench::results::read(&json, "table").expect("the table") };
    let before = read();
    let loaded = |text: &str| loaded_config(&dir, text);
    // A config changed in more than its explanations is refused, and the table left alone.
    let more_photons = CONFIG.replace("photons = [1024, 4096]", "photons = [1024, 2048]");
    let Err(err) = bench::explain::explain(&loaded(&more_photons), &json, &dir, "abc1234") else {
        panic!("a config changed in its matrix was accepted")
    };
    let msg = format!("{err:#}");
    assert!(msg.contains("synthetic.toml") && msg.contains("run the table again"), "{msg}");
    assert!(msg.contains("in what it measures (`matrix.photons`)"), "the key is named: {msg}");
    assert_eq!(read(), before);
    // A copy of the table elsewhere, or a part of one, is refused: either would overwrite the table.
    let copy = dir.join("copy.json");
    std::fs::copy(&json, &copy).expect("copy");
    let Err(err) = bench::explain::explain(&loaded(CONFIG), &copy, &dir, "abc1234") else {
        panic!("a copy was accepted")
    };
    assert!(format!("{err:#}").contains("not the table in the results folder"), "{err:#}");
    let mut part = before.clone();
    part.run.filter.terms = vec![("photons".into(), "1024".into())];
    std::fs::write(&copy, serde_json::to_string(&part).expect("json")).expect("write part");
    let Err(err) = bench::explain::explain(&loaded(CONFIG), &copy, &dir, "abc1234") else {
        panic!("a part was accepted")
    };
    assert!(format!("{err:#}").contains("bench merge"), "{err:#}");
    // Findings that differ from the run's (rules changed since) are refused.
    let mut judged_otherwise = before.clone();
    judged_otherwise.plausibility.clear();
    std::fs::write(
        &json,
        bench::results::gzip(&serde_json::to_string(&judged_otherwise).expect("json")).expect("gzip"),
    )
    .expect("write");
    let Err(err) = bench::explain::explain(&loaded(CONFIG), &json, &dir, "abc1234") else {
        panic!("other findings accepted")
    };
    assert!(format!("{err:#}").contains("the rules changed since the run"), "{err:#}");
    std::fs::write(&json, bench::results::gzip(&serde_json::to_string(&before).expect("json")).expect("gzip"))
        .expect("restore");
    // Explanations (and a comment) added: the `?` goes, the cells stay as measured.
    let explained = format!(
        "# explained later\n{CONFIG}\n[[plausibility.explained]]\nrule = \"b\"\nmetric = \"Gather\"\nphotons = 1024\nwhy = \"measured: the static cell rebuilt its photon buffer (test)\"\n"
    );
    let out = bench::explain::explain(&loaded(&explained), &json, &dir, "abc1234").expect("explained");
    let row = out.markdown.lines().find(|l| l.starts_with("| 1024²")).expect("1024 row").to_string();
    assert!(!row.contains('?'), "{row}");
    let header = out.markdown.lines().find(|l| l.contains("Explained after the run")).expect("header line");
    assert!(header.contains("abc1234") && header.contains(&format!("hash {}", before.config.hash)), "{header}");
    let after = read();
    assert_eq!(after.cells, before.cells, "no cell was measured again or changed");
    assert_eq!(after.meta, before.meta, "the measured commit, date and device stay");
    assert!(after.plausibility[0].explained.is_some());
    assert_eq!(after.config.hash, bench::config::fnv1a(explained.as_bytes()));
    // Explained once more: the table still cites the config it was measured with.
    let out = bench::explain::explain(&loaded(&explained), &json, &dir, "def5678").expect("again");
    assert!(
        out.markdown.contains("def5678 (")
            && out.markdown.contains(&format!("hash {} when measured", before.config.hash))
    );
}

#[test]
fn bench_explain_ignores_the_sources_of_paper_values() {
    // A table measured before its config cited where the paper's values are.
    let paper = "[[paper]]\nphotons = 1024\nlighting = \"static\"\nvalues = { Gather = 5.0 }\n";
    let measured = format!("{CONFIG}\n{paper}");
    let (c, r) = table(&measured, [12.0, 6.0, 30.0, 35.0], QUIET_EYE, None);
    let dir = caustics::scratch::ScratchDir::new("causticlab", "explain-sources");
    bench::run::write_table(&c, &r, &dir.join("synthetic"), &dir).expect("table written");
    let json = dir.join("synthetic/synthetic.json.gz");
    let loaded = |text: &str| loaded_config(&dir, text);
    let cited =
        |source: &str| measured.replace("Gather = 5.0 }\n", &format!("Gather = 5.0 }}\nsource = \"{source}\"\n"));
    // A source added, then changed: a citation, not a measurement.
    let first = cited("Table 1, row 1024²");
    assert_ne!(first, measured);
    bench::explain::explain(&loaded(&first), &json, &dir, "abc1234").expect("a source added is explained");
    let second = cited("Sec. 4, paragraph 'static'");
    bench::explain::explain(&loaded(&second), &json, &dir, "def5678").expect("a source changed is explained");
    // The published value itself is not a citation: changed, the config is refused.
    let other_value = second.replace("Gather = 5.0", "Gather = 6.0");
    let Err(err) = bench::explain::explain(&loaded(&other_value), &json, &dir, "abc1234") else {
        panic!("a changed paper value was accepted")
    };
    assert!(format!("{err:#}").contains("run the table again"), "{err:#}");
}

#[test]
fn bench_explain_reads_a_table_again_with_what_measures_nothing() {
    let (c, r) = table(CONFIG, [12.0, 6.0, 30.0, 35.0], QUIET_EYE, None);
    let dir = caustics::scratch::ScratchDir::new("causticlab", "explain-reading");
    bench::run::write_table(&c, &r, &dir.join("synthetic"), &dir).expect("table written");
    let json = dir.join("synthetic/synthetic.json.gz");
    let before = bench::results::read(&json, "table").expect("the table");
    assert!(before.plausibility.iter().all(|f| f.rule != "d"), "{:?}", before.plausibility);
    let loaded = |text: &str| loaded_config(&dir, text);
    // A new caption and note, and `Gather` said to be independent of the photons: the table is
    // judged by the new config, so rule d now finds Gather's 12 → 30 ms along the photons.
    let read_again = CONFIG
        .replace("caption = \"Plausibility.\"", "caption = \"Read again.\"\nnotes = [\"A note.\"]")
        .replace("bytes_per_photon = 32\n", "bytes_per_photon = 32\nindependent_of = [\"photons\"]\n");
    assert_ne!(read_again, CONFIG);
    let out = bench::explain::explain(&loaded(&read_again), &json, &dir, "abc1234").expect("read again");
    let after = bench::results::read(&json, "table").expect("the table");
    assert_eq!(after.cells, before.cells, "no cell changed");
    assert!(after.plausibility.iter().any(|f| f.rule == "d" && f.metric == "Gather"), "{:?}", after.plausibility);
    assert_eq!(after.config.caption, "Read again.");
    assert!(out.markdown.contains("Read again.") && out.markdown.contains("A note."), "{}", out.markdown);
    // A metric's frame mode is how it was measured: refused, naming it.
    let other_mode = read_again.replace("passes = [\"composite\"]\n", "passes = [\"composite\"]\nexclude = [\"x\"]\n");
    let Err(err) = bench::explain::explain(&loaded(&other_mode), &json, &dir, "def5678") else {
        panic!("a metric's passes changed were accepted")
    };
    assert!(format!("{err:#}").contains("(`metric[\"Eye\"].exclude`)"), "{err:#}");
}

/// One scene, one technique per entry of `labels`, each at the photon counts of `photons`; the
/// metrics of each cell from `metrics(technique, photons)` as (label, median) pairs.
fn grid(
    text: &str,
    labels: &[&str],
    photons: &[u32],
    metrics: impl Fn(usize, u32) -> Vec<(&'static str, f64)>,
) -> (Config, Results) {
    let config: Config = toml::from_str(text).expect("the test config parses");
    let mut cells = vec![];
    for (t, label) in labels.iter().enumerate() {
        for &p in photons {
            let mut c = cell(cells.len(), t, label, p, &around(1.0));
            c.metrics.clear();
            for (m, v) in metrics(t, p) {
                c.metrics.insert(m.into(), value(&around(v)));
            }
            cells.push(c);
        }
    }
    let mut r = results(&config, text, cells);
    r.run.copy_bandwidth_gbs = Some(20.0);
    (config, r)
}

const HEADER: &str = r#"
[table]
paper = "Synthetic"
number = "P"
caption = "Plausibility."

[layout]
rows = ["photons"]
columns = ["technique", "metric"]
"#;

const TRACE: &str = r#"
[matrix]
scenes = ["../scenes/sphere_on_plane.toml"]
photons = [256, 4096]

[[technique]]
label = "trace"
technique = "photon-trace"

[[metric]]
label = "Trace"
kind = "pass_ms"
passes = ["photon_trace*"]

[[metric]]
label = "Trace (host)"
kind = "pass_host_ms"
passes = ["photon_trace*"]

[[metric]]
label = "rate"
kind = "pass_mphotons"
passes = ["photon_trace*"]
not_monotonic = "a rate"
bytes_per_photon = 48
"#;

#[test]
fn e_a_pass_far_below_its_host_time_is_not_measured() {
    let text = format!("{HEADER}{TRACE}");
    // 0.05 ms on the device's clock, 130 ms on the host: the timestamps missed the trace.
    let (c, r) = grid(&text, &["trace"], &[256, 4096], |_, p| {
        vec![("Trace", if p == 256 { 0.05 } else { 900.0 }), ("Trace (host)", if p == 256 { 130.0 } else { 910.0 })]
    });
    let found = check(&c, &r);
    assert_eq!(rules(&found), vec![("e".into(), "Trace".into(), 0)], "{found:?}");
    assert!(found[0].text.contains("0.0500") && found[0].text.contains("130.0"), "{}", found[0].text);
    // The rate of the same passes comes from the same timestamps: marked with them (65536
    // photons in 0.05 ms is 1311 M photons/s, within rule f's cached bound, 10 x 20 GB/s x 1.1
    // over 48 B: only rule e can tell).
    let (c, r) = grid(&text, &["trace"], &[256, 4096], |_, p| {
        let (gpu, host) = if p == 256 { (0.05, 130.0) } else { (900.0, 910.0) };
        vec![("Trace", gpu), ("Trace (host)", host), ("rate", (p as f64).powi(2) / gpu / 1000.0)]
    });
    let found = check(&c, &r);
    assert_eq!(rules(&found), vec![("e".into(), "Trace".into(), 0), ("e".into(), "rate".into(), 0)], "{found:?}");
    assert!(found[1].text.contains("`rate` is a rate of `Trace`"), "{}", found[1].text);
    // So is a frame rate of the same passes (pass_fps: 1000 / pass_ms).
    let with_fps = text.replace(
        "[[metric]]\nlabel = \"rate\"",
        "[[metric]]\nlabel = \"Trace fps\"\nkind = \"pass_fps\"\npasses = [\"photon_trace*\"]\n\n[[metric]]\nlabel = \"rate\"",
    );
    assert_ne!(with_fps, text);
    let (c, r) = grid(&with_fps, &["trace"], &[256, 4096], |_, p| {
        let (gpu, host) = if p == 256 { (0.05, 130.0) } else { (900.0, 910.0) };
        vec![("Trace", gpu), ("Trace (host)", host), ("Trace fps", 1000.0 / gpu)]
    });
    let found = check(&c, &r);
    assert_eq!(rules(&found), vec![("e".into(), "Trace".into(), 0), ("e".into(), "Trace fps".into(), 0)], "{found:?}");
    // Just inside: a tenth of the host time (13 ms of 130), or under it by less than 1 ms.
    let (c, r) = grid(&text, &["trace"], &[256, 4096], |_, p| {
        vec![("Trace", if p == 256 { 13.1 } else { 140.0 }), ("Trace (host)", if p == 256 { 130.0 } else { 150.0 })]
    });
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    let (c, r) = grid(&text, &["trace"], &[256, 4096], |_, p| {
        // Under a tenth (0.05 of 0.9 ms) but less than 1 ms below: the submit and the wait.
        vec![("Trace", if p == 256 { 0.05 } else { 140.0 }), ("Trace (host)", if p == 256 { 0.9 } else { 150.0 })]
    });
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    // Without a host-timed metric over the same passes the rule cannot speak.
    let other = text.replace(
        "label = \"Trace (host)\"\nkind = \"pass_host_ms\"\npasses = [\"photon_trace*\"]",
        "label = \"Trace (host)\"\nkind = \"pass_host_ms\"\npasses = [\"splat*\"]",
    );
    assert_ne!(other, text);
    let (c, r) = grid(&other, &["trace"], &[256, 4096], |_, p| {
        vec![("Trace", if p == 256 { 0.05 } else { 900.0 }), ("Trace (host)", 130.0)]
    });
    assert!(check(&c, &r).iter().all(|f| f.rule != "e"), "{:?}", check(&c, &r));
}

#[test]
fn a_and_b_leave_out_entries_the_device_did_not_measure() {
    // a: the trace at 4096² reads 0.05 ms on the device's clock against 900 ms on the host
    // (rule e): not a time, so not "more work, less time" against 256²'s 50 ms.
    let text = format!("{HEADER}{TRACE}");
    let trace = |gpu4096: f64, host4096: f64| {
        grid(&text, &["trace"], &[256, 4096], move |_, p| {
            vec![
                ("Trace", if p == 256 { 50.0 } else { gpu4096 }),
                ("Trace (host)", if p == 256 { 55.0 } else { host4096 }),
            ]
        })
    };
    let (c, r) = trace(0.05, 900.0);
    assert_eq!(rules(&check(&c, &r)), vec![("e".into(), "Trace".into(), 1)]);
    // Timed by the device (10 ms, 56 on the host): faster with more photons, rule a speaks.
    let (c, r) = trace(10.0, 56.0);
    assert_eq!(rules(&check(&c, &r)), vec![("a".into(), "Trace".into(), 1)]);
    // b: the dynamic 1024² Gather (6 ms) beats its static twin (12 ms), but moves 33.5 MB at
    // 5.6 GB/s, over rule c's bound (0.4 GB/s measured, ten times it from caches, and 10%:
    // 4.4 GB/s): not measured, so not faster than anything. At 1 GB/s (bound 11) it is a time.
    let gather = [12.0, 6.0, 30.0, 35.0];
    let (c, r) = table(CONFIG, gather, QUIET_EYE, Some(0.4));
    let found = check(&c, &r);
    assert!(found.iter().any(|f| f.rule == "c" && f.cell == 1) && found.iter().all(|f| f.rule != "b"), "{found:?}");
    let (c, r) = table(CONFIG, gather, QUIET_EYE, Some(1.0));
    let found = check(&c, &r);
    assert!(found.iter().any(|f| f.rule == "b" && f.cell == 1 && f.metric == "Gather"), "{found:?}");
    assert!(found.iter().all(|f| f.rule != "c" || f.cell >= 2), "{found:?}");
    // Only the metric the device did not time leaves its pairs: Gather's rule c at 4096² leaves
    // Eye's dynamic 5 ms against static 9 ms there a finding of rule b.
    let (c, r) = table(CONFIG, gather, [5.0, 5.1, 9.0, 5.0], Some(1.0));
    let found = check(&c, &r);
    assert!(found.iter().any(|f| f.rule == "c" && f.cell == 3 && f.metric == "Gather"), "{found:?}");
    assert!(found.iter().any(|f| f.rule == "b" && f.cell == 3 && f.metric == "Eye"), "{found:?}");
}

#[test]
fn f_a_photon_rate_beyond_what_the_device_can_write_is_flagged() {
    let text = format!("{HEADER}{TRACE}");
    // 256² x 48 B = 3.1 MB, under 64 MiB: bound 10 x 20 GB/s x 1.1 = 220 GB/s, 4583 M photons/s.
    // 4096²: 805 MB, bound 22 GB/s, 458.3 M photons/s.
    let rate = |r256: f64, r4096: f64| {
        grid(&text, &["trace"], &[256, 4096], move |_, p| vec![("rate", if p == 256 { r256 } else { r4096 })])
    };
    let (c, r) = rate(8083.0, 470.0);
    let found = check(&c, &r);
    assert_eq!(rules(&found), vec![("f".into(), "rate".into(), 0), ("f".into(), "rate".into(), 1)], "{found:?}");
    assert!(found[0].text.contains("8083 M photons/s") && found[0].text.contains("GB/s"), "{}", found[0].text);
    let (c, r) = rate(4550.0, 455.0);
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    // A rate that is lower when faster (fps-like) is judged as a rate, not as a time: a tiny
    // rate is never beyond the device.
    let (c, r) = rate(0.001, 0.001);
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
}

const BATCHES: &str = r#"
[matrix]
scenes = ["../scenes/sphere_on_plane.toml"]
photons = [8192, 16384]

[plausibility]
work_grows_with = ["photons", "technique"]

[[technique]]
label = "1 batch"
technique = "adaptive"

[[technique]]
label = "16 batches"
technique = "adaptive"
photon_batches = 16

[[metric]]
label = "map"
kind = "pass_ms"
passes = ["adaptive*"]

[[metric]]
label = "batches"
kind = "photon_batches"

[[metric]]
label = "storage"
kind = "photon_storage"
"#;

#[test]
fn a_along_the_technique_axis_more_batches_faster_is_flagged() {
    let text = format!("{HEADER}{BATCHES}");
    // 16 batches at 1024 ms against one at 1672 ms (8192²): faster with more batches.
    let (c, r) = grid(&text, &["1 batch", "16 batches"], &[8192, 16384], |t, p| {
        let map = match (t, p) {
            (0, 8192) => 1672.0,
            (1, 8192) => 1100.0,
            (0, _) => 6000.0,
            _ => 6500.0,
        };
        vec![("map", map), ("batches", if t == 0 { 8.0 } else { 16.0 })]
    });
    let found = check(&c, &r);
    assert_eq!(rules(&found), vec![("a".into(), "map".into(), 2)], "{found:?}");
    assert!(found[0].text.contains("technique 1 batch → 16 batches"), "{}", found[0].text);
    // Slower with more batches is plausible; without `technique` among the axes it is not judged.
    let (c, r) = grid(&text, &["1 batch", "16 batches"], &[8192, 16384], |t, p| {
        vec![("map", if t == 0 { 1000.0 } else { 1100.0 } * (p / 8192) as f64), ("batches", 8.0 + t as f64)]
    });
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    let photons_only =
        text.replace("work_grows_with = [\"photons\", \"technique\"]", "work_grows_with = [\"photons\"]");
    let (c, r) = grid(&photons_only, &["1 batch", "16 batches"], &[8192, 16384], |t, p| {
        vec![("map", if t == 0 { 1672.0 } else { 1100.0 } * (p / 8192) as f64), ("batches", 8.0)]
    });
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
}

#[test]
fn g_a_count_that_falls_as_the_work_grows_is_flagged() {
    let text = format!("{HEADER}{BATCHES}");
    // 198 batches at 8192², 115 at 16384²: fewer with four times the photons.
    let counts = |at8192: f64, at16384: f64, text: &str| {
        grid(text, &["1 batch"], &[8192, 16384], move |_, p| {
            // The storage under a memory limit may fall as batching splits the lists: not judged.
            let storage = if p == 8192 { 96.0 } else { 95.9 };
            vec![
                ("map", 1000.0 * (p / 8192) as f64),
                ("batches", if p == 8192 { at8192 } else { at16384 }),
                ("storage", storage),
            ]
        })
    };
    let (c, r) = counts(198.0, 115.0, &text);
    let found = check(&c, &r);
    assert_eq!(rules(&found), vec![("g".into(), "batches".into(), 1)], "{found:?}");
    assert!(found[0].text.contains("198 → 115"), "{}", found[0].text);
    // Counts are exact: one fewer is a finding, the same is not.
    let (c, r) = counts(198.0, 197.0, &text);
    assert_eq!(rules(&check(&c, &r)), vec![("g".into(), "batches".into(), 1)]);
    let (c, r) = counts(198.0, 198.0, &text);
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    // A count that says why it need not grow is not judged.
    let excused = text.replace(
        "kind = \"photon_batches\"",
        "kind = \"photon_batches\"\nnot_monotonic = \"planned for the worst case\"",
    );
    let (c, r) = counts(198.0, 115.0, &excused);
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
}

#[test]
fn an_entry_the_device_cannot_have_measured_reads_not_measured() {
    let text = format!("{HEADER}{TRACE}");
    let (c, mut r) = grid(&text, &["trace"], &[256, 4096], |_, p| {
        vec![("Trace", if p == 256 { 0.05 } else { 900.0 }), ("Trace (host)", if p == 256 { 130.0 } else { 910.0 })]
    });
    r.plausibility = check(&c, &r);
    let dir = caustics::scratch::ScratchDir::new("causticlab", "unmeasured");
    let out = bench::run::write_table(&c, &r, &dir.join("dev"), &dir).expect("table written");
    let row = out.markdown.lines().find(|l| l.starts_with("| 256²")).expect("256 row").to_string();
    let rows: Vec<&str> = out.markdown.lines().filter(|l| l.starts_with('|')).collect();
    assert!(row.contains("not measured (e)") && !rows.iter().any(|l| l.contains("0.0500")), "{rows:?}");
    let host = out.markdown.lines().filter(|l| l.starts_with("| 256²")).any(|l| l.contains("130.0"));
    assert!(host, "the host time stays: {}", out.markdown);
    assert!(out.markdown.contains("`not measured (rule)` marks 1 entries"), "{}", out.markdown);
    let row = out.markdown.lines().find(|l| l.starts_with("| 4096²")).expect("4096 row").to_string();
    assert!(row.contains("900.0") && !row.contains("not measured"), "{row}");
}

/// The cells (by index) whose findings an explanation lifted.
fn explained_cells(found: &[Finding]) -> Vec<usize> {
    found.iter().filter(|f| f.explained.is_some()).map(|f| f.cell).collect()
}

#[test]
fn an_explanation_lifts_only_the_findings_it_names() {
    // Rule c finds all four cells (static/dynamic x 1024²/4096²); an explanation naming one cell
    // by every field lifts that one, and changing any one field moves it or lifts none: an
    // explanation written for one cell must not lift its neighbours' marks.
    let (c, r) = table(CONFIG, [0.01, 0.01, 1.0, 1.1], QUIET_EYE, Some(15.0));
    assert_eq!(rules(&check(&c, &r)).len(), 4, "{:?}", check(&c, &r));
    let exact = [
        ("rule", "\"c\""),
        ("metric", "\"Gather\""),
        ("scene", "\"sphere_on_plane\""),
        ("technique", "\"copy\""),
        ("photons", "1024"),
        ("lighting", "\"static\""),
        ("device", "\"synthetic\""),
    ];
    let with = |fields: &[(&str, &str)]| {
        let body: String = fields.iter().map(|(k, v)| format!("{k} = {v}\n")).collect();
        let text = format!("{CONFIG}\n[[plausibility.explained]]\n{body}why = \"named by the test\"\n");
        let (c, r) = table(&text, [0.01, 0.01, 1.0, 1.1], QUIET_EYE, Some(15.0));
        explained_cells(&check(&c, &r))
    };
    assert_eq!(with(&exact), vec![0], "every field names cell 0");
    let changed = [
        ("rule", "\"a\"", vec![]),
        ("metric", "\"Eye\"", vec![]),
        ("scene", "\"bunny_in_room\"", vec![]),
        ("technique", "\"gather\"", vec![]),
        ("photons", "4096", vec![2]),
        ("lighting", "\"dynamic\"", vec![1]),
        ("device", "\"llvmpipe\"", vec![]),
    ];
    for (field, value, want) in changed {
        let fields: Vec<(&str, &str)> =
            exact.iter().map(|&(k, v)| if k == field { (k, value) } else { (k, v) }).collect();
        assert_eq!(with(&fields), want, "{field} = {value}");
    }
    // A field left out matches every cell: lighting out, both 1024² cells.
    let fields: Vec<(&str, &str)> = exact.iter().copied().filter(|(k, _)| *k != "lighting").collect();
    assert_eq!(with(&fields), vec![0, 1]);
}

#[test]
fn c_counts_every_light_and_leaves_a_zero_time_alone() {
    // Two lights copy twice the bytes: 4096² x 32 B x 2 = 1074 MB in 50 ms is 21.5 GB/s, above
    // 15 GB/s x 1.1; one light's 537 MB in 50 ms (10.7 GB/s) is not.
    let (c, mut r) = table(CONFIG, [1.0, 1.0, 50.0, 55.0], QUIET_EYE, Some(15.0));
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    r.cells[2].cell.lights = 2;
    assert_eq!(rules(&check(&c, &r)), vec![("c".into(), "Gather".into(), 2)]);
    // A copy that reads 0 ms is no rate: rule c leaves it to the rules that compare times.
    let (c, r) = table(CONFIG, [0.0, 1.0, 50.0, 55.0], QUIET_EYE, Some(15.0));
    assert!(check(&c, &r).iter().all(|f| f.rule != "c"), "{:?}", check(&c, &r));
}

#[test]
fn c_a_copy_of_exactly_64_mib_gets_no_cache_allowance() {
    // 1024² x 64 B = 64 MiB exactly: held to 15 GB/s x 1.1 itself, so 67 MB in 1 ms is found,
    // and the finding does not speak of caches.
    let text = CONFIG.replace("bytes_per_photon = 32", "bytes_per_photon = 64");
    assert_ne!(text, CONFIG);
    let (c, r) = table(&text, [1.0, 1.0, 200.0, 220.0], QUIET_EYE, Some(15.0));
    let found = check(&c, &r);
    assert_eq!(rules(&found), vec![("c".into(), "Gather".into(), 0), ("c".into(), "Gather".into(), 1)]);
    assert!(found.iter().all(|f| !f.text.contains("caches")), "{found:?}");
}

#[test]
fn d_twice_the_smallest_is_the_bound_and_zero_is_no_value() {
    let quiet = [10.0, 10.0, 40.0, 40.0];
    // Exactly twice: not more than twice.
    let (c, r) = table(CONFIG, quiet, [5.0, 5.0, 10.0, 10.0], None);
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
    let (c, r) = table(CONFIG, quiet, [5.0, 5.0, 10.1, 10.0], None);
    assert_eq!(rules(&check(&c, &r)), vec![("d".into(), "Eye".into(), 2)]);
    // A zero is no time to compare with.
    let (c, r) = table(CONFIG, quiet, [0.0, 5.0, 5.0, 5.0], None);
    assert!(check(&c, &r).is_empty(), "{:?}", check(&c, &r));
}

#[test]
fn e_the_share_and_the_gap_are_bounds_not_findings() {
    let text = format!("{HEADER}{TRACE}");
    let e = |gpu: f64, host: f64| {
        let (c, r) = grid(&text, &["trace"], &[256, 4096], |_, p| {
            if p == 256 {
                vec![("Trace", gpu), ("Trace (host)", host)]
            } else {
                vec![("Trace", 900.0), ("Trace (host)", 910.0)]
            }
        });
        check(&c, &r).iter().filter(|f| f.rule == "e").count()
    };
    let share = bench::plausibility::RULE_E_SHARE;
    // Exactly a tenth of the host time is not under it; just under is.
    assert_eq!(e(share * 150.0, 150.0), 0);
    assert_eq!(e(share * 150.0 * 0.99, 150.0), 1);
    // Exactly 1 ms below the host time is not more than 1 ms below (0.0625 and 1.0625 are exact).
    assert_eq!(e(0.0625, 1.0625), 0);
    assert_eq!(e(0.0625, 1.07), 1);
    // The gap is the host time less the device's: 0.95 - 0.06 is under 1 ms (their sum is not).
    assert_eq!(e(0.06, 0.95), 0);
}
