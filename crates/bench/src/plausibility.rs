//! Rules that catch timings that cannot be right, applied to every table. A finding marks its
//! entry `?`, is listed under the table and is kept in the JSON; it goes away only by a fix, or
//! by an explanation in the config (`[[plausibility.explained]]`) that cites a measurement.
//!
//! - **a** More work, less time: a cell faster than its neighbour with less work along an axis
//!   the config says grows the work (`work_grows_with`: photons and resolution by default; the
//!   technique axis, in the config's order, where its entries add work, e.g. more batches),
//!   beyond both cells' interquartile ranges (and 1%).
//! - **b** Dynamic beats static: a `dynamic` cell faster than its `static` twin, likewise.
//!
//!   Rules a and b compare times the device took: an entry that rule c, e or f finds (it reads
//!   `not measured`: the device's clock missed the work) is in no pair of theirs.
//! - **c** Faster than memory: a copy whose bytes (`bytes_per_photon`) over its time exceed what
//!   the device can copy: its copy bandwidth, measured at the start of the run, plus 10% (the
//!   two are measured apart) for copies of at least 64 MiB; ten times that below 64 MiB, where
//!   a copy may run from caches (the L2 and last-level caches of current CPUs and GPUs stream
//!   3-8 times faster than their memory, none ten times).
//! - **d** Not independent: a metric declared independent of an axis (`independent_of`) that
//!   varies by more than 2x along it; the cells above twice the smallest are marked.
//! - **e** Timestamps missed the work: a `pass_ms` cell under a tenth of the same passes'
//!   `pass_host_ms` (each pass submitted alone and waited for), and more than 1 ms below it
//!   (submitting and waiting cost the host a little): a pass cannot finish on the host before
//!   the device ran it, so the device's timestamps did not bracket its work. A `pass_mphotons`
//!   rate of the same passes comes from the same timestamps and is marked with it.
//! - **f** Faster than the device can write: a photon rate (`pass_mphotons`, `frame_mphotons`,
//!   `pass_host_mphotons`) whose photons, each writing at least `bytes_per_photon`, would need
//!   more than the bound of rule c for the bytes they write.
//! - **g** Fewer with more work: a count (photons emitted, valid, processed, splats, batches;
//!   not the storage, which a memory limit caps and batching shrinks) lower at a cell with more
//!   work along a `work_grows_with` axis than at its neighbour with less; counts are exact, so
//!   any drop is a finding unless the metric says why its count need not grow (`not_monotonic`).

use crate::config::{Config, MetricSpec};
use crate::plan::{Cell, Matrix};
use crate::results::{is_timing, CellResult, Results};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One implausible entry.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Finding {
    /// `a` to `g` (see the module).
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
/// How much faster than the measured copy bandwidth a copy under [`RULE_C_MIN_BYTES`] may run
/// (from caches) before rule c speaks.
pub const RULE_C_CACHE_FACTOR: f64 = 10.0;
/// Rule e: a GPU time under this share of the host time of the same passes...
pub const RULE_E_SHARE: f64 = 0.1;
/// ...and this many ms below it.
pub const RULE_E_MIN_GAP_MS: f64 = 1.0;
/// Margin beyond the interquartile ranges before rules a and b speak.
const MARGIN: f64 = 0.01;

/// The most GB/s a copy of `bytes` may move on a device that copies `gbs` (rule c, f).
pub fn copy_bound_gbs(bytes: f64, gbs: f64) -> f64 {
    let cached = if bytes < RULE_C_MIN_BYTES { RULE_C_CACHE_FACTOR } else { 1.0 };
    gbs * cached * (1.0 + RULE_C_MARGIN)
}

/// Rules whose finding means the device cannot have done what the entry says: its timestamps
/// missed the work. Such entries are not printed as numbers, explained or not (`crate::table`).
pub const UNMEASURED_RULES: [&str; 3] = ["c", "e", "f"];

/// Counts that grow with the work (rule g). Not the photon storage: a memory limit caps it, and
/// batching (which more photons start) makes it smaller by design.
fn is_growing_count(kind: &str) -> bool {
    matches!(kind, "photons_emitted" | "splats_drawn" | "photons_processed" | "valid_photons" | "photon_batches")
}

/// Photon rates (rule f).
pub fn is_rate(kind: &str) -> bool {
    matches!(kind, "pass_mphotons" | "frame_mphotons" | "pass_host_mphotons")
}

/// Frame rates: timings where higher is faster, like the photon rates.
fn is_frame_rate(kind: &str) -> bool {
    matches!(kind, "fps" | "pass_fps")
}

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
    !is_frame_rate(kind) && !is_rate(kind)
}

