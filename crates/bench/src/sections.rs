//! The printed tables of a grid, in Markdown or plain text: each section laid out like the
//! paper's table with every entry `ours ±spread (paper)`, the legend under them, and the ratios
//! against the config's baseline as one compact grid per metric.

use crate::config::Config;
use crate::format::{format_value, paper_value, ratio};
use crate::table::{Entry, Grid, Section};
use crate::text_table::{Style, TextTable, WIDTH};

/// An entry whose technique cannot run at its photon count (Wyman & Nichols 2009 Table 1's N/A).
pub const NOT_RUN: &str = "N/A";
/// An entry a partial merge has no cell for (`bench merge --partial`).
pub const MISSING: &str = "not run";
/// An entry whose value the device cannot have measured (plausibility rules c, e, f).
pub const UNMEASURED: &str = "not measured";

/// Superscript markers of the "not comparable" footnotes.
const MARKS: [&str; 9] = ["¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"];

/// Distinct `not_comparable` reasons, in order of appearance.
#[derive(Default)]
pub struct Footnotes(Vec<String>);

impl Footnotes {
    fn mark(&mut self, reason: &str) -> String {
        let i = match self.0.iter().position(|r| r == reason) {
            Some(i) => i,
            None => {
                self.0.push(reason.to_string());
                self.0.len() - 1
            }
        };
        MARKS.get(i).map(|m| m.to_string()).unwrap_or_else(|| format!("[{}]", i + 1))
    }

    pub fn lines(&self) -> Vec<String> {
        self.0
            .iter()
            .enumerate()
            .map(|(i, r)| format!("{} The paper's value measures other work: {r}", MARKS.get(i).unwrap_or(&"*")))
            .collect()
    }
}

/// `ours ±s% (paper)`: the spread for times, the paper's value where it has one, with its
/// scene when that is not ours and a footnote mark when it is not comparable.
pub fn cell_text(e: &Entry, notes: &mut Footnotes) -> String {
    let mut s = if e.not_run {
        NOT_RUN.to_string()
    } else if e.missing {
        MISSING.to_string()
    } else if let Some(rule) = &e.unmeasured {
        format!("{UNMEASURED} ({rule})")
    } else {
        format_value(&e.kind, e.ours)
    };
    if let (Some(sp), Some(_)) = (e.spread, e.ours) {
        s.push(' ');
        s.push_str(&crate::stats::format_spread(sp));
    }
    if e.busy {
        s.push('~');
    }
    if e.implausible {
        s.push('?');
    }
    if let Some(p) = &e.paper {
        let mut inner = paper_value(&e.kind, Some(p.value));
        if let Some(r) = &p.not_comparable {
            inner.push_str(&notes.mark(r));
        }
        if let Some(scene) = &p.scene_note {
            inner = format!("{inner}, {scene}");
        }
        s = format!("{s} ({inner})");
    }
    s
}

fn heading(style: Style, level: usize, text: &str) -> String {
    match style {
        Style::Markdown => format!("{} {text}\n\n", "#".repeat(level)),
        Style::Plain => format!("{text}\n"),
    }
}

fn stub_headers(g: &Grid) -> Vec<String> {
    g.row_axes.clone()
}

/// Every section of the grid as a table, each under the name of its metric when split.
pub fn value_tables(g: &Grid, style: Style, notes: &mut Footnotes) -> String {
    let mut out = String::new();
    for sec in &g.sections {
        if let Some(m) = &sec.metric {
            out.push_str(&heading(style, 3, m));
        }
        let mut t = TextTable {
            stub_headers: stub_headers(g),
            headers: sec.cols.iter().map(|&ci| g.cols[ci].header.clone()).collect(),
            rows: vec![],
        };
        for ri in 0..g.rows.len() {
            let cells = sec.cols.iter().map(|&ci| cell_text(&g.entries[ri][ci], notes)).collect();
            t.rows.push((g.row_labels(ri), cells));
        }
        t.group_stub();
        out.push_str(&t.render(style, WIDTH));
        out.push('\n');
    }
    out
}

/// Counts of timed entries and of flagged ones, over the printed sections.
pub fn flagged(g: &Grid) -> (usize, usize) {
    let shown = printed(g);
    let timed = shown.iter().filter(|e| e.spread.is_some()).count();
    (timed, shown.iter().filter(|e| e.noisy()).count())
}

fn printed(g: &Grid) -> Vec<&Entry> {
    let mut cols: Vec<usize> = g.sections.iter().flat_map(|s| s.cols.iter().copied()).collect();
    cols.sort_unstable();
    cols.dedup();
    g.entries.iter().flat_map(|row| cols.iter().map(move |&ci| &row[ci])).collect()
}

