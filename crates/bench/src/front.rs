//! The error-against-time front of a config with `[front]`: per scene, every cell is a point (x
//! a time metric, y an error metric, both lower is better), the Pareto front joins the points no
//! other point beats on both, and for each error level the table names the cheapest cell that
//! reaches it. Drawn by `crate::front_plot`; written into the table by [`markdown`].

use crate::config::{Config, FrontLevels, FrontSpec};
use crate::format::significant;
use crate::plan::scene_label;
use crate::results::Results;
use std::fmt::Write as _;

/// Checks `[front]`: every x and y a metric's label, and error levels above 0 for each y (a
/// list for one y, a table keyed by the y labels for several).
pub(crate) fn validate(c: &Config, f: &FrontSpec, bad: &dyn Fn(&str, String) -> anyhow::Error) -> anyhow::Result<()> {
    if f.x.is_empty() {
        return Err(bad("front.x", "needs the label of at least one time metric".into()));
    }
    if f.y.is_empty() {
        return Err(bad("front.y", "needs the label of at least one error metric".into()));
    }
    for (key, label) in f.x.iter().map(|x| ("front.x", x)).chain(f.y.iter().map(|y| ("front.y", y))) {
        if !c.metrics.iter().any(|m| &m.label == label) {
            return Err(bad(key, format!("`{label}` is the label of no [[metric]]")));
        }
    }
    match &f.levels {
        FrontLevels::All(_) if f.y.len() > 1 => {
            return Err(bad(
                "front.levels",
                format!("{} y metrics: give their levels as a table, e.g. {{ \"{}\" = [0.1] }}", f.y.len(), f.y[0]),
            ))
        }
        FrontLevels::ByMetric(m) => {
            if let Some(k) = m.keys().find(|k| !f.y.contains(k)) {
                return Err(bad("front.levels", format!("`{k}` is not one of front.y")));
            }
        }
        FrontLevels::All(_) => {}
    }
    if let Some(curves) = &f.curves {
        crate::front_curves::validate(c, curves, bad)?;
    }
    for y in &f.y {
        let levels = f.levels_of(y);
        if levels.is_empty() || levels.iter().any(|l| !(l.is_finite() && *l > 0.0)) {
            return Err(bad("front.levels", format!("needs error levels above 0 for `{y}`, got {levels:?}")));
        }
    }
    Ok(())
}

/// One cell as a point of the front.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    pub technique: String,
    /// The paper its technique reproduces (`Technique::paper`): its marker.
    pub paper: String,
    pub photons: u32,
    pub x: f64,
    pub y: f64,
}

/// A scene's points and its Pareto front, along one of the x metrics.
#[derive(Debug, Clone)]
pub struct SceneFront {
    pub scene: String,
    /// The x metric's label.
    pub x: String,
    /// The y metric's label.
    pub y: String,
    pub points: Vec<Point>,
    /// Indices into `points` of the front, by increasing x (and decreasing y).
    pub front: Vec<usize>,
}

