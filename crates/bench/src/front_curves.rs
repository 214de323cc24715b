//! Curves on a front (`[front.curves]`): progressive accumulation's error after each frame
//! against the time its frames took together (`crate::progressive`, Table T4), drawn on the
//! panels of single frames' error against their time (`crate::front`, Table F1). A cell of the
//! front is what one frame gives; a curve is what the same photons give when a static scene
//! lets frames add up. The curves come from another table of the same results folder, copied
//! into the front's JSON when its table is written (with that table's commit), so that the
//! front's Markdown and plot are their own; `bench explain` draws them again from a newer run.
//!
//! A curve is drawn only where it measures what the front's cells measure: the same device,
//! `--quick` and validation, the same paths of light, camera and objects, the same CPU reference
//! (photons and seed), and per scene the same scene file (and models), output size, lights,
//! lighting and Fresnel setting as every cell of the front, from a cell that was not busy; its
//! frames time passes the front's x metric times (each of its patterns one of the x metric's).
//! Otherwise the front's table says why no curve is drawn, and the plot has none.

use crate::config::Config;
use crate::format::significant;
use crate::plan::scene_label;
use crate::progressive::Point;
use crate::results::Results;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::Path;

/// `[front.curves]`: which table's progressive curves to draw, on which panels.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CurvesSpec {
    /// The name of the config whose table has the curves (`photon_trace_progressive`): its
    /// `<name>.json.gz` in the front's results folder.
    pub table: String,
    /// The front's time metric they are drawn against (a `pass_host_ms` metric: a curve's
    /// time is its frames' pass host times added up).
    pub x: String,
    /// The front's error metric (a `rel_rmse` metric: a curve's error is the receiver map's).
    pub y: String,
    /// The labels of the techniques of that table whose curves are drawn; all by default.
    #[serde(default)]
    pub techniques: Vec<String>,
}

impl CurvesSpec {
    /// Whether the curves are drawn on the panels (and sections) of x metric `x` and y metric `y`.
    pub fn drawn_on(&self, x: &str, y: &str) -> bool {
        self.x == x && self.y == y
    }

    /// Whether the curve of the technique labelled `label` is drawn.
    pub fn draws(&self, label: &str) -> bool {
        self.techniques.is_empty() || self.techniques.iter().any(|t| t == label)
    }
}

/// What a front drew from `[front.curves]`, kept in its JSON.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct FrontCurves {
    /// The config name of the table the curves come from.
    pub table: String,
    /// That table's commit and date (its `meta`), empty where it was not read.
    pub commit: String,
    pub date: String,
    pub curves: Vec<Curve>,
    /// Why no curve is drawn (the table is missing, or measures something else); None when
    /// they are.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub missing: Option<String>,
}

/// One technique's curve on one scene.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Curve {
    /// The scene's label (`crate::plan::scene_label`), as the front's panels name it.
    pub scene: String,
    pub technique: String,
    pub points: Vec<Point>,
}

/// Checks `[front.curves]` against the config: its x one of the front's x and a
/// `pass_host_ms` metric, its y one of the front's y and a `rel_rmse` metric.
pub(crate) fn validate(c: &Config, s: &CurvesSpec, bad: &dyn Fn(&str, String) -> anyhow::Error) -> anyhow::Result<()> {
    let (xs, ys) = c.front.as_ref().map_or((&[][..], &[][..]), |f| (f.x.as_slice(), f.y.as_slice()));
    let axes = [
        ("front.curves.x", &s.x, xs, "front.x", "pass_host_ms", "time is its frames' pass host times added up"),
        ("front.curves.y", &s.y, ys, "front.y", "rel_rmse", "error is the receiver map's relative RMSE"),
    ];
    for (key, label, axis, axis_key, kind, why) in axes {
        if !axis.contains(label) {
            return Err(bad(key, format!("`{label}` is not one of {axis_key}")));
        }
        if c.metric_kind(label) != Some(kind) {
            return Err(bad(key, format!("`{label}` is not a `{kind}` metric, as a curve's {why}")));
        }
    }
    if s.table.is_empty() || s.table.contains(['/', '\\', '.']) {
        return Err(bad(
            "front.curves.table",
            format!("`{}` is not a config's name (its file stem, e.g. `photon_trace_progressive`)", s.table),
        ));
    }
    Ok(())
}

/// The CPU reference a table's errors are taken against: (photons, seed).
fn reference(c: &Config, quick: bool) -> (u64, u64) {
    let photons = if quick { c.quick.reference_photons } else { c.quality.reference_photons };
    (photons, c.quality.seed)
}

