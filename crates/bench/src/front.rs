//! The error-against-time front of a config with `[front]`: per scene, every cell is a point (x
//! a time metric, y an error metric, both lower is better), the Pareto front joins the points no
//! other point beats on both, and for each error level the table names the cheapest cell that
//! reaches it. Drawn by `crate::front_plot`; written into the table by [`markdown`].

use crate::config::{Config, FrontSpec};
use crate::format::significant;
use crate::plan::scene_label;
use crate::results::Results;
use std::fmt::Write as _;

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

/// Every scene's points (cells with both metrics, finite and positive) along x metric `x`, in
/// the matrix's order.
pub fn fronts(config: &Config, results: &Results, spec: &FrontSpec, x_label: &str) -> Vec<SceneFront> {
    let mut out: Vec<SceneFront> = vec![];
    for c in &results.cells {
        let get = |label: &str| c.metrics.get(label).and_then(|v| v.value).filter(|v| v.is_finite() && *v > 0.0);
        let (Some(x), Some(y)) = (get(x_label), get(&spec.y)) else { continue };
        let paper = config
            .techniques
            .get(c.cell.technique)
            .and_then(|t| t.settings.technique)
            .map_or_else(|| "(no technique)".to_string(), |t| t.paper().to_string());
        let point = Point { technique: c.cell.technique_label.clone(), paper, photons: c.cell.photons, x, y };
        let scene = scene_label(&c.cell.scene);
        match out.iter_mut().find(|f| f.scene == scene) {
            Some(f) => f.points.push(point),
            None => out.push(SceneFront { scene, x: x_label.to_string(), points: vec![point], front: vec![] }),
        }
    }
    for f in &mut out {
        f.front = pareto(&f.points.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>());
    }
    out
}

/// The fronts as the table's sections, one per x metric: per scene the cheapest cell at each
/// error level, and the front itself.
pub fn markdown(config: &Config, results: &Results) -> String {
    let Some(spec) = &config.front else { return String::new() };
    spec.x.iter().map(|x| section(config, results, spec, x)).collect()
}

fn section(config: &Config, results: &Results, spec: &FrontSpec, x: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## {} against {}\n", spec.y, x);
    let _ = writeln!(
        s,
        "Per scene, the cheapest cell (least `{}`) whose `{}` is at most each level; then the Pareto front, \
         the cells no other cell beats on both.\n",
        x, spec.y
    );
    for f in fronts(config, results, spec, x) {
        let _ = writeln!(s, "**{}**\n", f.scene);
        let _ = writeln!(s, "| {} at most | cheapest | photons | {} | {} |", spec.y, x, spec.y);
        let _ = writeln!(s, "|---|---|---|---|---|");
        for &level in &spec.levels {
            match cheapest(&f.points, level) {
                Some(i) => {
                    let p = &f.points[i];
                    let _ = writeln!(
                        s,
                        "| {level} | {} | {}² | {} | {:.4} |",
                        p.technique,
                        p.photons,
                        significant(p.x),
                        p.y
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
                format!("{} {}² ({}, {:.4})", p.technique, p.photons, significant(p.x), p.y)
            })
            .collect();
        let _ = writeln!(s, "\nFront: {}.\n", front.join(" → "));
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
