//! `causticlab bench explain CONFIG TABLE.json.gz`: a committed table read again with what its
//! config says of how to read it, without timing anything again. An explanation is a reading of
//! the numbers, not a number: it may come after them. So may everything else that measures
//! nothing ([`what_was_measured`] drops it): the `[table]` text (caption, notes, plot scale),
//! the `[layout]` (which axes are rows and columns), the `source` of the `[[paper]]` entries
//! (where in the paper the published values are: a citation; the values themselves are cells
//! of the table, beside ours and in its ratios, and stay), the judging of the cells
//! (`[plausibility]`: the axes the work grows with and the explanations; a metric's
//! `independent_of`, `not_monotonic`, `absent` and `bytes_per_photon`), the `[front]` (how the
//! cells are drawn and summed up, and which other table's curves are drawn beside them:
//! `crate::front_curves`, read again here) and, for a full table, the `[quick]` sizes. They are
//! compared as TOML values, so comments and layout may change too; anything else (the matrix,
//! the run, the caustic settings, a technique or a metric's passes, kind or frame mode) would
//! make the table describe a run that did not happen, and is refused. The table then embeds
//! the new config and says under its commit line which commit read it again, and the config's
//! hash when measured.

use crate::config::LoadedConfig;
use crate::results::Explained;
use crate::run::{device_dir, write_table, Outcome};
use anyhow::Result;
use caustics::input_error;
use std::path::Path;

/// What a metric's entry may change after the run: how its cells are judged (`independent_of`,
/// `not_monotonic`, `bytes_per_photon`) and why some may read n/a (`absent`, once added: a run
/// that recorded no such pass failed without it, so the table has none to read; taken away, it
/// would have failed a run that the table's n/a cells show passed, and is a difference).
const METRIC_READING: [&str; 4] = ["independent_of", "not_monotonic", "absent", "bytes_per_photon"];

/// A config's text as a TOML value; `what` names it in the error.
pub(crate) fn parse(text: &str, what: &str) -> Result<toml::Value> {
    Ok(toml::from_str(text).map_err(|e| input_error!("{what}: does not parse: {e}"))?)
}

/// The config without what measures nothing (see the module): what must not change after the
/// run. `quick`: the table is a `--quick` run's, which the `[quick]` sizes made.
fn what_was_measured(mut v: toml::Value, quick: bool) -> toml::Value {
    if let Some(t) = v.as_table_mut() {
        for key in ["table", "layout", "plausibility", "front"] {
            t.remove(key);
        }
        if !quick {
            t.remove("quick");
        }
    }
    // A paper's value stays: it is a cell of the table (beside ours, and in the ratio).
    if let Some(entries) = v.get_mut("paper").and_then(|p| p.as_array_mut()) {
        for e in entries.iter_mut().filter_map(|e| e.as_table_mut()) {
            e.remove("source");
        }
    }
    if let Some(entries) = v.get_mut("metric").and_then(|p| p.as_array_mut()) {
        for e in entries.iter_mut().filter_map(|e| e.as_table_mut()) {
            for key in METRIC_READING {
                e.remove(key);
            }
        }
    }
    v
}

/// The labels of the metrics of `v` that say why they may read n/a (`absent`).
fn absent(v: &toml::Value) -> Vec<&str> {
    let entries = v.get("metric").and_then(|p| p.as_array()).into_iter().flatten();
    entries
        .filter(|e| e.get("absent").is_some())
        .map(|e| e.get("label").and_then(|l| l.as_str()).unwrap_or_default())
        .collect()
}

/// The keys (`crate::drift::differences`) where `today`'s config differs from `measured`'s, the
/// table's, in what was measured: empty when `bench explain` may read the table with it.
pub(crate) fn measured_differences(measured: &toml::Value, today: &toml::Value, quick: bool) -> Vec<String> {
    let mut keys = crate::drift::differences(
        &what_was_measured(measured.clone(), quick),
        &what_was_measured(today.clone(), quick),
    );
    let now = absent(today);
    for label in absent(measured).into_iter().filter(|l| !now.contains(l)) {
        keys.push(format!("metric[{label:?}].absent (taken away)"));
    }
    keys
}

