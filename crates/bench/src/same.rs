//! `bench same A.json B.json`: two results of one config compared cell by cell in everything
//! but the timings. The check that a sweep split into shards (the GPU suite, a cluster's job
//! array) and merged gives the table one unsharded run gives: the same cells, and in each the
//! same counts, errors and FLIP values. Times (`results::is_timing`) differ from run to run and
//! are not compared.
//!
//! Counts are compared exactly. Errors and ratios (the receiver map against its CPU reference,
//! FLIP, depth complexity) within a relative tolerance: a GPU's additive splats and atomic adds
//! sum in an order that can change between runs, so two runs of one cell agree to float
//! rounding, not bit for bit.

use crate::results::{is_timing, CellResult, Results};
use std::collections::BTreeMap;

/// What `same` compares a value with: exactly, or within `tolerance` of the larger magnitude.
fn exact(kind: &str) -> bool {
    matches!(
        kind,
        "photons_emitted"
            | "splats_drawn"
            | "photons_processed"
            | "valid_photons"
            | "photon_storage"
            | "photon_batches"
    )
}

/// Every difference between `a` and `b` outside the timings, one line each, naming the cell
/// and the metric; empty when they agree. `tolerance` is relative (values agree when
/// |a - b| <= tolerance * max(|a|, |b|)).
pub fn differences(a: &Results, b: &Results, tolerance: f64) -> Vec<String> {
    let mut out = vec![];
    if a.config.hash != b.config.hash {
        out.push(format!("config: hash {} against {} (not the same config file)", a.config.hash, b.config.hash));
        return out;
    }
    if a.run.quick != b.run.quick {
        out.push(format!("run: quick {} against {}", a.run.quick, b.run.quick));
    }
    let by_index =
        |r: &Results| -> BTreeMap<usize, CellResult> { r.cells.iter().map(|c| (c.cell.index, c.clone())).collect() };
    let (ca, cb) = (by_index(a), by_index(b));
    for (i, x) in &ca {
        let Some(y) = cb.get(i) else {
            out.push(format!("{}: only in the first", x.cell.describe()));
            continue;
        };
        cell(x, y, tolerance, &mut out);
    }
    for (i, y) in &cb {
        if !ca.contains_key(i) {
            out.push(format!("{}: only in the second", y.cell.describe()));
        }
    }
    out
}

fn cell(x: &CellResult, y: &CellResult, tolerance: f64, out: &mut Vec<String>) {
    let name = x.cell.describe();
    if x.cell != y.cell {
        out.push(format!("{name}: the cell differs ({} in the second)", y.cell.describe()));
        return;
    }
    if x.triangles != y.triangles {
        out.push(format!("{name}: triangles {} against {}", x.triangles, y.triangles));
    }
    if x.list_sizes != y.list_sizes {
        out.push(format!("{name}: the traversal's list sizes {:?} against {:?}", x.list_sizes, y.list_sizes));
    }
    for (label, vx) in &x.metrics {
        let Some(vy) = y.metrics.get(label) else {
            out.push(format!("{name}: metric `{label}` only in the first"));
            continue;
        };
        if vx.kind != vy.kind {
            out.push(format!("{name}: metric `{label}` is {} against {}", vx.kind, vy.kind));
            continue;
        }
        if is_timing(&vx.kind) {
            continue;
        }
        let agree = match (vx.value, vy.value) {
            (None, None) => true,
            (Some(p), Some(q)) if exact(&vx.kind) => p == q,
            (Some(p), Some(q)) => (p - q).abs() <= tolerance * p.abs().max(q.abs()) || (p.is_nan() && q.is_nan()),
            _ => false,
        };
        if !agree {
            out.push(format!("{name}: `{label}` ({}) {} against {}", vx.kind, show(vx.value), show(vy.value)));
        }
    }
    for label in y.metrics.keys() {
        if !x.metrics.contains_key(label) {
            out.push(format!("{name}: metric `{label}` only in the second"));
        }
    }
}

fn show(v: Option<f64>) -> String {
    v.map_or_else(|| "none".into(), |v| format!("{v}"))
}

#[cfg(test)]
mod tests {
    use super::differences;
    use crate::results::{Results, Value};

