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

/// Where in the paper some of an entry's values come from: one citation of its `source`
/// (`bench_configs/README.md`, `[[paper]]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Citation {
    /// The `values` keys it covers.
    pub keys: Vec<String>,
    pub place: Place,
    /// The citation as written (without its keys).
    pub text: String,
}

/// The place a citation names.
#[derive(Debug, Clone, PartialEq)]
pub enum Place {
    /// `Table N, row R`: the table's number and the labels that find its row, outermost first
    /// (`row Ball & Dragon / 512²`: the first row labelled `Ball & Dragon`, then from it on the
    /// first labelled `512²`).
    Table { number: String, row: Vec<String> },
    /// `Sec. X`, optionally `, paragraph 'words'`: the paragraph of section X that contains the
    /// words.
    Section { number: String, paragraph: Option<String> },
    /// `read from Fig. N`: a chart, read by eye; no text holds the value.
    Figure { number: String },
}

const KINDS: &str = "`Table N, row R`, `Sec. N` (optionally `, paragraph 'words'`) or `read from Fig. N`";

/// Splits `s` at `sep` outside single quotes. A quote opens after a space (or at the start) and
/// closes before a comma, a semicolon, a space (or at the end), so an apostrophe (`Davis's`)
/// is not one.
fn split_outside_quotes<'a>(s: &'a str, sep: &str) -> Result<Vec<&'a str>, String> {
    let b = s.as_bytes();
    let mut parts = vec![];
    let mut start = 0;
    let mut quoted = false;
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'\'' {
            let before = i == 0 || b[i - 1] == b' ';
            let after = i + 1 == b.len() || matches!(b[i + 1], b',' | b';' | b' ');
            if !quoted && before {
                quoted = true;
            } else if quoted && after {
                quoted = false;
            }
        } else if !quoted && b[i..].starts_with(sep.as_bytes()) {
            parts.push(&s[start..i]);
            i += sep.len();
            start = i;
            continue;
        }
        i += 1;
    }
    if quoted {
        return Err(format!("`{s}`: a quote (') is not closed"));
    }
    parts.push(&s[start..]);
    Ok(parts)
}

/// `'words'` → `words`; anything else as it is.
fn unquote(s: &str) -> &str {
    s.strip_prefix('\'').and_then(|s| s.strip_suffix('\'')).unwrap_or(s)
}

/// A table, section or figure number: digits and dots, e.g. `3` or `5.2`.
fn number(n: &str, what: &str, text: &str) -> Result<String, String> {
    if n.is_empty() || !n.chars().all(|c| c.is_ascii_digit() || c == '.') || n.starts_with('.') || n.ends_with('.') {
        return Err(format!("`{text}`: `{n}` is not a {what} number (e.g. 3 or 5.2)"));
    }
    Ok(n.to_string())
}

/// One citation without its keys.
fn place(text: &str) -> Result<Place, String> {
    let fields = split_outside_quotes(text, ", ")?;
    let head = fields[0].trim();
    if let Some(n) = head.strip_prefix("Table ") {
        let number = number(n, "table", text)?;
        let Some(row) = fields.get(1).and_then(|f| f.trim().strip_prefix("row ")) else {
            return Err(format!("`{text}`: a table's citation names its row: `Table {number}, row R`"));
        };
        let row: Vec<String> =
            split_outside_quotes(row, " / ")?.iter().map(|l| unquote(l.trim()).to_string()).collect();
        if row.iter().any(|l| l.trim().is_empty()) {
            return Err(format!("`{text}`: an empty row label"));
        }
        Ok(Place::Table { number, row })
    } else if let Some(n) = head.strip_prefix("Sec. ") {
        let number = number(n, "section", text)?;
        let mut paragraph = None;
        for f in &fields[1..] {
            if let Some(p) = f.trim().strip_prefix("paragraph ") {
                let words = p.strip_prefix('\'').and_then(|p| p.strip_suffix('\''));
                match words {
                    Some(w) if !w.trim().is_empty() => paragraph = Some(w.to_string()),
                    _ => return Err(format!("`{text}`: quote the paragraph's words: `paragraph 'words'`")),
                }
            }
        }
        Ok(Place::Section { number, paragraph })
    } else if let Some(n) = head.strip_prefix("read from Fig. ") {
        Ok(Place::Figure { number: number(n, "figure", text)? })
    } else {
        Err(format!("`{text}`: a citation is {KINDS}"))
    }
}

/// The citations of an entry's `source`: parts separated by `; `, each but one prefixed by the
/// `values` keys it covers (`height field fps: Sec. 5.1, ...`); the one without covers the rest.
/// Every key of `values` is covered by exactly one. Errors say what is wrong, without the key.
pub fn citations(e: &PaperEntry) -> Result<Vec<Citation>, String> {
    let Some(source) = e.source.as_deref() else {
        return Err(format!("missing: say where in the paper the values are, as {KINDS}"));
    };
    if source.trim().is_empty() {
        return Err("must not be empty".into());
    }
    let mut out: Vec<Citation> = vec![];
    let mut rest: Option<usize> = None;
    for part in split_outside_quotes(source, "; ")? {
        let part = part.trim();
        let starts = ["Table ", "Sec. ", "read from Fig. "].iter().any(|k| part.starts_with(k));
        let (keys, text) = match part.split_once(": ") {
            Some((keys, text)) if !starts => (keys.split(", ").map(|k| k.trim().to_string()).collect(), text.trim()),
            _ => (vec![], part),
        };
        for k in &keys {
            if !e.values.contains_key(k) {
                return Err(format!("`{part}` names `{k}`, which is not a key of `values`"));
            }
            if out.iter().any(|c| c.keys.contains(k)) {
                return Err(format!("`{k}` is cited twice"));
            }
        }
        if keys.is_empty() {
            if rest.is_some() {
                return Err(format!(
                    "`{part}`: only one citation may go without the keys it covers (`KEY, KEY: citation`)"
                ));
            }
            rest = Some(out.len());
        }
        out.push(Citation { keys, place: place(text)?, text: text.to_string() });
    }
    let named: Vec<String> = out.iter().flat_map(|c| c.keys.clone()).collect();
    let uncited: Vec<String> = e.values.keys().filter(|k| !named.contains(k)).cloned().collect();
    match rest {
        Some(i) if uncited.is_empty() => {
            Err(format!("`{}` covers no value: the other citations name every key", out[i].text))
        }
        Some(i) => {
            out[i].keys = uncited;
            Ok(out)
        }
        None if !uncited.is_empty() => Err(format!("no citation covers {}", uncited.join(", "))),
        None => Ok(out),
    }
}

/// The axes an entry fixes, for messages: `scene = pool, photons = 128`.
pub fn describe(e: &PaperEntry) -> String {
    let axes = fixed_axes(e);
    if axes.is_empty() {
        return "(no axes)".into();
    }
    axes.iter().map(|(a, v)| format!("{a} = {v}")).collect::<Vec<_>>().join(", ")
}