/// The lines under the tables: how to read a cell, and the footnotes.
pub fn legend(g: &Grid, notes: &Footnotes) -> Vec<String> {
    let mut lines = vec![];
    let (timed, noisy) = flagged(g);
    if timed > 0 {
        lines.push(format!(
            "Times are medians over each cell's measured frames; ±s% is their interquartile range as a share of \
             the median, and `!` marks a spread over {:.0}% ({noisy} of {timed} timed cells): do not rank \
             techniques by such a median.",
            crate::stats::NOISY_SPREAD * 100.0
        ));
    }
    let (busy, implausible) = (
        g.entries.iter().flatten().filter(|e| e.busy).count(),
        g.entries.iter().flatten().filter(|e| e.implausible).count(),
    );
    let remeasured = g.entries.iter().flatten().filter(|e| e.remeasured).count();
    if remeasured > 0 {
        lines.push(format!(
            "{remeasured} timed entries come from cells measured again because a timed metric's spread was over \
             {:.0}%: each cell keeps its attempt with the smallest spread (every attempt's largest spread is in the \
             JSON, `spread_attempts`).",
            crate::stats::NOISY_SPREAD * 100.0
        ));
    }
    if busy > 0 {
        lines.push(format!(
            "`~` marks {busy} entries whose cell ran while other processes kept the machine busy, even when measured \
             again: not a quiet machine's times."
        ));
    }
    let unmeasured = g.entries.iter().flatten().filter(|e| e.unmeasured.is_some()).count();
    if unmeasured > 0 {
        lines.push(format!(
            "`{UNMEASURED} (rule)` marks {unmeasured} entries whose value the device cannot have done (rules c, e, f \
             under *Plausibility*: faster than it can copy or write, or far below the host time of the same passes): \
             its clock missed the work, so no number is given; read the host-timed columns where the table has them."
        ));
    }
    if implausible > 0 {
        lines.push(format!(
            "`?` marks {implausible} implausible entries (listed under *Plausibility* in the table's .md): not numbers to cite until \
             fixed or explained."
        ));
    }
    if g.has_paper() {
        lines.push(
            "In parentheses: the paper's value for the same cell; `(x, Scene)`: the paper measured Scene, not ours."
                .into(),
        );
    }
    lines.extend(notes.lines());
    lines
}

/// Our ratio and, where both of the paper's cells measure the same work on our kind of scene,
/// the paper's: `0.38 (0.20)`; `!` when either time is flagged.
fn ratio_text(e: &Entry, b: &Entry) -> Option<String> {
    let ours = match (e.ours, b.ours) {
        (Some(x), Some(y)) if y != 0.0 => Some(x / y),
        _ => None,
    };
    let paper = match (&e.paper, &b.paper) {
        (Some(x), Some(y)) if x.comparable() && y.comparable() && y.value != 0.0 => Some(x.value / y.value),
        _ => None,
    };
    if ours.is_none() && paper.is_none() {
        return None;
    }
    let mut s = ours.map(ratio).unwrap_or_else(|| "–".into());
    if e.noisy() || b.noisy() {
        s.push('!');
    }
    if let Some(p) = paper {
        s = format!("{s} ({})", ratio(p));
    }
    Some(s)
}

/// The ratio grid of one section: its rows and columns less the baseline's, each entry over
/// the baseline's entry with the same other labels. `None` when nothing has a ratio.
fn ratio_table(g: &Grid, sec: &Section, axis: &str, baseline: &str) -> Option<TextTable> {
    let is_base = |e: &Entry| e.keys.get(axis).map(String::as_str) == Some(baseline);
    let cols: Vec<usize> = sec.cols.iter().copied().filter(|&ci| !g.entries.iter().all(|r| is_base(&r[ci]))).collect();
    let rows: Vec<usize> = (0..g.rows.len()).filter(|&ri| !g.entries[ri].iter().all(is_base)).collect();
    let mut t = TextTable {
        stub_headers: stub_headers(g),
        headers: cols.iter().map(|&ci| g.cols[ci].header.clone()).collect(),
        rows: vec![],
    };
    let mut any = false;
    for &ri in &rows {
        let cells: Vec<String> = cols
            .iter()
            .map(|&ci| {
                let e = &g.entries[ri][ci];
                let r = g.baseline_of(e, axis, baseline).and_then(|b| ratio_text(e, b));
                any |= r.is_some();
                r.unwrap_or_else(|| "–".into())
            })
            .collect();
        t.rows.push((g.row_labels(ri), cells));
    }
    t.group_stub();
    any.then_some(t)
}

/// `Ratios against <axis> <baseline>`: one grid per section (per metric when split, restricted
/// to `compare.metrics` when given).
pub fn ratio_tables(config: &Config, g: &Grid, style: Style) -> String {
    let Some(cmp) = &config.layout.compare else { return String::new() };
    let wanted = |m: &Option<String>| cmp.metrics.is_empty() || m.as_ref().is_some_and(|m| cmp.metrics.contains(m));
    let mut out = String::new();
    for sec in &g.sections {
        // A section of picked columns keeps the columns of the wanted metrics.
        let sec = Section {
            metric: sec.metric.clone(),
            cols: sec.cols.iter().copied().filter(|&ci| wanted(&sec.metric.clone().or(g.metric_of(ci)))).collect(),
        };
        let Some(t) = ratio_table(g, &sec, &cmp.axis, &cmp.baseline) else { continue };
        if let Some(m) = &sec.metric {
            out.push_str(&heading(style, 3, m));
        }
        out.push_str(&t.render(style, WIDTH));
        out.push('\n');
    }
    if out.is_empty() {
        return out;
    }
    let title = format!("Ratios against {} `{}`", cmp.axis, crate::format::display(&cmp.axis, &cmp.baseline));
    let legend = "Each cell: our value over the baseline's, then the paper's in parentheses where both of its \
                  values are for the same work on our kind of scene; `!`: one of our two times is flagged.";
    let legend = match style {
        Style::Markdown => legend.to_string(),
        Style::Plain => crate::text_table::wrap(legend, WIDTH),
    };
    format!("{}{out}{legend}\n", heading(style, 2, &title))
}