    /// A result of two cells, each with a time, a count and an error.
    fn results(time: f64, count: f64, error: f64) -> Results {
        let value = |kind: &str, v: f64| Value {
            kind: kind.into(),
            value: Some(v),
            min: Some(v),
            max: Some(v),
            q1: None,
            q3: None,
            samples: vec![v],
        };
        // A committed table, cut to two cells whose metrics are replaced.
        let mut r: Results = serde_json::from_str(include_str!(
            "../../../results/llvmpipe-llvmpipe-llvm-15-0-6-256-bits-mesa-22-3-6-llvm-15-0-6/wyman_davis2006_fig8.json"
        ))
        .unwrap();
        r.cells.truncate(2);
        for c in &mut r.cells {
            c.metrics.clear();
            c.metrics.insert("Trace".into(), value("pass_host_ms", time));
            c.metrics.insert("photons".into(), value("valid_photons", count));
            c.metrics.insert("rel. RMSE".into(), value("rel_rmse", error));
        }
        r
    }

    #[test]
    fn timings_are_ignored_and_counts_and_errors_are_not() {
        let a = results(10.0, 4096.0, 0.25);
        // Another run: every time differs, the error by float rounding.
        assert!(differences(&a, &results(13.0, 4096.0, 0.25 * (1.0 + 1e-7)), 1e-5).is_empty());
        // A count one off, in both cells.
        let d = differences(&a, &results(10.0, 4095.0, 0.25), 1e-5);
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(d[0].contains("`photons` (valid_photons) 4096 against 4095"), "{d:?}");
        // An error outside the tolerance; and just inside it.
        let d = differences(&a, &results(10.0, 4096.0, 0.25 * (1.0 + 1e-4)), 1e-5);
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(d[0].contains("`rel. RMSE` (rel_rmse)"), "{d:?}");
        assert!(differences(&a, &results(10.0, 4096.0, 0.25 * (1.0 + 0.9e-5)), 1e-5).is_empty());
    }

    #[test]
    fn counts_are_exact_and_unmeasured_and_nan_values_compare_as_such() {
        // A count off by one in ten million, well inside the tolerance: still a difference.
        let a = results(10.0, 1e7, 0.25);
        let d = differences(&a, &results(10.0, 1e7 + 1.0, 0.25), 1e-5);
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(d[0].contains("`photons` (valid_photons) 10000000 against 10000001"), "{d:?}");
        // An entry neither run measured agrees; one measured on one side only does not.
        let none = |r: &Results| {
            let mut r = r.clone();
            for c in &mut r.cells {
                c.metrics.get_mut("rel. RMSE").unwrap().value = None;
            }
            r
        };
        assert!(differences(&none(&a), &none(&a), 1e-5).is_empty());
        let d = differences(&a, &none(&a), 1e-5);
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(d[0].contains("0.25 against none"), "{d:?}");
        // NaN agrees with NaN only.
        let nan = results(10.0, 4096.0, f64::NAN);
        assert!(differences(&nan, &nan.clone(), 1e-5).is_empty());
        assert_eq!(differences(&nan, &results(10.0, 4096.0, 0.25), 1e-5).len(), 2);
        assert_eq!(differences(&results(10.0, 4096.0, 0.25), &nan, 1e-5).len(), 2);
    }

    #[test]
    fn missing_cells_metrics_and_other_configs_are_named() {
        let a = results(10.0, 4096.0, 0.25);
        let mut b = a.clone();
        b.cells.pop();
        let d = differences(&a, &b, 1e-5);
        assert_eq!(d.len(), 1, "{d:?}");
        assert!(d[0].ends_with(": only in the first"), "{d:?}");
        assert!(differences(&b, &a, 1e-5)[0].ends_with(": only in the second"));
        let mut c = a.clone();
        c.cells[0].metrics.remove("rel. RMSE");
        assert!(differences(&a, &c, 1e-5)[0].contains("metric `rel. RMSE` only in the first"));
        let mut e = a.clone();
        e.cells[1].triangles += 1;
        assert!(differences(&a, &e, 1e-5)[0].contains("triangles"));
        let mut f = a.clone();
        f.config.hash = "0".into();
        assert!(differences(&a, &f, 1e-5)[0].starts_with("config: hash"));
    }
}
