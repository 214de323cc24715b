//! The plausibility rules (`bench::plausibility`) on synthetic tables: each rule trips on a
//! table that breaks it and stays quiet on one that does not; a finding marks its entry `?` and
//! is listed under the table and kept in the JSON; an explanation in the config lifts the `?`.

mod common;
use bench::config::Config;
use bench::plausibility::{check, Finding};
use bench::results::{CellResult, Results};
use common::{cell, results, value};

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
fn c_a_copy_faster_than_memory_is_flagged_above_64_mib() {
    // 4096² x 32 B = 537 MB: in 1 ms that is 537 GB/s, above 15 GB/s; in 50 ms, 10.7 GB/s.
    let (c, r) = table(CONFIG, [0.01, 0.01, 1.0, 1.1], QUIET_EYE, Some(15.0));
    let found = check(&c, &r);
    assert_eq!(
        rules(&found),
        vec![("c".into(), "Gather".into(), 2), ("c".into(), "Gather".into(), 3)],
        "1024² (34 MB) is not judged"
    );
    assert!(found[0].text.contains("GB/s"), "{}", found[0].text);
    let (c, r) = table(CONFIG, [0.01, 0.01, 50.0, 55.0], QUIET_EYE, Some(15.0));
    assert!(check(&c, &r).is_empty());
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
        serde_json::from_str(&std::fs::read_to_string(dir.join("dev/synthetic.json")).expect("json")).expect("parses");
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
    let json = dir.join("synthetic/synthetic.json");
    let read = || -> Results { serde_json::from_str(&std::fs::read_to_string(&json).expect("json")).expect("parses") };
    let before = read();
    let loaded = |text: &str| bench::LoadedConfig {
        path: dir.join("synthetic.toml"),
        name: "synthetic".into(),
        hash: bench::config::fnv1a(text.as_bytes()),
        text: text.into(),
        config: toml::from_str(text).expect("parses"),
    };
    // A config changed in more than its explanations is refused, and the table left alone.
    let more_photons = CONFIG.replace("photons = [1024, 4096]", "photons = [1024, 2048]");
    let Err(err) = bench::explain::explain(&loaded(&more_photons), &json, &dir, "abc1234") else {
        panic!("a config changed in its matrix was accepted")
    };
    let msg = format!("{err:#}");
    assert!(msg.contains("synthetic.toml") && msg.contains("run the table again"), "{msg}");
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
    std::fs::write(&json, serde_json::to_string(&judged_otherwise).expect("json")).expect("write");
    let Err(err) = bench::explain::explain(&loaded(CONFIG), &json, &dir, "abc1234") else {
        panic!("other findings accepted")
    };
    assert!(format!("{err:#}").contains("the rules changed since the run"), "{err:#}");
    std::fs::write(&json, serde_json::to_string(&before).expect("json")).expect("restore");
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