/// The curves `[front.curves]` names, read from `dir` (the folder `front` is written to) and
/// checked against it; None where the config has no `[front.curves]`.
pub fn load(c: &Config, front: &Results, dir: &Path) -> Option<FrontCurves> {
    let spec = c.front.as_ref()?.curves.as_ref()?;
    let outcome = |commit: &str, date: &str, drawn: Result<Vec<Curve>, String>| {
        let (curves, missing) = match drawn {
            Ok(curves) => (curves, None),
            Err(why) => (vec![], Some(why)),
        };
        Some(FrontCurves { table: spec.table.clone(), commit: commit.into(), date: date.into(), curves, missing })
    };
    let path = match crate::results::table_file(dir, &spec.table) {
        Ok(path) => path,
        Err(e) => return outcome("", "", Err(format!("{e:#}"))),
    };
    if !path.exists() {
        return outcome("", "", Err(format!("no table `{}` in this results folder", spec.table)));
    }
    let other = match crate::results::read(&path, "table") {
        Ok(r) => r,
        Err(e) => return outcome("", "", Err(format!("{e:#}"))),
    };
    let (commit, date) = (&other.meta.commit, &other.meta.date);
    let drawn = curves(c, front, spec, &other).map_err(|why| format!("`{}` (commit {commit}): {why}", spec.table));
    outcome(commit, date, drawn)
}

/// Whether the config of the curves' table (`other`) measures what the front's (`c`) does,
/// as far as the configs say (`--quick` or not): the same reference and output sizes, a scene
/// in common, the Fresnel setting of each drawn technique that of every front technique, and
/// timed passes the x metric names; `Err` says what differs. [`curves`] checks it, then each
/// cell as run.
pub fn agree(c: &Config, spec: &CurvesSpec, other: &Config, quick: bool) -> Result<(), String> {
    let (mine, theirs) = (reference(c, quick), reference(other, quick));
    if mine != theirs {
        return Err(format!(
            "its errors are against a reference of {} photons (seed {}), the front's against {} (seed {})",
            theirs.0, theirs.1, mine.0, mine.1
        ));
    }
    let resolutions = |c: &Config| if quick { c.quick.resolution.clone() } else { c.matrix.resolution.clone() };
    if resolutions(c) != resolutions(other) {
        return Err(format!("its output sizes are {:?}, the front's {:?}", resolutions(other), resolutions(c)));
    }
    let scenes = |c: &Config| c.matrix.scenes.iter().map(|s| scene_label(s)).collect::<Vec<_>>();
    if !scenes(other).iter().any(|s| scenes(c).contains(s)) {
        return Err("no curve of a scene the front has".into());
    }
    let timed = crate::progressive::timed_passes(&other.metrics);
    let x_passes = c.metrics.iter().find(|m| m.label == spec.x).map_or(&[][..], |m| m.passes.as_slice());
    if timed.is_empty() {
        return Err("its curves time whole frames, not passes".into());
    }
    if let Some(p) = timed.iter().find(|p| !x_passes.contains(p)) {
        return Err(format!("its frames time passes `{p}`, which `{}` does not name", spec.x));
    }
    let labels: Vec<&str> = other.techniques.iter().map(|t| t.label.as_str()).collect();
    if let Some(t) = spec.techniques.iter().find(|t| !labels.contains(&t.as_str())) {
        return Err(format!("it has no technique `{t}` (front.curves.techniques)"));
    }
    for t in (0..other.techniques.len()).filter(|&t| spec.draws(&other.techniques[t].label)) {
        let fresnel = other.technique_settings(t).fresnel;
        if let Some(f) = (0..c.techniques.len()).find(|&f| c.technique_settings(f).fresnel != fresnel) {
            return Err(format!(
                "`{}` has fresnel = {fresnel}, the front's `{}` fresnel = {}",
                other.techniques[t].label, c.techniques[f].label, !fresnel
            ));
        }
    }
    Ok(())
}

