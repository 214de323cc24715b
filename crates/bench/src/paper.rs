//! The paper's published values: which axes an entry fixes, and the value for a table cell.

use crate::config::{Config, PaperEntry};
use std::collections::BTreeMap;

/// (axis, label) pairs an entry names, in axis order.
pub fn fixed_axes(e: &PaperEntry) -> Vec<(&'static str, String)> {
    let mut v = vec![];
    if let Some(s) = &e.scene {
        v.push(("scene", s.clone()));
    }
    if let Some(t) = &e.technique {
        v.push(("technique", t.clone()));
    }
    if let Some(p) = e.photons {
        v.push(("photons", p.to_string()));
    }
    if let Some(l) = e.lights {
        v.push(("lights", crate::plan::lights_label(l)));
    }
    if let Some(r) = &e.resolution {
        v.push(("resolution", r.clone()));
    }
    if let Some(l) = &e.lighting {
        v.push(("lighting", l.clone()));
    }
    if let Some(m) = &e.metric {
        v.push(("metric", m.clone()));
    }
    v
}

/// The published value of the table cell whose axis labels are `keys` (every axis, metric
/// included), if the paper has one.
pub fn value(c: &Config, keys: &BTreeMap<String, String>) -> Option<f64> {
    let inner = c.layout.columns.last()?;
    let inner_key = keys.get(inner)?;
    c.paper
        .iter()
        .filter(|e| fixed_axes(e).iter().all(|(a, v)| keys.get(*a) == Some(v)))
        .find_map(|e| e.values.get(inner_key).copied())
}
