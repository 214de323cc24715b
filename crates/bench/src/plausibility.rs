//! Rules that catch timings that cannot be right, applied to every table. A finding marks its
//! entry `?`, is listed under the table and is kept in the JSON; it goes away only by a fix, or
//! by an explanation in the config (`[[plausibility.explained]]`) that cites a measurement.
//!
//! - **a** More work, less time: a cell faster than its neighbour with less work along an axis
//!   the config says grows the work (`work_grows_with`: photons and resolution by default),
//!   beyond both cells' interquartile ranges (and 1%).
//! - **b** Dynamic beats static: a `dynamic` cell faster than its `static` twin, likewise.
//! - **c** Faster than memory: a copy whose bytes (`bytes_per_photon`) over its time exceed the
//!   device's copy bandwidth, measured at the start of the run, by more than 10% (the two are
//!   measured apart); only for copies of at least 64 MiB (smaller ones may run from caches).
//! - **d** Not independent: a metric declared independent of an axis (`independent_of`) that
//!   varies by more than 2x along it; the cells above twice the smallest are marked.

use crate::config::{Config, MetricSpec};
use crate::plan::{Cell, Matrix};
use crate::results::{is_timing, CellResult, Results};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One implausible entry.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Finding {
    /// `a`, `b`, `c` or `d` (see the module).
    pub rule: String,
    pub metric: String,
    /// The flagged cell's index and its labels.
    pub cell: usize,
    pub keys: BTreeMap<String, String>,
    /// What is wrong, with the numbers.
    pub text: String,
    /// The config's explanation, where it has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub explained: Option<String>,
}

/// How far above the measured copy bandwidth rule c lets a copy go (measurement noise).
pub const RULE_C_MARGIN: f64 = 0.10;
/// Smallest copy rule c judges.
pub const RULE_C_MIN_BYTES: f64 = 64.0 * 1024.0 * 1024.0;
/// Margin beyond the interquartile ranges before rules a and b speak.
const MARGIN: f64 = 0.01;

/// (q1, median, q3) of a metric of a cell.
fn spread(c: &CellResult, metric: &str) -> Option<(f64, f64, f64)> {
    let v = c.metrics.get(metric)?;
    let m = v.value?;
    match (v.q1, v.q3) {
        (Some(a), Some(b)) => Some((a, m, b)),
        _ => crate::stats::quartiles(&v.samples).map(|(a, _, b)| (a, m, b)).or(Some((m, m, m))),
    }
}

fn lower_is_faster(kind: &str) -> bool {
    !matches!(kind, "fps" | "pass_fps" | "pass_mphotons" | "frame_mphotons")
}

/// Is `b` (with more work, or dynamic) clearly faster than `a`?
fn clearly_faster(kind: &str, a: (f64, f64, f64), b: (f64, f64, f64)) -> bool {
    if lower_is_faster(kind) {
        b.2 * (1.0 + MARGIN) < a.0
    } else {
        b.0 > a.2 * (1.0 + MARGIN)
    }
}

fn keys_of(cell: &Cell) -> BTreeMap<String, String> {
    ["scene", "technique", "photons", "lights", "resolution", "lighting"]
        .iter()
        .map(|a| (a.to_string(), cell.key(a)))
        .collect()
}

/// The cell whose labels equal `cell`'s except `axis`, which is `label`.
fn twin<'r>(results: &'r Results, cell: &Cell, axis: &str, label: &str) -> Option<&'r CellResult> {
    let mut want = keys_of(cell);
    want.insert(axis.to_string(), label.to_string());
    results.cells.iter().find(|c| keys_of(&c.cell) == want)
}

fn fmt(v: f64) -> String {
    crate::format::format_value("pass_ms", Some(v))
}