/// Kinds that rules c and f can read with `bytes_per_photon`: a time in ms or a photon rate.
pub fn takes_bytes_per_photon(kind: &str) -> bool {
    crate::results::is_timing(kind) && !is_frame_rate(kind)
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

/// Each cell with its neighbour one step up `axis` (more work), for every axis in
/// `work_grows_with` that `m` is not independent of.
fn more_work_pairs<'r>(
    config: &Config,
    matrix: &Matrix,
    results: &'r Results,
    m: &MetricSpec,
) -> Vec<(&'r CellResult, &'r CellResult, String, String, String)> {
    let mut out = vec![];
    for axis in config.plausibility.work_grows_with.iter().filter(|a| !m.independent_of.contains(a)) {
        let labels = matrix.keys(config, axis);
        for c in &results.cells {
            let here = c.cell.key(axis);
            let Some(i) = labels.iter().position(|l| *l == here) else { continue };
            let Some(next) = labels.get(i + 1) else { continue };
            if let Some(d) = twin(results, &c.cell, axis, next) {
                out.push((c, d, axis.clone(), here, next.clone()));
            }
        }
    }
    out
}

/// The value of metric `label` in cell `c`.
fn value_of(c: &CellResult, label: &str) -> Option<f64> {
    c.metrics.get(label).and_then(|v| v.value)
}

fn same_passes(a: &[String], b: &[String]) -> bool {
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    a.sort();
    b.sort();
    a == b
}

