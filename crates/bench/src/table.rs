//! The table a config lays out: rows and columns as nested axes, each entry our value and the
//! paper's for the same cell. Markdown, CSV and the plot are all drawn from this one grid.

use crate::config::Config;
use crate::plan::Matrix;
use crate::results::{CellResult, Results};
use std::collections::BTreeMap;

/// One table entry.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Every axis's label for this entry (metric included).
    pub keys: BTreeMap<String, String>,
    pub ours: Option<f64>,
    pub paper: Option<f64>,
    pub kind: String,
}

pub struct Grid {
    pub row_axes: Vec<String>,
    pub col_axes: Vec<String>,
    /// Each row's labels, one per row axis.
    pub rows: Vec<Vec<String>>,
    pub cols: Vec<Vec<String>>,
    /// entries[row][col].
    pub entries: Vec<Vec<Entry>>,
}

fn product(axes: &[String], keys: &dyn Fn(&str) -> Vec<String>) -> Vec<Vec<String>> {
    let mut out: Vec<Vec<String>> = vec![vec![]];
    for a in axes {
        out = out.iter().flat_map(|p| keys(a).into_iter().map(move |k| [p.clone(), vec![k]].concat())).collect();
    }
    out
}

/// The cell of `results` whose labels match `keys` on every non-metric axis.
fn find<'r>(results: &'r Results, keys: &BTreeMap<String, String>) -> Option<&'r CellResult> {
    results.cells.iter().find(|c| keys.iter().filter(|(a, _)| *a != "metric").all(|(a, k)| c.cell.key(a) == *k))
}

pub fn grid(config: &Config, results: &Results) -> Grid {
    let quick = results.run.quick.then_some(&config.quick);
    let matrix = Matrix::new(config, quick);
    let keys = |a: &str| matrix.keys(config, a);
    let (row_axes, col_axes) = (config.layout.rows.clone(), config.layout.columns.clone());
    let rows = product(&row_axes, &keys);
    let cols = product(&col_axes, &keys);
    // Axes outside the layout have exactly one value.
    let fixed: Vec<(String, String)> = crate::config::AXES
        .iter()
        .filter(|a| !row_axes.iter().chain(&col_axes).any(|x| x == *a))
        .filter_map(|a| keys(a).first().map(|k| (a.to_string(), k.clone())))
        .collect();
    let entries = rows
        .iter()
        .map(|r| {
            cols.iter()
                .map(|c| {
                    let mut k: BTreeMap<String, String> = fixed.iter().cloned().collect();
                    k.extend(row_axes.iter().cloned().zip(r.iter().cloned()));
                    k.extend(col_axes.iter().cloned().zip(c.iter().cloned()));
                    let metric = k.get("metric").cloned().unwrap_or_default();
                    let kind =
                        config.metrics.iter().find(|m| m.label == metric).map(|m| m.kind.clone()).unwrap_or_default();
                    let ours = find(results, &k).and_then(|cell| cell.metrics.get(&metric)).and_then(|v| v.value);
                    let paper = crate::paper::value(config, &k);
                    Entry { keys: k, ours, paper, kind }
                })
                .collect()
        })
        .collect();
    Grid { row_axes, col_axes, rows, cols, entries }
}

impl Grid {
    /// The entry with `keys` changed to `baseline` on `axis` (for ratios).
    pub fn baseline_of(&self, e: &Entry, axis: &str, baseline: &str) -> Option<&Entry> {
        let mut want = e.keys.clone();
        want.insert(axis.to_string(), baseline.to_string());
        self.entries.iter().flatten().find(|x| x.keys == want)
    }
}

/// A label as the papers print it: photon counts as N².
pub fn display(axis: &str, key: &str) -> String {
    match axis {
        "photons" => format!("{key}²"),
        "lights" if key != "scene" => format!("{key} light{}", if key == "1" { "" } else { "s" }),
        _ => key.to_string(),
    }
}

/// A value formatted for its metric kind.
pub fn format_value(kind: &str, v: Option<f64>) -> String {
    let Some(v) = v else { return "–".into() };
    if !v.is_finite() {
        return "n/a".into();
    }
    match kind {
        "pass_ms" | "gpu_frame_ms" | "frame_ms" | "fps" | "pass_fps" => significant(v),
        "photons_emitted" | "splats_drawn" | "photons_processed" => thousands(v.round() as u64),
        "rel_rmse" | "flux_ratio" => format!("{v:.4}"),
        _ => format!("{v}"),
    }
}

/// A time or a rate with at least three significant digits and at most one decimal above 10, so
/// that lavapipe's 0.013 fps and a GPU's 0.024 ms passes do not print as 0.0.
fn significant(v: f64) -> String {
    let a = v.abs();
    if a >= 10.0 || a == 0.0 {
        return format!("{v:.1}");
    }
    // Digits before the decimal point are 1 for a ≥ 1; below 1, leading zeros add decimals.
    let decimals = (2.0 - a.log10().floor()).max(2.0) as usize;
    format!("{v:.decimals$}")
}

fn thousands(n: u64) -> String {
    let digits: Vec<char> = n.to_string().chars().collect();
    let head = digits.len() % 3;
    let mut groups: Vec<String> = vec![];
    if head > 0 {
        groups.push(digits[..head].iter().collect());
    }
    groups.extend(digits[head..].chunks(3).map(|c| c.iter().collect::<String>()));
    groups.join(",")
}

/// The unit of a metric kind, for headers and plot axes.
pub fn unit(kind: &str) -> &'static str {
    match kind {
        "pass_ms" | "gpu_frame_ms" | "frame_ms" => "ms",
        "fps" | "pass_fps" => "fps",
        "photons_emitted" => "photons",
        "splats_drawn" | "photons_processed" => "points",
        _ => "",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formatting() {
        assert_eq!(thousands(16777216), "16,777,216");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(format_value("pass_ms", Some(4.256)), "4.26");
        assert_eq!(format_value("pass_ms", Some(861.54)), "861.5");
        assert_eq!(format_value("fps", None), "–");
        assert_eq!(format_value("fps", Some(32.44)), "32.4");
        assert_eq!(format_value("fps", Some(3.456)), "3.46");
        assert_eq!(format_value("fps", Some(0.01234)), "0.0123");
        assert_eq!(format_value("pass_ms", Some(0.5)), "0.500");
        assert_eq!(format_value("fps", Some(0.0)), "0.0");
        assert_eq!(display("photons", "256"), "256²");
        assert_eq!(display("lights", "2"), "2 lights");
    }
}