pub fn check(config: &Config, results: &Results) -> Vec<Finding> {
    let matrix = Matrix::new(config, results.run.quick.then_some(&config.quick));
    let mut out = vec![];
    let mut add = |rule: &str, m: &MetricSpec, c: &CellResult, text: String| {
        out.push(Finding {
            rule: rule.into(),
            metric: m.label.clone(),
            cell: c.cell.index,
            keys: keys_of(&c.cell),
            text,
            explained: None,
        })
    };
    for m in config.metrics.iter().filter(|m| is_timing(&m.kind)) {
        let kind = m.kind.as_str();
        // a: more work, less time.
        if m.not_monotonic.is_none() {
            for axis in config.plausibility.work_grows_with.iter().filter(|a| !m.independent_of.contains(a)) {
                let labels = matrix.keys(config, axis);
                for c in &results.cells {
                    let here = c.cell.key(axis);
                    let Some(i) = labels.iter().position(|l| *l == here) else { continue };
                    let Some(next) = labels.get(i + 1) else { continue };
                    let Some(d) = twin(results, &c.cell, axis, next) else { continue };
                    if let (Some(a), Some(b)) = (spread(c, &m.label), spread(d, &m.label)) {
                        if clearly_faster(kind, a, b) {
                            add(
                                "a",
                                m,
                                d,
                                format!(
                                    "more work, less time: `{}` {axis} {here} → {next}: {} → {}",
                                    m.label,
                                    fmt(a.1),
                                    fmt(b.1)
                                ),
                            );
                        }
                    }
                }
            }
        }
        // b: dynamic beats static.
        for d in results.cells.iter().filter(|c| c.cell.lighting == "dynamic") {
            let Some(s) = twin(results, &d.cell, "lighting", "static") else { continue };
            if let (Some(a), Some(b)) = (spread(s, &m.label), spread(d, &m.label)) {
                if clearly_faster(kind, a, b) {
                    add(
                        "b",
                        m,
                        d,
                        format!("dynamic beats static: `{}` {} static, {} dynamic", m.label, fmt(a.1), fmt(b.1)),
                    );
                }
            }
        }
        // c: faster than the device's memory.
        if let (Some(bpp), Some(gbs)) = (&m.bytes_per_photon, results.run.copy_bandwidth_gbs) {
            for c in &results.cells {
                let (Some(per), Some(ms)) =
                    (bpp.of(&c.cell.technique_label), c.metrics.get(&m.label).and_then(|v| v.value))
                else {
                    continue;
                };
                let bytes = per * (c.cell.photons as f64).powi(2) * c.cell.lights.max(1) as f64;
                if bytes < RULE_C_MIN_BYTES || ms <= 0.0 {
                    continue;
                }
                let rate = bytes / (ms * 1e-3) / 1e9;
                if rate > gbs * (1.0 + RULE_C_MARGIN) {
                    add(
                        "c",
                        m,
                        c,
                        format!(
                            "faster than memory: `{}` moves {:.0} MB in {} ms = {rate:.0} GB/s, above the device's copy \
                             bandwidth ({gbs:.1} GB/s)",
                            m.label,
                            bytes / 1e6,
                            fmt(ms)
                        ),
                    );
                }
            }
        }
        // d: declared independent of an axis, varies by more than 2x along it.
        for axis in &m.independent_of {
            let mut groups: BTreeMap<Vec<(String, String)>, Vec<&CellResult>> = BTreeMap::new();
            for c in &results.cells {
                let mut k = keys_of(&c.cell);
                k.remove(axis);
                groups.entry(k.into_iter().collect()).or_default().push(c);
            }
            for cells in groups.values() {
                let values: Vec<(f64, &CellResult)> = cells
                    .iter()
                    .filter_map(|c| c.metrics.get(&m.label).and_then(|v| v.value).map(|v| (v, *c)))
                    .filter(|(v, _)| *v > 0.0)
                    .collect();
                let Some(min) = values.iter().map(|(v, _)| *v).reduce(f64::min) else { continue };
                for (v, c) in values.iter().filter(|(v, _)| *v > 2.0 * min) {
                    add(
                        "d",
                        m,
                        c,
                        format!(
                            "not independent of {axis}: `{}` {} here, {} at another {axis} ({:.1}x)",
                            m.label,
                            fmt(*v),
                            fmt(min),
                            v / min
                        ),
                    );
                }
            }
        }
    }
    for f in &mut out {
        f.explained = config
            .plausibility
            .explained
            .iter()
            .find(|e| {
                e.rule == f.rule
                    && e.metric == f.metric
                    && e.scene.as_ref().is_none_or(|s| f.keys.get("scene") == Some(s))
                    && e.technique.as_ref().is_none_or(|t| f.keys.get("technique") == Some(t))
                    && e.photons.is_none_or(|p| f.keys.get("photons") == Some(&p.to_string()))
                    && e.lighting.as_ref().is_none_or(|l| f.keys.get("lighting") == Some(l))
                    && e.device.as_ref().is_none_or(|d| results.meta.device.to_lowercase().contains(&d.to_lowercase()))
            })
            .map(|e| e.why.clone());
    }
    out.sort_by(|a, b| (a.cell, &a.metric, &a.rule).cmp(&(b.cell, &b.metric, &b.rule)));
    out.dedup();
    out
}
