//! `bench same A.json.gz B.json.gz`: two results of one config compared cell by cell in everything
//! but the timings. The check that a sweep split into shards (the GPU suite, a cluster's job
//! array) and merged gives the table one unsharded run gives: the same cells, and in each the
//! same counts, errors and FLIP values. Times (`results::is_timing`) differ from run to run and
//! are not compared, nor what each frame asked of the driver (`frame_counters`: submits,
//! barriers and objects made, which depend on the frame mode's bookkeeping, not on the cell's
//! answer). The cell itself, the caustic settings in effect, the photon copy, the triangles, the
//! models (by checksum) and the traversal's list sizes must be equal.
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
    // A cell index twice in one result (a merge gone wrong) would hide one of the two.
    for (r, which) in [(a, "first"), (b, "second")] {
        let mut seen = std::collections::BTreeSet::new();
        for c in &r.cells {
            if !seen.insert(c.cell.index) {
                out.push(format!("{}: cell index {} twice in the {which}", c.cell.describe(), c.cell.index));
            }
        }
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

/// The caustic settings two cells ran with, key by key (`key: a against b`). A key only one
/// side has (a result written before the setting existed) is not compared: what the older
/// run did is not always the setting's default today (before `moving_objects`, ray queries
/// rebuilt every structure on each pose, which is `rebuild`, not the default `transform`);
/// [`absent_settings`] names such keys.
fn settings_differences(x: &serde_json::Value, y: &serde_json::Value) -> Vec<String> {
    let (Some(a), Some(b)) = (x.as_object(), y.as_object()) else {
        return if x == y { vec![] } else { vec![format!("{x} against {y}")] };
    };
    a.iter()
        .filter_map(|(k, u)| {
            let v = b.get(k)?;
            (u != v).then(|| format!("`{k}` {u} against {v}"))
        })
        .collect()
}

/// The caustic settings some cell of one result has and the same cell of the other lacks:
/// `same` does not compare them (see [`settings_differences`]), and says so.
pub fn absent_settings(a: &Results, b: &Results) -> std::collections::BTreeSet<String> {
    let by_index = |r: &Results| -> BTreeMap<usize, serde_json::Value> {
        r.cells.iter().map(|c| (c.cell.index, c.caustics.clone())).collect()
    };
    let (ca, cb) = (by_index(a), by_index(b));
    let mut out = std::collections::BTreeSet::new();
    for (i, x) in &ca {
        let (Some(x), Some(y)) = (x.as_object(), cb.get(i).and_then(|y| y.as_object())) else { continue };
        out.extend(x.keys().filter(|k| !y.contains_key(*k)).cloned());
        out.extend(y.keys().filter(|k| !x.contains_key(*k)).cloned());
    }
    out
}

fn cell(x: &CellResult, y: &CellResult, tolerance: f64, out: &mut Vec<String>) {
    let name = x.cell.describe();
    if x.cell != y.cell {
        out.push(format!("{name}: the cell differs ({} in the second)", y.cell.describe()));
        return;
    }
    for d in settings_differences(&x.caustics, &y.caustics) {
        out.push(format!("{name}: the caustic settings in effect differ: {d}"));
    }
    if x.photon_copy != y.photon_copy {
        out.push(format!("{name}: photon copy `{}` against `{}`", x.photon_copy, y.photon_copy));
    }
    if x.triangles != y.triangles {
        out.push(format!("{name}: triangles {} against {}", x.triangles, y.triangles));
    }
    if x.models != y.models {
        let files = |m: &[caustics::scene::models::ModelFile]| -> Vec<String> {
            m.iter().map(|f| format!("{} {}", f.file, &f.sha256[..f.sha256.len().min(12)])).collect()
        };
        out.push(format!("{name}: models {:?} against {:?}", files(&x.models), files(&y.models)));
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
    use super::{absent_settings, differences};
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
        let mut r = crate::results::read(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../results/llvmpipe-llvmpipe-llvm-15-0-6-256-bits-mesa-22-3-6-llvm-15-0-6/wyman_davis2006_fig8.json.gz"),
            "table",
        )
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

    #[test]
    fn a_setting_one_result_lacks_is_not_compared_and_is_named() {
        let mut a = results(10.0, 4096.0, 0.25);
        a.cells[0].caustics = serde_json::json!({"photons": 4096, "trace": "ray-query", "moving_objects": "transform"});
        let mut b = a.clone();
        b.cells[0].caustics.as_object_mut().expect("an object").remove("moving_objects");
        assert!(differences(&a, &b, 1e-5).is_empty(), "a key one side lacks is not compared");
        assert_eq!(absent_settings(&a, &b).into_iter().collect::<Vec<_>>(), ["moving_objects"]);
        assert_eq!(absent_settings(&b, &a).into_iter().collect::<Vec<_>>(), ["moving_objects"]);
        assert!(absent_settings(&a, &a).is_empty());
        b.cells[0].caustics["moving_objects"] = serde_json::json!("rebuild");
        let d = differences(&a, &b, 1e-5);
        assert!(d.len() == 1 && d[0].contains("`moving_objects` \"transform\" against \"rebuild\""), "{d:?}");
    }

    #[test]
    fn settings_models_photon_copy_and_a_duplicated_cell_are_named() {
        let a = results(10.0, 4096.0, 0.25);
        let mut b = a.clone();
        b.cells[0].caustics["photons"] = serde_json::json!(12345);
        let d = differences(&a, &b, 1e-5);
        assert!(d.len() == 1 && d[0].contains("caustic settings in effect differ"), "{d:?}");
        let mut c = a.clone();
        c.cells[1].photon_copy += "-other";
        let d = differences(&a, &c, 1e-5);
        assert!(d.len() == 1 && d[0].contains("photon copy"), "{d:?}");
        let mut m = a.clone();
        m.cells[0].models =
            vec![caustics::scene::models::ModelFile { file: "x.obj".into(), sha256: "ab".repeat(32), expected: None }];
        let d = differences(&a, &m, 1e-5);
        assert!(d.len() == 1 && d[0].contains("models [] against [\"x.obj abababababab\"]"), "{d:?}");
        // The second cell given the first's index: named, though the map by index keeps one.
        let mut t = a.clone();
        t.cells[1] = t.cells[0].clone();
        let d = differences(&a, &t, 1e-5);
        assert!(d.iter().any(|l| l.contains("twice in the second")), "{d:?}");
    }
}