pub fn check(config: &Config, results: &Results) -> Vec<Finding> {
    let matrix = Matrix::new(config, results.run.quick.then_some(&config.quick));
    let mut out = vec![];
    let add = |out: &mut Vec<Finding>, rule: &str, m: &MetricSpec, c: &CellResult, text: String| {
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
        // c: faster than the device's memory; f: photons faster than the device can write them.
        if let (Some(bpp), Some(gbs)) = (&m.bytes_per_photon, results.run.copy_bandwidth_gbs) {
            for c in &results.cells {
                let (Some(per), Some(v)) = (bpp.of(&c.cell.technique_label), value_of(c, &m.label)) else {
                    continue;
                };
                let bytes = per * (c.cell.photons as f64).powi(2) * c.cell.lights.max(1) as f64;
                if v <= 0.0 || !v.is_finite() {
                    continue;
                }
                let bound = copy_bound_gbs(bytes, gbs);
                let cached = if bytes < RULE_C_MIN_BYTES { " (ten times it: under 64 MiB, from caches)" } else { "" };
                if is_rate(kind) {
                    // v M photons/s, each writing `per` bytes.
                    let rate = v * 1e6 * per / 1e9;
                    if rate > bound {
                        add(
                            &mut out,
                            "f",
                            m,
                            c,
                            format!(
                                "faster than the device can write: `{}` {v:.0} M photons/s × {per:.0} B = {rate:.0} GB/s, \
                                 above the device's copy bandwidth ({gbs:.1} GB/s){cached}",
                                m.label
                            ),
                        );
                    }
                } else {
                    let rate = bytes / (v * 1e-3) / 1e9;
                    if rate > bound {
                        add(
                            &mut out,
                            "c",
                            m,
                            c,
                            format!(
                                "faster than memory: `{}` moves {:.1} MB in {} ms = {rate:.0} GB/s, above the device's \
                                 copy bandwidth ({gbs:.1} GB/s){cached}",
                                m.label,
                                bytes / 1e6,
                                fmt(v)
                            ),
                        );
                    }
                }
            }
        }
        // e: the device's timestamps missed the work its host time shows; a rate of the same
        // passes from the same timestamps (pass_mphotons, pass_fps) with them.
        if matches!(kind, "pass_ms" | "pass_mphotons" | "pass_fps") {
            let same = |k: &str| config.metrics.iter().find(|h| h.kind == k && same_passes(&h.passes, &m.passes));
            if let (Some(gpu_metric), Some(h)) = (same("pass_ms"), same("pass_host_ms")) {
                for c in &results.cells {
                    let (Some(_), Some(gpu), Some(host_ms)) =
                        (value_of(c, &m.label), value_of(c, &gpu_metric.label), value_of(c, &h.label))
                    else {
                        continue;
                    };
                    if gpu < RULE_E_SHARE * host_ms && host_ms - gpu > RULE_E_MIN_GAP_MS {
                        let from = if gpu_metric.label == m.label {
                            String::new()
                        } else {
                            format!("`{}` is a rate of `{}`: ", m.label, gpu_metric.label)
                        };
                        add(
                            &mut out,
                            "e",
                            m,
                            c,
                            format!(
                                "the timestamps missed the work: {from}`{}` {} ms on the device's clock, `{}` {} ms \
                                 on the host for the same passes submitted alone",
                                gpu_metric.label,
                                fmt(gpu),
                                h.label,
                                fmt(host_ms)
                            ),
                        );
                    }
                }
            }
        }
        // a and b compare what the device timed: not an entry c, e or f found (`not measured`).
        let unmeasured: std::collections::BTreeSet<usize> = out
            .iter()
            .filter(|f| f.metric == m.label && UNMEASURED_RULES.contains(&f.rule.as_str()))
            .map(|f| f.cell)
            .collect();
        let measured = |c: &CellResult| !unmeasured.contains(&c.cell.index);
        // a: more work, less time.
        if m.not_monotonic.is_none() {
            for (c, d, axis, here, next) in more_work_pairs(config, &matrix, results, m) {
                if !measured(c) || !measured(d) {
                    continue;
                }
                if let (Some(a), Some(b)) = (spread(c, &m.label), spread(d, &m.label)) {
                    if clearly_faster(kind, a, b) {
                        add(
                            &mut out,
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
        // b: dynamic beats static.
        for d in results.cells.iter().filter(|c| c.cell.lighting == "dynamic") {
            let Some(s) = twin(results, &d.cell, "lighting", "static") else { continue };
            if !measured(s) || !measured(d) {
                continue;
            }
            if let (Some(a), Some(b)) = (spread(s, &m.label), spread(d, &m.label)) {
                if clearly_faster(kind, a, b) {
                    add(
                        &mut out,
                        "b",
                        m,
                        d,
                        format!("dynamic beats static: `{}` {} static, {} dynamic", m.label, fmt(a.1), fmt(b.1)),
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
                        &mut out,
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
    // g: a count that falls as the work grows.
    for m in config.metrics.iter().filter(|m| is_growing_count(&m.kind) && m.not_monotonic.is_none()) {
        for (c, d, axis, here, next) in more_work_pairs(config, &matrix, results, m) {
            if let (Some(a), Some(b)) = (value_of(c, &m.label), value_of(d, &m.label)) {
                if b < a {
                    add(
                        &mut out,
                        "g",
                        m,
                        d,
                        format!("fewer with more work: `{}` {axis} {here} → {next}: {a} → {b}", m.label),
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

#[cfg(test)]
mod tests;