/// Judges `table` (a `<config>.json.gz` the bench wrote) again with `config`'s explanations and
/// writes it back, with its Markdown, CSV and plot, into `root`'s device folder.
pub fn explain(config: &LoadedConfig, table: &Path, root: &Path, commit: &str) -> Result<Outcome> {
    let t = table.display();
    let mut r = crate::results::read(table, "table")?;
    if r.run.shard.is_some() || r.run.filter != Default::default() {
        return Err(
            input_error!("{t}: a part of a table (a shard or a --filter run): `bench merge` the parts first").into()
        );
    }
    if r.config.name != config.name {
        return Err(input_error!(
            "{t}: the table of `{}`, not of {} (`{}`)",
            r.config.name,
            config.path.display(),
            config.name
        )
        .into());
    }
    let keys = measured_differences(
        &parse(&r.config.toml, &format!("{t}: the embedded config"))?,
        &parse(&config.text, &config.path.display().to_string())?,
        r.run.quick,
    );
    if !keys.is_empty() {
        return Err(input_error!(
            "{}: differs from the config {t} was measured with (hash {}) in what it measures ({}): run the table again",
            config.path.display(),
            r.run.explained.as_ref().map_or(&r.config.hash, |e| &e.measured_config_hash),
            keys.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")
        )
        .into());
    }
    // The table is rewritten where the bench keeps it: only from that file, so that a copy or an
    // older table cannot replace it.
    let home = crate::results::table_file(&device_dir(root, &r), &r.config.name)?;
    let same = |a: &Path, b: &Path| matches!((a.canonicalize(), b.canonicalize()), (Ok(a), Ok(b)) if a == b);
    if !same(table, &home) {
        return Err(input_error!(
            "{t}: not the table in the results folder ({}): explain the table where the bench wrote it, or pass that folder's root as --results",
            home.display()
        )
        .into());
    }
    // The rules must be the run's: judged with the config it embeds (which wrote its findings,
    // their explanations too), the table must give the findings it has. Then the new config
    // judges it (`write_table`).
    let embedded: crate::config::Config =
        toml::from_str(&r.config.toml).map_err(|e| input_error!("{t}: the embedded config does not parse: {e}"))?;
    let now = crate::plausibility::check(&embedded, &crate::results::rounded(&r)?);
    if now != r.plausibility {
        return Err(input_error!(
            "{t}: this causticlab's plausibility rules find {} entries where the run's found {}: the rules changed since the run; run the table again",
            now.len(),
            r.plausibility.len()
        )
        .into());
    }
    let measured_config_hash =
        r.run.explained.as_ref().map_or(r.config.hash.clone(), |e| e.measured_config_hash.clone());
    r.run.explained =
        Some(Explained { commit: commit.to_string(), date: crate::meta::utc_now(), measured_config_hash });
    r.config.toml = config.text.clone();
    r.config.hash = config.hash.clone();
    let table = &config.config.table;
    (r.config.paper, r.config.table, r.config.caption) =
        (table.paper.clone(), table.number.clone(), table.caption.clone());
    let dir = device_dir(root, &r);
    write_table(&config.config, &r, &dir, root)
}

#[cfg(test)]
mod tests {
    use super::{measured_differences, parse};

    const RUN: &str = r#"
[table]
paper = "P"
number = "1"
caption = "C"

[run]
warmup_frames = 2

[layout]
rows = ["photons"]

[[paper]]
photons = 256
values = { Gather = 5.0 }

[[metric]]
label = "Gather"
kind = "pass_ms"
passes = ["splat.*"]

[[metric]]
label = "Copy"
kind = "pass_ms"
passes = ["copy"]
absent = "no copy on this path"

[quick]
photons = [64]
"#;

    fn keys(today: &str, quick: bool) -> Vec<String> {
        let v = |text: &str| parse(text, "a config").expect("both parse");
        measured_differences(&v(RUN), &v(today), quick)
    }

    #[test]
    fn what_measures_nothing_may_change_and_the_rest_is_named() {
        let gather = "passes = [\"splat.*\"]\n";
        // Each of these measures nothing: no key is named.
        let reading = [
            RUN.replace("caption = \"C\"", "caption = \"D\"\nnotes = [\"n\"]\nplot_log_y = true"),
            RUN.replace("rows = [\"photons\"]", "rows = [\"photons\"]\ncolumns = [\"metric\"]"),
            RUN.replace("values = { Gather = 5.0 }", "values = { Gather = 5.0 }\nsource = \"Table 1\""),
            RUN.replace(gather, &format!("{gather}independent_of = [\"photons\"]\nnot_monotonic = \"why\"")),
            RUN.replace(gather, &format!("{gather}bytes_per_photon = 16\nabsent = \"why\"")),
            format!("{RUN}\n[plausibility]\nwork_grows_with = [\"photons\"]\n"),
            format!("{RUN}\n[front]\nx = 1\n"),
            RUN.replace("photons = [64]", "photons = [32]"),
        ];
        for today in &reading {
            assert_eq!(keys(today, false), Vec::<String>::new(), "{today}");
        }
        // The [quick] sizes made a --quick table.
        assert_eq!(keys(&reading[7], true), ["quick.photons"]);
        // What was measured, and the papers' values (cells of the table), are named.
        assert_eq!(keys(&RUN.replace("warmup_frames = 2", "warmup_frames = 3"), false), ["run.warmup_frames"]);
        assert_eq!(keys(&RUN.replace("Gather = 5.0", "Gather = 6.0"), false), ["paper[0].values.Gather"]);
        assert_eq!(keys(&RUN.replace(gather, "passes = [\"splat\"]\n"), false), ["metric[\"Gather\"].passes"]);
        // `absent` taken away: the table's n/a cells show a run that config would fail.
        assert_eq!(
            keys(&RUN.replace("absent = \"no copy on this path\"\n", ""), false),
            ["metric[\"Copy\"].absent (taken away)"]
        );
        assert!(format!("{:#}", parse("[run", "today.toml").unwrap_err()).contains("today.toml: does not parse"));
    }
}
