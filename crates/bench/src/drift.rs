//! How a written table's config differs from its config file today: a table is the run of the
//! config it embeds, and a config edited since (a frame mode, an orbit, a technique's setting)
//! describes a run that did not happen. The index (`results/README.md`) says so for every
//! table, so that a reader citing a number knows whether today's config would measure it the
//! same way, or needs the table run again.
//!
//! Compared as TOML values, so comments and layout are not differences. What `bench explain`
//! may change after the run (what measures nothing: the text, the layout, the papers' sources,
//! how the cells are judged, the front; `crate::explain`) is a change of how the table is read,
//! not of what it measured, and is told apart. Only the config file is compared: the code that
//! ran it may have changed too (the table names its commit).

use std::path::Path;

/// A table's config against the file it names, today.
#[derive(Debug, Clone, PartialEq)]
pub enum Drift {
    /// The file holds the config the table embeds.
    Same,
    /// They differ only in what measures nothing, which `bench explain` may change (keys named).
    Reading(Vec<String>),
    /// They differ in what was measured (keys named): the table needs running again.
    Measured(Vec<String>),
    /// The file cannot be compared (why).
    Unknown(String),
}

/// `embedded` (the table's `config.toml`) against the config file `file` (the table's
/// `config.file`), looked for relative to each of `roots` in turn; `quick`: the table is a
/// `--quick` run's.
pub fn drift(embedded: &str, file: &str, roots: &[&Path], quick: bool) -> Drift {
    let Some(path) = roots.iter().map(|r| r.join(file)).find(|p| p.is_file()) else {
        return Drift::Unknown(format!("`{file}` is not there"));
    };
    let today = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => return Drift::Unknown(format!("`{file}`: {e}")),
    };
    let parse = |text: &str| toml::from_str::<toml::Value>(text);
    let (Ok(then), Ok(now)) = (parse(embedded), parse(&today)) else {
        return Drift::Unknown(format!("`{file}` or the table's copy does not parse"));
    };
    let all = differences(&then, &now);
    if all.is_empty() {
        return Drift::Same;
    }
    let measured = crate::explain::measured_differences(&then, &now, quick);
    if measured.is_empty() {
        Drift::Reading(all)
    } else {
        Drift::Measured(measured)
    }
}

/// The keys where `a` and `b` differ, as dotted paths: `run.period_frames`; an entry of an
/// array of tables by its `label` where every entry has one (`metric["fps"].mode`), else by
/// its position (`paper[2].fps`); an entry on one side only by itself (`technique["fast"]`).
pub fn differences(a: &toml::Value, b: &toml::Value) -> Vec<String> {
    let mut out = vec![];
    walk(a, b, "", &mut out);
    out
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

fn walk(a: &toml::Value, b: &toml::Value, path: &str, out: &mut Vec<String>) {
    use toml::Value::{Array, Table};
    match (a, b) {
        (Table(x), Table(y)) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
            keys.sort();
            keys.dedup();
            for k in keys {
                match (x.get(k), y.get(k)) {
                    (Some(p), Some(q)) => walk(p, q, &join(path, k), out),
                    _ => out.push(join(path, k)),
                }
            }
        }
        (Array(x), Array(y)) if labelled(x) && labelled(y) => {
            let label = |v: &toml::Value| v.get("label").and_then(|l| l.as_str()).unwrap_or_default().to_string();
            let before = out.len();
            let mut seen = std::collections::BTreeSet::new();
            for l in x.iter().chain(y).map(label).filter(|l| seen.insert(l.clone())) {
                let here = format!("{path}[{l:?}]");
                match (x.iter().find(|v| label(v) == l), y.iter().find(|v| label(v) == l)) {
                    (Some(p), Some(q)) => walk(p, q, &here, out),
                    _ => out.push(here),
                }
            }
            // The same entries in another order: another order of the table's rows or columns.
            if out.len() == before && !x.iter().map(label).eq(y.iter().map(label)) {
                out.push(format!("{path} (order)"));
            }
        }
        (Array(x), Array(y)) if x.len() == y.len() && x.iter().chain(y).all(|v| v.is_table()) => {
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                walk(p, q, &format!("{path}[{i}]"), out);
            }
        }
        _ => {
            if a != b {
                out.push(path.to_string());
            }
        }
    }
}

/// An array of tables whose every entry has a distinct string `label`.
fn labelled(v: &[toml::Value]) -> bool {
    let labels: Vec<&str> = v.iter().filter_map(|e| e.get("label").and_then(|l| l.as_str())).collect();
    !v.is_empty()
        && labels.len() == v.len()
        && labels.iter().collect::<std::collections::BTreeSet<_>>().len() == labels.len()
}