/// The points of `(x, y)` that no other point beats on both (lower x and lower y; a tie on x
/// keeps the lower y), by increasing x.
pub fn pareto(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0).then(points[a].1.total_cmp(&points[b].1)));
    let mut best = f64::INFINITY;
    let mut front = vec![];
    for i in order {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

/// Of `points`, the one with the least x among those with y at most `level`.
pub fn cheapest(points: &[Point], level: f64) -> Option<usize> {
    (0..points.len()).filter(|&i| points[i].y <= level).min_by(|&a, &b| points[a].x.total_cmp(&points[b].x))
}

/// Every scene's points (cells with both metrics, finite and positive) of y metric `y_label`
/// along x metric `x_label`, in the matrix's order.
pub fn fronts(config: &Config, results: &Results, x_label: &str, y_label: &str) -> Vec<SceneFront> {
    let mut out: Vec<SceneFront> = vec![];
    for c in &results.cells {
        let get = |label: &str| c.metrics.get(label).and_then(|v| v.value).filter(|v| v.is_finite() && *v > 0.0);
        let (Some(x), Some(y)) = (get(x_label), get(y_label)) else { continue };
        let paper = config
            .techniques
            .get(c.cell.technique)
            .and_then(|t| t.settings.technique)
            .map_or_else(|| "(no technique)".to_string(), |t| t.paper().to_string());
        let point = Point { technique: c.cell.technique_label.clone(), paper, photons: c.cell.photons, x, y };
        let scene = scene_label(&c.cell.scene);
        match out.iter_mut().find(|f| f.scene == scene) {
            Some(f) => f.points.push(point),
            None => out.push(SceneFront {
                scene,
                x: x_label.to_string(),
                y: y_label.to_string(),
                points: vec![point],
                front: vec![],
            }),
        }
    }
    for f in &mut out {
        f.front = pareto(&f.points.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>());
    }
    out
}

/// The fronts as the table's sections, one per y and x metric (the y metrics outermost): per
/// scene the cheapest cell at each error level, and the front itself.
pub fn markdown(config: &Config, results: &Results) -> String {
    let Some(spec) = &config.front else { return String::new() };
    spec.y.iter().flat_map(|y| spec.x.iter().map(move |x| section(config, results, spec, x, y))).collect()
}

fn section(config: &Config, results: &Results, spec: &FrontSpec, x: &str, y: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## {y} against {x}\n");
    let _ = writeln!(
        s,
        "Per scene, the cheapest cell (least `{x}`) whose `{y}` is at most each level; then the Pareto front, \
         the cells no other cell beats on both.\n"
    );
    // The error as the table prints its metric.
    let kind = config.metric_kind(y).unwrap_or("rel_rmse");
    let err = |v: f64| crate::format::format_value(kind, Some(v));
    // Progressive accumulation's curves, where they are drawn against this x and y.
    let curves = results.front_curves.as_ref().filter(|_| spec.curves.as_ref().is_some_and(|c| c.drawn_on(x, y)));
    if let Some(why) = curves.and_then(|c| c.missing.as_ref()) {
        let _ = writeln!(s, "No progressive curves drawn: {}.\n", why.trim_end_matches('.'));
    }
    for f in fronts(config, results, x, y) {
        let _ = writeln!(s, "**{}**\n", f.scene);
        let _ = writeln!(s, "| {y} at most | cheapest | photons | {x} | {y} |");
        let _ = writeln!(s, "|---|---|---|---|---|");
        for &level in spec.levels_of(y) {
            match cheapest(&f.points, level) {
                Some(i) => {
                    let p = &f.points[i];
                    let _ = writeln!(
                        s,
                        "| {level} | {} | {}² | {} | {} |",
                        p.technique,
                        p.photons,
                        significant(p.x),
                        err(p.y)
                    );
                }
                None => {
                    let _ = writeln!(s, "| {level} | (none reaches it) | | | |");
                }
            }
        }
        let front: Vec<String> = f
            .front
            .iter()
            .map(|&i| {
                let p = &f.points[i];
                format!("{} {}² ({}, {})", p.technique, p.photons, significant(p.x), err(p.y))
            })
            .collect();
        let _ = writeln!(s, "\nFront: {}.\n", front.join(" → "));
        if let Some(c) = curves {
            s.push_str(&crate::front_curves::markdown(c, &f.scene, spec.levels_of(y), x, y, &err));
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_front_keeps_the_points_nothing_beats_on_both() {
        // (time, error): b is beaten by a on both; c is slower than a but more accurate; d ties
        // a's time with a lower error; e is the fastest.
        let pts = [(2.0, 0.5), (3.0, 0.6), (5.0, 0.1), (2.0, 0.4), (1.0, 0.9)];
        assert_eq!(pareto(&pts), vec![4, 3, 2]);
        let points: Vec<Point> =
            pts.iter().map(|&(x, y)| Point { technique: "t".into(), paper: "p".into(), photons: 256, x, y }).collect();
        assert_eq!(cheapest(&points, 0.45), Some(3));
        assert_eq!(cheapest(&points, 0.2), Some(2));
        assert_eq!(cheapest(&points, 0.05), None);
    }
}
