//! `causticlab bench explain CONFIG TABLE.json.gz`: a committed table judged again with the
//! explanations (`[[plausibility.explained]]`) its config gained after the run, without timing
//! anything again. An explanation is a reading of the numbers, not a number: it may come after
//! them. The config may differ from the one the table embeds in its explanations only, in
//! the `source` of its `[[paper]]` entries (where in the paper the published values are: a
//! citation, not a measurement) and in its `[front]` (how the cells are drawn and summed up,
//! and which other table's curves are drawn beside them: `crate::front_curves`, read again
//! here), compared as TOML values, so comments and layout may change too; anything else would
//! make the table describe a run that did not happen, and is refused. The table then embeds
//! the new config and says under its commit line which commit added the explanations, and the
//! config's hash when measured.

use crate::config::LoadedConfig;
use crate::plausibility::Finding;
use crate::results::Explained;
use crate::run::{device_dir, write_table, Outcome};
use anyhow::Result;
use caustics::input_error;
use std::path::Path;

/// The config's TOML without its `[[plausibility.explained]]` entries, the `source` of its
/// `[[paper]]` entries and its `[front]`: what must not change after the run.
fn what_was_measured(text: &str, what: &str) -> Result<toml::Value> {
    let mut v: toml::Value = toml::from_str(text).map_err(|e| input_error!("{what}: does not parse: {e}"))?;
    if let Some(t) = v.as_table_mut() {
        t.remove("front");
    }
    if let Some(entries) = v.get_mut("paper").and_then(|p| p.as_array_mut()) {
        for e in entries.iter_mut().filter_map(|e| e.as_table_mut()) {
            e.remove("source");
        }
    }
    if let Some(p) = v.get_mut("plausibility").and_then(|p| p.as_table_mut()) {
        p.remove("explained");
        if p.is_empty() {
            if let Some(t) = v.as_table_mut() {
                t.remove("plausibility");
            }
        }
    }
    Ok(v)
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
    let measured = what_was_measured(&r.config.toml, &format!("{t}: the embedded config"))?;
    if what_was_measured(&config.text, &config.path.display().to_string())? != measured {
        return Err(input_error!(
            "{}: differs from the config {t} was measured with (hash {}) in more than its \
             [[plausibility.explained]] entries, its [[paper]] sources and its [front]: run the table again",
            config.path.display(),
            r.run.explained.as_ref().map_or(&r.config.hash, |e| &e.measured_config_hash)
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
    // The findings must be the run's: rules changed since would change more than the explanations.
    let unexplained =
        |f: &[Finding]| -> Vec<Finding> { f.iter().cloned().map(|x| Finding { explained: None, ..x }).collect() };
    let now = crate::plausibility::check(&config.config, &crate::results::rounded(&r)?);
    if unexplained(&now) != unexplained(&r.plausibility) {
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
    let dir = device_dir(root, &r);
    write_table(&config.config, &r, &dir, root)
}
