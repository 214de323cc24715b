//! The paper's published values: which axes an entry fixes, and the value for a table cell with
//! what the config says about it (measured on another scene, or not comparable at all).

use crate::config::{ColumnSpec, Config, PaperEntry};
use std::collections::BTreeMap;

/// A published value for one table cell.
#[derive(Debug, Clone, PartialEq)]
pub struct PaperValue {
    pub value: f64,
    /// The paper's scene, when it is not ours (`scene_note`).
    pub scene_note: Option<String>,
    /// Why the paper's value measures other work (`not_comparable`).
    pub not_comparable: Option<String>,
}

impl PaperValue {
    /// Does a ratio against this value say anything? Not when the paper measured another
    /// scene or other work.
    pub fn comparable(&self) -> bool {
        self.scene_note.is_none() && self.not_comparable.is_none()
    }
}

/// (axis, label) pairs of the axis fields shared by `[[paper]]` and `[[layout.column]]`.
#[allow(clippy::too_many_arguments)]
fn pairs(
    scene: &Option<String>,
    technique: &Option<String>,
    photons: Option<u32>,
    lights: Option<u32>,
    resolution: &Option<String>,
    lighting: &Option<String>,
    metric: &Option<String>,
) -> Vec<(&'static str, String)> {
    let mut v = vec![];
    if let Some(s) = scene {
        v.push(("scene", s.clone()));
    }
    if let Some(t) = technique {
        v.push(("technique", t.clone()));
    }
    if let Some(p) = photons {
        v.push(("photons", p.to_string()));
    }
    if let Some(l) = lights {
        v.push(("lights", crate::plan::lights_label(l)));
    }
    if let Some(r) = resolution {
        v.push(("resolution", r.clone()));
    }
    if let Some(l) = lighting {
        v.push(("lighting", l.clone()));
    }
    if let Some(m) = metric {
        v.push(("metric", m.clone()));
    }
    v
}

/// (axis, label) pairs an entry names, in axis order.
pub fn fixed_axes(e: &PaperEntry) -> Vec<(&'static str, String)> {
    pairs(&e.scene, &e.technique, e.photons, e.lights, &e.resolution, &e.lighting, &e.metric)
}

/// (axis, label) pairs a `[[layout.column]]` names, in axis order.
pub fn column_axes(c: &ColumnSpec) -> Vec<(&'static str, String)> {
    pairs(&c.scene, &c.technique, c.photons, c.lights, &c.resolution, &c.lighting, &c.metric)
}

/// The published value of the table cell whose axis labels are `keys` (every axis, metric
/// included), if the paper has one.
pub fn value(c: &Config, keys: &BTreeMap<String, String>) -> Option<PaperValue> {
    let inner = c.layout.columns.last()?;
    let inner_key = keys.get(inner)?;
    c.paper.iter().filter(|e| fixed_axes(e).iter().all(|(a, v)| keys.get(*a) == Some(v))).find_map(|e| {
        e.values.get(inner_key).map(|&value| PaperValue {
            value,
            scene_note: e.scene_note.clone(),
            not_comparable: e.not_comparable.clone(),
        })
    })
}