/// The index's cell for `d`: at most `shown` keys, the papers' values last (a re-run does not
/// change them), then how many more.
pub fn describe(d: &Drift, shown: usize) -> String {
    let keys = |k: &[String]| {
        let (ours, papers): (Vec<&String>, Vec<&String>) = k.iter().partition(|k| !k.starts_with("paper"));
        let mut s = ours.into_iter().chain(papers).take(shown).map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ");
        if k.len() > shown {
            s.push_str(&format!(" and {} more", k.len() - shown));
        }
        s
    };
    match d {
        Drift::Same => "same".into(),
        Drift::Reading(k) => format!("reading changed: {} (`bench explain` rewrites it)", keys(k)),
        Drift::Measured(k) => format!("**changed**: {} (run it again)", keys(k)),
        Drift::Unknown(why) => why.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(text: &str) -> toml::Value {
        toml::from_str(text).expect("toml")
    }

    #[test]
    fn keys_are_named_by_path_and_label() {
        let a = v("[run]\nperiod_frames = 40\nwarmup_frames = 2\n[[metric]]\nlabel = \"fps\"\nkind = \"fps\"\n[[metric]]\nlabel = \"Gather\"\nkind = \"pass_ms\"\n");
        let b = v("[run]\nperiod_frames = 10\nwarmup_frames = 2\n[[metric]]\nlabel = \"fps\"\nkind = \"fps\"\nmode = \"throughput\"\n[[metric]]\nlabel = \"Gather\"\nkind = \"pass_ms\"\n");
        assert_eq!(differences(&a, &b), ["metric[\"fps\"].mode", "run.period_frames"]);
        assert!(differences(&a, &a).is_empty());
        // An entry on one side only, and entries without labels by position.
        let c = v("[[metric]]\nlabel = \"fps\"\nkind = \"fps\"\n");
        assert_eq!(differences(&a, &c), ["metric[\"Gather\"]", "run"]);
        let p = v("[[paper]]\nfps = 1.0\n[[paper]]\nfps = 2.0\n");
        let q = v("[[paper]]\nfps = 1.0\n[[paper]]\nfps = 3.0\n");
        assert_eq!(differences(&p, &q), ["paper[1].fps"]);
        // The same columns in another order.
        let d = v("[[metric]]\nlabel = \"Gather\"\nkind = \"pass_ms\"\n[[metric]]\nlabel = \"fps\"\nkind = \"fps\"\n");
        let a_metrics =
            v("[[metric]]\nlabel = \"fps\"\nkind = \"fps\"\n[[metric]]\nlabel = \"Gather\"\nkind = \"pass_ms\"\n");
        assert_eq!(differences(&a_metrics, &d), ["metric (order)"]);
        // Labels that do not name every entry once: by position, or the whole array.
        let twice = v("[[metric]]\nlabel = \"x\"\nkind = \"a\"\n[[metric]]\nlabel = \"x\"\nkind = \"b\"\n");
        let twice_b = v("[[metric]]\nlabel = \"x\"\nkind = \"a\"\n[[metric]]\nlabel = \"x\"\nkind = \"c\"\n");
        assert_eq!(differences(&twice, &twice_b), ["metric[1].kind"]);
        assert_eq!(differences(&p, &v("[[paper]]\nfps = 1.0\n")), ["paper"]);
        // Labelled on one side only: by position.
        let one_unlabelled = v("[[metric]]\nlabel = \"fps\"\nkind = \"fps\"\n[[metric]]\nkind = \"pass_ms\"\n");
        let both =
            v("[[metric]]\nlabel = \"fps\"\nkind = \"fps\"\n[[metric]]\nlabel = \"Gather\"\nkind = \"pass_ms\"\n");
        assert_eq!(differences(&both, &one_unlabelled), ["metric[1].label"]);
        assert_eq!(differences(&one_unlabelled, &both), ["metric[1].label"]);
        assert_eq!(differences(&v("x = [1, 2]"), &v("x = [1, 3]")), ["x"]);
    }

    #[test]
    fn what_explain_may_change_is_a_reading_and_the_rest_a_measurement() {
        let dir = caustics::scratch::ScratchDir::new("causticlab", "drift");
        std::fs::create_dir_all(dir.join("bench_configs")).expect("a temp folder");
        let then = "[run]\nperiod_frames = 40\n";
        let write = |text: &str| std::fs::write(dir.join("bench_configs/t.toml"), text).expect("config");
        let roots = [Path::new("/nonexistent-root"), &dir];
        write("# a comment\n[run]\nperiod_frames   = 40\n");
        assert_eq!(drift(then, "bench_configs/t.toml", &roots, false), Drift::Same);
        write("[run]\nperiod_frames = 40\n[[plausibility.explained]]\nrule = \"a\"\nmetric = \"fps\"\nwhy = \"x\"\n");
        assert_eq!(drift(then, "bench_configs/t.toml", &roots, false), Drift::Reading(vec!["plausibility".into()]));
        write("[run]\nperiod_frames = 10\n[[plausibility.explained]]\nrule = \"a\"\nmetric = \"fps\"\nwhy = \"x\"\n");
        let d = drift(then, "bench_configs/t.toml", &roots, false);
        assert_eq!(d, Drift::Measured(vec!["run.period_frames".into()]));
        assert_eq!(describe(&d, 3), "**changed**: `run.period_frames` (run it again)");
        write("[run\n");
        assert!(
            matches!(drift(then, "bench_configs/t.toml", &roots, false), Drift::Unknown(w) if w.contains("does not parse"))
        );
        assert_eq!(
            drift(then, "bench_configs/gone.toml", &roots, false),
            Drift::Unknown("`bench_configs/gone.toml` is not there".into())
        );
        let many = Drift::Measured((0..5).map(|i| format!("k{i}")).collect());
        assert_eq!(describe(&many, 2), "**changed**: `k0`, `k1` and 3 more (run it again)");
        let papers_first = Drift::Measured(vec!["paper[0].fps".into(), "run.period_frames".into()]);
        assert_eq!(describe(&papers_first, 1), "**changed**: `run.period_frames` and 1 more (run it again)");
        let reading = Drift::Reading(vec!["table.notes".into()]);
        assert_eq!(describe(&reading, 3), "reading changed: `table.notes` (`bench explain` rewrites it)");
        assert_eq!(describe(&Drift::Same, 3), "same");
        let exactly = Drift::Measured(vec!["a".into(), "b".into()]);
        assert_eq!(describe(&exactly, 2), "**changed**: `a`, `b` (run it again)", "no `and 0 more`");
    }
}
