//! The registry of variants (`crates/caustics/src/techniques/variants.toml`) against what
//! names its rows by hand: the techniques of the quality and front configs (each is a row:
//! their committed tables embed the configs' hashes, so the configs are checked, not
//! generated), the README's technique table and `docs/command_line.md`'s flags (each row's
//! technique and flags are documented, every value it uses listed).

use caustics::techniques::variants::{registry, Variant};
use caustics::techniques::{CausticOverrides, CausticSettings};
use std::path::PathBuf;

fn repo(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").join(path)
}

fn read(path: &str) -> String {
    std::fs::read_to_string(repo(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The settings in effect, less the matrix's axes and the quality tables' Fresnel (a config
/// sets `photons` and `fresnel` for every technique alike).
fn in_effect(o: &CausticOverrides) -> CausticSettings {
    let mut s = CausticSettings::default();
    o.apply(&mut s);
    let d = CausticSettings::default();
    s.photons = d.photons;
    s.fresnel = d.fresnel;
    s
}

#[test]
fn every_technique_of_the_quality_and_front_configs_is_a_registry_row() {
    let rows = registry().expect("the registry");
    let configs = ["bench_configs/quality.toml", "bench_configs/quality_wd2006.toml", "bench_configs/front.toml"];
    let mut missing = vec![];
    for path in configs {
        let config: bench::config::Config = toml::from_str(&read(path)).unwrap_or_else(|e| panic!("{path}: {e}"));
        for t in &config.techniques {
            let want = in_effect(&t.settings);
            if !rows.iter().any(|v| in_effect(&v.settings) == want) {
                missing.push(format!("{path}: [[technique]] `{}` ({:?})", t.label, t.settings.keys_set()));
            }
        }
    }
    assert!(missing.is_empty(), "not in the registry of variants:\n{}", missing.join("\n"));
}

/// The lines of the README's technique table (from its header to the first line that is not a
/// table row).
fn readme_technique_table() -> Vec<String> {
    let readme = read("README.md");
    let start = readme.lines().position(|l| l.starts_with("| `--technique` |")).expect("the README's technique table");
    readme.lines().skip(start + 2).take_while(|l| l.starts_with('|')).map(str::to_string).collect()
}

/// Each flag of `v` with its value: `("--splat", "thin-lens")`.
fn flag_pairs(v: &Variant) -> Vec<(String, String)> {
    v.flags().chunks(2).map(|p| (p[0].clone(), p[1].clone())).collect()
}

#[test]
fn the_readme_names_every_row_s_technique_and_flags() {
    let table = readme_technique_table();
    let mut missing = vec![];
    for v in registry().expect("the registry") {
        let t = format!("`{}`", v.technique());
        if !table.iter().any(|l| l.split('|').nth(1).is_some_and(|first| first.contains(&t))) {
            missing.push(format!("{}: technique {t} has no row", v.name));
        }
        for (flag, _) in flag_pairs(&v).into_iter().filter(|(f, _)| f != "--technique") {
            // The flag as a whole word in a code span: `--splat` or `--splat fixed\|...`, not
            // `--splat-path`.
            let named = |l: &String| l.contains(&format!("`{flag}`")) || l.contains(&format!("`{flag} "));
            if !table.iter().any(named) {
                missing.push(format!("{}: {flag} is in no row's flags", v.name));
            }
        }
    }
    assert!(missing.is_empty(), "README.md's technique table:\n{}", missing.join("\n"));
}

#[test]
fn the_command_line_page_lists_every_row_s_flags_and_values() {
    let page = read("docs/command_line.md");
    let mut missing = vec![];
    for v in registry().expect("the registry") {
        for (flag, value) in flag_pairs(&v) {
            let Some(line) =
                page.lines().find(|l| l.starts_with(&format!("| `{flag}`")) || l.starts_with(&format!("| `{flag} ")))
            else {
                missing.push(format!("{}: {flag} has no row", v.name));
                continue;
            };
            // Names are listed (`a\|b` or `a`); numbers are the reader's to choose.
            let named = value.parse::<f64>().is_err();
            let listed = line.contains(&format!("`{value}`"))
                || line.contains(&format!("{value}\\|"))
                || line.contains(&format!("\\|{value}`"))
                || line.contains(&format!("\\|{value}\\|"))
                || line.contains(&format!(" {value}`"));
            if named && !listed {
                missing.push(format!("{}: {flag} {value} is not listed in its row", v.name));
            }
        }
    }
    assert!(missing.is_empty(), "docs/command_line.md's flags:\n{}", missing.join("\n"));
}
