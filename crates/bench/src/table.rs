//! The table a config lays out: rows and columns as nested axes, each entry our value (with its
//! spread, for times) and the paper's for the same cell. The Markdown, the terminal summary,
//! the CSV and the plots are all drawn from this one grid.
//!
//! The printed tables are *sections* of the grid: the columns the config picks with
//! `[[layout.column]]` (the paper's own columns, in its order), or else every column, one table
//! per metric when the columns cross the metrics with another axis.

use crate::config::Config;
use crate::format::display;
use crate::paper::PaperValue;
use crate::plan::Matrix;
use crate::results::{is_timing, CellResult, Results};
use std::collections::BTreeMap;

/// One table entry.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Every axis's label for this entry (metric included).
    pub keys: BTreeMap<String, String>,
    pub ours: Option<f64>,
    /// Times: interquartile range of the per-frame samples over their median.
    pub spread: Option<f64>,
    pub paper: Option<PaperValue>,
    pub kind: String,
    /// The cell's technique cannot run at its photon count ([`Config::runs`]): no cell was
    /// measured, and the entry reads N/A.
    pub not_run: bool,
    /// The cell could run but is not in a table merged with `--partial` (the run was cut off
    /// before it): the entry reads `not run`.
    pub missing: bool,
    /// A plausibility rule found this entry implausible and nothing explains it (`?`).
    pub implausible: bool,
    /// The rule (c, e or f: [`crate::plausibility::UNMEASURED_RULES`]) that found this entry
    /// beyond what the device can do, explained or not: its value is not what the device did
    /// (its clock missed the work), so the entry reads `not measured (rule)`, not a number.
    pub unmeasured: Option<String>,
    /// The cell ran while other processes kept the machine busy (`~`).
    pub busy: bool,
    /// A timed entry whose cell was measured again for its spread (`spread_attempts`).
    pub remeasured: bool,
}

impl Entry {
    pub fn noisy(&self) -> bool {
        self.spread.is_some_and(crate::stats::is_noisy)
    }
}

/// One column of the layout: a label per column axis and the header it prints under.
#[derive(Debug, Clone)]
pub struct Column {
    pub labels: Vec<String>,
    pub header: String,
}

/// One printed table: a title (the metric, when a table is split by metric) and its columns.
#[derive(Debug, Clone)]
pub struct Section {
    pub metric: Option<String>,
    /// Indices into [`Grid::cols`].
    pub cols: Vec<usize>,
}

pub struct Grid {
    pub row_axes: Vec<String>,
    pub col_axes: Vec<String>,
    /// Each row's labels, one per row axis.
    pub rows: Vec<Vec<String>>,
    /// Every column of the layout (the product of its column axes).
    pub cols: Vec<Column>,
    /// entries[row][col].
    pub entries: Vec<Vec<Entry>>,
    pub sections: Vec<Section>,
}

fn product(axes: &[String], keys: &dyn Fn(&str) -> Vec<String>) -> Vec<Vec<String>> {
    let mut out: Vec<Vec<String>> = vec![vec![]];
    for a in axes {
        out = out.iter().flat_map(|p| keys(a).into_iter().map(move |k| [p.clone(), vec![k]].concat())).collect();
    }
    out
}

/// The cell of `results` whose labels match `keys` on every non-metric axis.
pub(crate) fn find<'r>(results: &'r Results, keys: &BTreeMap<String, String>) -> Option<&'r CellResult> {
    results.cells.iter().find(|c| keys.iter().filter(|(a, _)| *a != "metric").all(|(a, k)| c.cell.key(a) == *k))
}

fn header_of(axes: &[String], labels: &[String], skip: Option<&str>) -> String {
    axes.iter()
        .zip(labels)
        .filter(|(a, _)| Some(a.as_str()) != skip)
        .map(|(a, k)| display(a, k))
        .collect::<Vec<_>>()
        .join(" · ")
}

