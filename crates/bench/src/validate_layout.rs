//! Checks that a config's layout fits its matrix: the axes placed, `compare`, the columns
//! `[[layout.column]]` picks, and the paper's values. Every message names the file and the key.

use crate::config::{LoadedConfig, AXES};
use crate::plan::Matrix;
use anyhow::Result;

pub fn validate_layout(lc: &LoadedConfig, bad: &dyn Fn(&str, String) -> anyhow::Error) -> Result<()> {
    let c = &lc.config;
    let l = &c.layout;
    let m = Matrix::new(c, None);
    let placed: Vec<&String> = l.rows.iter().chain(&l.columns).collect();
    for (i, a) in placed.iter().enumerate() {
        if !AXES.contains(&a.as_str()) {
            return Err(bad("layout", format!("unknown axis `{a}`; axes: {}", AXES.join(", "))));
        }
        if placed[..i].contains(a) {
            return Err(bad("layout", format!("axis `{a}` is placed twice")));
        }
    }
    if l.rows.is_empty() || l.columns.is_empty() {
        return Err(bad("layout", "needs at least one axis in `rows` and one in `columns`".into()));
    }
    let quick = Matrix::new(c, Some(&c.quick));
    for a in AXES {
        for (matrix, which) in [(&m, ""), (&quick, " under --quick")] {
            if matrix.keys(c, a).len() > 1 && !placed.iter().any(|p| p == a) {
                return Err(bad(
                    "layout",
                    format!("axis `{a}` has several values{which} but is in neither `rows` nor `columns`"),
                ));
            }
        }
    }
    if let Some(cmp) = &l.compare {
        if !placed.iter().any(|p| **p == cmp.axis) {
            return Err(bad("layout.compare.axis", format!("`{}` is not in the layout", cmp.axis)));
        }
        if !m.keys(c, &cmp.axis).contains(&cmp.baseline) || !quick.keys(c, &cmp.axis).contains(&cmp.baseline) {
            return Err(bad(
                "layout.compare.baseline",
                format!("`{}` is not a value of axis `{}`", cmp.baseline, cmp.axis),
            ));
        }
    }
    if let Some(cmp) = &l.compare {
        for (i, metric) in cmp.metrics.iter().enumerate() {
            if !c.metrics.iter().any(|m| m.label == *metric) {
                return Err(bad(&format!("layout.compare.metrics[{i}]"), format!("`{metric}` is no metric's label")));
            }
        }
    }
    validate_picks(c, &m, bad)?;
    let inner = l.columns.last().map(String::as_str).unwrap_or("metric");
    let inner_keys = m.keys(c, inner);
    for (i, e) in c.paper.iter().enumerate() {
        let fixed = crate::paper::fixed_axes(e);
        for (axis, value) in &fixed {
            if *axis == inner {
                return Err(bad(
                    &format!("paper[{i}].{axis}"),
                    format!("`{inner}` is the innermost column axis: its values are the keys of `values`"),
                ));
            }
            if !m.keys(c, axis).contains(value) {
                return Err(bad(
                    &format!("paper[{i}].{axis}"),
                    format!("`{value}` is not a value of axis `{axis}` ({})", m.keys(c, axis).join(", ")),
                ));
            }
        }
        for a in AXES.iter().filter(|a| **a != inner) {
            if m.keys(c, a).len() > 1 && !fixed.iter().any(|(x, _)| x == a) {
                return Err(bad(&format!("paper[{i}]"), format!("must name a `{a}` (the axis has several values)")));
            }
        }
        for (key, v) in [("scene_note", &e.scene_note), ("not_comparable", &e.not_comparable)] {
            if v.as_ref().is_some_and(|v| v.trim().is_empty()) {
                return Err(bad(&format!("paper[{i}].{key}"), "must not be empty".into()));
            }
        }
        for (k, v) in &e.values {
            // A published time, rate, count or error: TOML's `nan` and `inf` are numbers to
            // serde, and a negative one is a typo; either would become a ratio beside ours.
            if !(v.is_finite() && *v >= 0.0) {
                return Err(bad(
                    &format!("paper[{i}].values.{k}"),
                    format!("`{v}` is not a value a paper publishes (a finite number, 0 or more)"),
                ));
            }
            if !inner_keys.contains(k) {
                return Err(bad(
                    &format!("paper[{i}].values"),
                    format!("`{k}` is not a value of the innermost column axis `{inner}` ({})", inner_keys.join(", ")),
                ));
            }
        }
        // Where in the paper the values are (the test `paper_sources` reads them there).
        crate::paper::citations(e).map_err(|m| {
            bad(&format!("paper[{i}].source"), format!("{m} (the entry {})", crate::paper::describe(e)))
        })?;
    }
    Ok(())
}

/// `[[layout.column]]`: each names one column of the layout by a label of every column axis
/// that has several values, and no column twice.
fn validate_picks(c: &crate::config::Config, m: &Matrix, bad: &dyn Fn(&str, String) -> anyhow::Error) -> Result<()> {
    let l = &c.layout;
    let mut seen: Vec<Vec<(&'static str, String)>> = vec![];
    for (i, p) in l.pick.iter().enumerate() {
        let key = |k: &str| format!("layout.column[{i}]{k}");
        let axes = crate::paper::column_axes(p);
        for (axis, value) in &axes {
            if !l.columns.iter().any(|a| a == axis) {
                return Err(bad(&key(&format!(".{axis}")), format!("`{axis}` is not a column axis of the layout")));
            }
            if !m.keys(c, axis).contains(value) {
                return Err(bad(
                    &key(&format!(".{axis}")),
                    format!("`{value}` is not a value of axis `{axis}` ({})", m.keys(c, axis).join(", ")),
                ));
            }
        }
        for a in &l.columns {
            if m.keys(c, a).len() > 1 && !axes.iter().any(|(x, _)| x == a) {
                return Err(bad(&key(""), format!("must name a `{a}` (a column axis with several values)")));
            }
        }
        if p.header.as_ref().is_some_and(|h| h.trim().is_empty()) {
            return Err(bad(&key(".header"), "must not be empty".into()));
        }
        let mut sorted = axes.clone();
        sorted.sort();
        if seen.contains(&sorted) {
            return Err(bad(&key(""), "picks a column that an earlier entry picks".into()));
        }
        seen.push(sorted);
    }
    Ok(())
}
