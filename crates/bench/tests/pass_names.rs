//! Every pass a bench config selects (`passes` and `exclude` globs, anywhere in the config) is
//! one the renderer can record: each pattern matches some name built by
//! `caustics::gpu::pass_name` from its stages, views, levels, layers, refractors, batches and
//! lights. A renamed stage breaks this test, not a table run hours later (the run itself also
//! refuses a metric whose passes match nothing: `bench_input_errors.rs`).

use bench::metrics::glob;
use caustics::gpu::{BatchPart, PassName, Stage};
use std::path::PathBuf;

/// Every name the stages can make, over enough levels, layers, batches and lights for any
/// shipped config (adaptive traversals go to level 8).
fn recordable_names() -> Vec<String> {
    let mut names = vec![];
    for &stage in Stage::ALL {
        let mut bases: Vec<PassName> = vec![stage.pass()];
        bases.extend(["eye", "receiver", "light_space"].map(|v| stage.pass().view(v)));
        bases.extend((0..=8).map(|k| stage.pass().level(k)));
        bases.extend((0..4).map(|k| stage.pass().layer(k)));
        bases.extend((0..4).map(|k| stage.pass().refractor(k)));
        for base in bases {
            for part in [BatchPart::Whole, BatchPart::Breadth, BatchPart::Batch(0), BatchPart::Batch(1)] {
                let n = base.clone().batch(part);
                names.push(n.to_string());
                names.extend((0..2).map(|l| n.clone().light(l).to_string()));
            }
        }
    }
    names
}

/// The strings of every `passes` and `exclude` array in `v`, with the path to them.
fn patterns(v: &toml::Value, path: &str, out: &mut Vec<(String, String)>) {
    match v {
        toml::Value::Table(t) => {
            for (k, v) in t {
                let here = format!("{path}.{k}");
                match (k.as_str(), v) {
                    ("passes" | "exclude", toml::Value::Array(a)) => {
                        out.extend(a.iter().filter_map(|p| p.as_str()).map(|p| (here.clone(), p.to_string())))
                    }
                    _ => patterns(v, &here, out),
                }
            }
        }
        toml::Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                patterns(v, &format!("{path}[{i}]"), out);
            }
        }
        _ => {}
    }
}

#[test]
fn every_pass_a_bench_config_selects_is_one_a_stage_can_record() {
    let names = recordable_names();
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../bench_configs");
    let mut checked = 0;
    let mut unmatched = vec![];
    for e in std::fs::read_dir(&dir).expect("bench_configs/") {
        let path = e.expect("entry").path();
        if path.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("config");
        let v: toml::Value = toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut found = vec![];
        patterns(&v, "", &mut found);
        for (key, pattern) in found {
            checked += 1;
            if !names.iter().any(|n| glob(&pattern, n)) {
                unmatched.push(format!("{} {key}: `{pattern}`", path.display()));
            }
        }
    }
    assert!(checked > 50, "only {checked} patterns found: is the config layout still `passes = [..]`?");
    assert!(unmatched.is_empty(), "patterns no stage records:\n{}", unmatched.join("\n"));
}

#[test]
fn a_misspelt_stage_matches_nothing() {
    // The check can fail: a stage name with one letter off matches no recordable name.
    let names = recordable_names();
    assert!(names.iter().any(|n| glob("photon_buffer.light*", n)));
    assert!(!names.iter().any(|n| glob("photon_bufer.light*", n)));
}