pub fn grid(config: &Config, results: &Results) -> Grid {
    let quick = results.run.quick.then_some(&config.quick);
    let matrix = Matrix::new(config, quick);
    let keys = |a: &str| matrix.keys(config, a);
    let (row_axes, col_axes) = (config.layout.rows.clone(), config.layout.columns.clone());
    let rows = product(&row_axes, &keys);
    let col_labels = product(&col_axes, &keys);
    // Axes outside the layout have exactly one value.
    let fixed: Vec<(String, String)> = crate::config::AXES
        .iter()
        .filter(|a| !row_axes.iter().chain(&col_axes).any(|x| x == *a))
        .filter_map(|a| keys(a).first().map(|k| (a.to_string(), k.clone())))
        .collect();
    let entries = rows
        .iter()
        .map(|r| {
            col_labels
                .iter()
                .map(|c| {
                    let mut k: BTreeMap<String, String> = fixed.iter().cloned().collect();
                    k.extend(row_axes.iter().cloned().zip(r.iter().cloned()));
                    k.extend(col_axes.iter().cloned().zip(c.iter().cloned()));
                    entry(config, results, k)
                })
                .collect()
        })
        .collect();
    let by_metric = col_axes.len() > 1 && col_axes.iter().any(|a| a == "metric") && config.metrics.len() > 1;
    let skip = by_metric.then_some("metric");
    let mut cols: Vec<Column> =
        col_labels.iter().map(|l| Column { labels: l.clone(), header: header_of(&col_axes, l, skip) }).collect();
    let sections = if !config.layout.pick.is_empty() {
        let mut picked = vec![];
        for p in &config.layout.pick {
            let want = crate::paper::column_axes(p);
            let found = (0..cols.len()).find(|&ci| {
                want.iter().all(|(a, v)| col_axes.iter().position(|x| x == a).is_some_and(|i| cols[ci].labels[i] == *v))
            });
            if let Some(ci) = found {
                if let Some(h) = &p.header {
                    cols[ci].header = h.clone();
                } else {
                    cols[ci].header = header_of(&col_axes, &cols[ci].labels, None);
                }
                picked.push(ci);
            }
        }
        vec![Section { metric: None, cols: picked }]
    } else if by_metric {
        let m = col_axes.iter().position(|a| a == "metric").unwrap_or(0);
        config
            .metrics
            .iter()
            .map(|mt| Section {
                metric: Some(mt.label.clone()),
                cols: (0..cols.len()).filter(|&ci| cols[ci].labels[m] == mt.label).collect(),
            })
            .collect()
    } else {
        vec![Section { metric: None, cols: (0..cols.len()).collect() }]
    };
    Grid { row_axes, col_axes, rows, cols, entries, sections }
}

fn entry(config: &Config, results: &Results, keys: BTreeMap<String, String>) -> Entry {
    let metric = keys.get("metric").cloned().unwrap_or_default();
    let kind = config.metric_kind(&metric).unwrap_or_default().to_string();
    let found = find(results, &keys);
    let value = found.and_then(|cell| cell.metrics.get(&metric));
    let ours = value.and_then(|v| v.value);
    let spread = value.and_then(|v| crate::results::timed_spread(&kind, v));
    let paper = crate::paper::value(config, &keys);
    let technique = keys.get("technique").and_then(|l| config.techniques.iter().position(|t| t.label == *l));
    let photons = keys.get("photons").and_then(|p| p.parse().ok());
    let not_run = matches!((technique, photons), (Some(t), Some(p)) if !config.runs(t, p));
    let missing = !not_run && found.is_none() && !results.run.not_run.is_empty();
    let implausible = found.is_some_and(|c| {
        results.plausibility.iter().any(|f| f.cell == c.cell.index && f.metric == metric && f.explained.is_none())
    });
    let unmeasured = found.and_then(|c| {
        results
            .plausibility
            .iter()
            .find(|f| {
                f.cell == c.cell.index
                    && f.metric == metric
                    && crate::plausibility::UNMEASURED_RULES.contains(&f.rule.as_str())
            })
            .map(|f| f.rule.clone())
    });
    let (ours, spread) = if unmeasured.is_some() { (None, None) } else { (ours, spread) };
    let busy = found.is_some_and(|c| c.busy) && is_timing(&kind);
    let remeasured = found.is_some_and(|c| c.spread_attempts.len() > 1) && is_timing(&kind);
    Entry { keys, ours, spread, paper, kind, not_run, missing, implausible, unmeasured, busy, remeasured }
}

impl Grid {
    /// The entry with `keys` changed to `baseline` on `axis` (for ratios).
    pub fn baseline_of(&self, e: &Entry, axis: &str, baseline: &str) -> Option<&Entry> {
        let mut want = e.keys.clone();
        want.insert(axis.to_string(), baseline.to_string());
        self.entries.iter().flatten().find(|x| x.keys == want)
    }

    /// The metric of column `ci`, when the metric is a column axis or fixed (not a row axis).
    pub fn metric_of(&self, ci: usize) -> Option<String> {
        if self.row_axes.iter().any(|a| a == "metric") {
            return None;
        }
        self.entries.first()?.get(ci)?.keys.get("metric").cloned()
    }

    /// Any paper value anywhere in the grid?
    pub fn has_paper(&self) -> bool {
        self.entries.iter().flatten().any(|e| e.paper.is_some())
    }

    /// A row's labels as printed, one per row axis.
    pub fn row_labels(&self, ri: usize) -> Vec<String> {
        self.row_axes.iter().zip(&self.rows[ri]).map(|(a, k)| display(a, k)).collect()
    }
}