/// The curves of `other` that `spec` asks for, or why they do not measure what `front` does.
pub fn curves(c: &Config, front: &Results, spec: &CurvesSpec, other: &Results) -> Result<Vec<Curve>, String> {
    if other.meta.device_slug != front.meta.device_slug || other.run.quick != front.run.quick {
        return Err(format!(
            "measured on {}{}, the front on {}{}",
            other.meta.device_slug,
            if other.run.quick { " (--quick)" } else { "" },
            front.meta.device_slug,
            if front.run.quick { " (--quick)" } else { "" }
        ));
    }
    let (a, b) = (&other.run, &front.run);
    if a.validation != b.validation {
        return Err(format!("its run had validation {}, the front's {}", on(a.validation), on(b.validation)));
    }
    let paths = |r: &crate::results::RunInfo| [r.light_path.clone(), r.camera_path.clone(), r.object_path.clone()];
    if paths(a) != paths(b) {
        return Err(format!("its light, camera and object paths are {:?}, the front's {:?}", paths(a), paths(b)));
    }
    let oc: Config =
        toml::from_str(&other.config.toml).map_err(|e| format!("its embedded config does not parse: {e}"))?;
    agree(c, spec, &oc, front.run.quick)?;
    let mut out = vec![];
    for cell in other.cells.iter().filter(|r| !r.progressive.is_empty()) {
        let technique = &cell.cell.technique_label;
        if !spec.draws(technique) {
            continue;
        }
        let scene = scene_label(&cell.cell.scene);
        let same_scene: Vec<_> = front.cells.iter().filter(|f| scene_label(&f.cell.scene) == scene).collect();
        if same_scene.is_empty() {
            continue;
        }
        if cell.busy {
            return Err(format!("{scene}: its `{technique}` cell ran on a busy machine"));
        }
        let fresnel = |v: &serde_json::Value| v.get("fresnel").map_or_else(|| "unset".to_string(), |f| f.to_string());
        for f in same_scene {
            let (mine, theirs) = (&cell.cell, &f.cell);
            let differs = if mine.scene != theirs.scene || cell.models != f.models {
                Some(format!("scene file {} (its models by checksum)", mine.scene))
            } else if mine.resolution != theirs.resolution {
                Some(format!("output {}x{}", mine.resolution[0], mine.resolution[1]))
            } else if (mine.lights, &mine.lighting) != (theirs.lights, &theirs.lighting) {
                Some(format!("lights {} with {} lighting", mine.lights, mine.lighting))
            } else if fresnel(&cell.caustics) != fresnel(&f.caustics) {
                Some(format!("fresnel {}", fresnel(&cell.caustics)))
            } else {
                None
            };
            if let Some(d) = differs {
                return Err(format!(
                    "{scene}: `{technique}` has another {d} than the front's `{}` cell",
                    theirs.technique_label
                ));
            }
        }
        out.push(Curve { scene, technique: technique.clone(), points: cell.progressive.clone() });
    }
    if out.is_empty() {
        return Err("no curve of a scene the front has".into());
    }
    Ok(out)
}

fn on(b: bool) -> &'static str {
    if b {
        "on"
    } else {
        "off"
    }
}

/// The first point of `points` whose error is at most `level`: the time and frames a curve
/// needs to reach it.
pub fn reaches(points: &[Point], level: f64) -> Option<&Point> {
    points.iter().find(|p| p.rel_rmse <= level)
}

/// Per error level, the accumulated time (and frames) at which each of `scene`'s curves first
/// reaches it: the curves' answer to the front's table of cheapest cells. Empty where the
/// scene has no curve. `err` prints an error as the front's table does.
pub fn markdown(c: &FrontCurves, scene: &str, levels: &[f64], x: &str, y: &str, err: &dyn Fn(f64) -> String) -> String {
    let mine: Vec<&Curve> = c.curves.iter().filter(|k| k.scene == scene).collect();
    if mine.is_empty() {
        return String::new();
    }
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Progressive accumulation (`{}`, commit {}): the host time of its frames' passes (those its config names, \
         each named by `{x}` too), added up until each curve's `{y}` is first at most each level, with those frames \
         and the error they reached; the last row, where each curve ends.\n",
        c.table, c.commit
    );
    let names: Vec<&str> = mine.iter().map(|k| k.technique.as_str()).collect();
    let _ = writeln!(s, "| {y} at most | {} |", names.join(" | "));
    let _ = writeln!(s, "|---|{}", "---|".repeat(names.len()));
    let cell = |p: &Point| {
        let frames = if p.frames == 1 { "1 frame".to_string() } else { format!("{} frames", p.frames) };
        format!("{} ({frames}, {})", significant(p.ms), err(p.rel_rmse))
    };
    for &level in levels {
        let row: Vec<String> =
            mine.iter().map(|k| reaches(&k.points, level).map_or_else(|| "(not reached)".to_string(), cell)).collect();
        let _ = writeln!(s, "| {level} | {} |", row.join(" | "));
    }
    let last: Vec<String> = mine.iter().map(|k| k.points.last().map_or_else(String::new, cell)).collect();
    let _ = writeln!(s, "| (end) | {} |\n", last.join(" | "));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_are_drawn_on_their_own_x_and_y_only_and_for_the_techniques_named() {
        let spec = CurvesSpec { table: "t".into(), x: "ms".into(), y: "err".into(), techniques: vec!["a".into()] };
        assert!(spec.drawn_on("ms", "err"));
        assert!(!spec.drawn_on("ms", "FLIP") && !spec.drawn_on("Frame", "err") && !spec.drawn_on("Frame", "FLIP"));
        assert!(spec.draws("a") && !spec.draws("b"));
        assert!(CurvesSpec { techniques: vec![], ..spec }.draws("b"));
    }
}
