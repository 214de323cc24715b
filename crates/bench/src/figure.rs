//! What a table's plot shows, independent of how it is drawn: one panel of values per metric
//! (ours solid, the paper's dashed in the same colour), against photon count where photons is a
//! row axis, else as grouped bars over the rows (Table 5's scenes); then, where the config
//! compares against a baseline, a panel of ratios against it per metric. A panel with more
//! series than its legend can list (W&D 2006 Table 1: 6 scenes × 8 columns, each with the
//! paper's) becomes small multiples: one panel per row group (scene), its series the columns.

use crate::config::Config;
use crate::format::{display, unit};
use crate::results::Results;
use crate::table::{Entry, Grid};

#[derive(Debug, Clone)]
pub struct Figure {
    pub title: String,
    pub subtitle: String,
    pub panels: Vec<Panel>,
}

#[derive(Debug, Clone)]
pub struct Panel {
    pub title: String,
    pub y_label: String,
    pub log_y: bool,
    /// Tick labels of the x axis, evenly spaced: photon counts (`256²`) or row labels.
    pub x_labels: Vec<String>,
    /// Grouped bars over categories rather than lines over photon counts.
    pub bars: bool,
    /// Draw a line at y = 1 (the baseline of a ratio panel).
    pub unit_line: bool,
    pub series: Vec<Series>,
}

#[derive(Debug, Clone)]
pub struct Series {
    pub label: String,
    /// Palette index: a column keeps its colour across panels, the paper's shares ours.
    pub colour: usize,
    /// The paper's values: dashed line, hollow bar.
    pub paper: bool,
    /// (x index, value).
    pub points: Vec<(usize, f64)>,
}

/// The most series a panel's legend lists readably (rows of at least 12 px in a 420 px panel);
/// a panel with more is split by row group.
pub const MAX_SERIES: usize = 28;

/// How many times its smallest value a panel's largest may be on a linear axis: beyond it,
/// everything under a hundredth of the largest would lie on the zero line (Wyman & Davis 2006
/// Fig. 10: the metal octahedron's quads read 957 where the other techniques read 0.1-0.4).
pub const LINEAR_SPAN: f64 = 100.0;

/// Whether `series` has values, all of them positive, whose largest is more than
/// [`LINEAR_SPAN`] times the smallest: such a panel is drawn on a log axis.
pub fn spans_decades(series: &[Series]) -> bool {
    let values: Vec<f64> =
        series.iter().flat_map(|s| s.points.iter().map(|&(_, v)| v)).filter(|v| v.is_finite()).collect();
    let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    !values.is_empty() && lo > 0.0 && hi > LINEAR_SPAN * lo
}

/// Colour indices by series name, in first-seen order over the whole figure.
#[derive(Default)]
struct Palette(Vec<String>);

impl Palette {
    fn of(&mut self, name: &str) -> usize {
        self.0.iter().position(|n| n == name).unwrap_or_else(|| {
            self.0.push(name.to_string());
            self.0.len() - 1
        })
    }
}

/// The columns of each value panel: the sections' columns grouped by metric.
fn panel_columns(g: &Grid) -> Vec<(Option<String>, Vec<usize>)> {
    let mut out: Vec<(Option<String>, Vec<usize>)> = vec![];
    for sec in &g.sections {
        for &ci in &sec.cols {
            let m = sec.metric.clone().or_else(|| g.metric_of(ci));
            match out.iter_mut().find(|(x, _)| *x == m) {
                Some((_, cols)) => cols.push(ci),
                None => out.push((m, vec![ci])),
            }
        }
    }
    out
}

pub fn figure(config: &Config, results: &Results, g: &Grid) -> Figure {
    let photons = g.row_axes.iter().position(|a| a == "photons");
    // Rows group into series by their labels other than photons, and into x positions by photons.
    let group_of = |ri: usize| -> String {
        let labels = g.row_labels(ri);
        labels
            .iter()
            .enumerate()
            .filter(|(i, _)| Some(*i) != photons)
            .map(|(_, l)| l.clone())
            .collect::<Vec<_>>()
            .join(" · ")
    };
    let x_of = |ri: usize| -> usize { photons.map_or(ri, |p| g.rows[ri][p].parse::<usize>().unwrap_or(0)) };
    let mut xs: Vec<usize> = (0..g.rows.len()).map(x_of).collect();
    xs.sort_unstable();
    xs.dedup();
    let x_index = |ri: usize| xs.iter().position(|&x| x == x_of(ri)).unwrap_or(0);
    let x_labels: Vec<String> = match photons {
        Some(_) => xs.iter().map(|x| display("photons", &x.to_string())).collect(),
        None => (0..g.rows.len()).map(|ri| g.row_labels(ri).join(" · ")).collect(),
    };
    let mut palette = Palette::default();
    let mut panels = vec![];
    let cols = panel_columns(g);
    let kind_of = |m: &Option<String>| m.as_deref().and_then(|l| config.metric_kind(l)).unwrap_or_default().to_string();
    // Row groups (the rows' labels other than photons), in first-seen order.
    let groups = crate::format::first_seen((0..g.rows.len()).map(group_of));
    // Series: one per column and row group of the rows in `group` (None: all rows); `value`
    // picks what each entry contributes. Within one group's panel a series is its column.
    let mut series_of =
        |cols: &[usize], group: Option<&str>, value: &dyn Fn(usize, usize) -> (Option<f64>, Option<f64>)| {
            let mut out: Vec<Series> = vec![];
            for &ci in cols {
                for ri in (0..g.rows.len()).filter(|&ri| group.is_none_or(|grp| group_of(ri) == grp)) {
                    let name = match (photons.is_some() && group.is_none(), group_of(ri)) {
                        (true, grp) if !grp.is_empty() => format!("{grp} · {}", g.cols[ci].header),
                        _ => g.cols[ci].header.clone(),
                    };
                    let colour = palette.of(&name);
                    let (ours, paper) = value(ri, ci);
                    let x = x_index(ri);
                    for (is_paper, v) in [(false, ours), (true, paper)] {
                        let label = if is_paper { format!("{name} (paper)") } else { name.clone() };
                        let s = match out.iter_mut().position(|s| s.label == label) {
                            Some(i) => &mut out[i],
                            None => {
                                out.push(Series { label, colour, paper: is_paper, points: vec![] });
                                out.last_mut().expect("just pushed")
                            }
                        };
                        if let Some(v) = v.filter(|v| v.is_finite()) {
                            s.points.push((x, v));
                        }
                    }
                }
            }
            // Paper series the paper has no value for are left out; ours stay (a gap says so).
            out.retain(|s| !s.paper || !s.points.is_empty());
            out
        };
    let bars = photons.is_none();
    // What each panel shows: its title, y label, log scale, line at 1, columns, and whether its
    // values are ratios against the compared baseline.
    struct Spec {
        title: String,
        y_label: String,
        log_y: bool,
        ratio: bool,
        cols: Vec<usize>,
    }
    let mut specs = vec![];
    for (metric, cs) in &cols {
        let u = unit(&kind_of(metric));
        specs.push(Spec {
            title: metric.clone().unwrap_or_default(),
            y_label: if u.is_empty() { metric.clone().unwrap_or_else(|| "value".into()) } else { u.to_string() },
            log_y: config.table.plot_log_y,
            ratio: false,
            cols: cs.clone(),
        });
    }
    let cmp = config.layout.compare.as_ref();
    if let Some(cmp) = cmp {
        let base = display(&cmp.axis, &cmp.baseline);
        for (metric, cs) in &cols {
            if !cmp.metrics.is_empty() && !metric.as_ref().is_some_and(|m| cmp.metrics.contains(m)) {
                continue;
            }
            let not_base = |ci: usize| !g.entries.iter().all(|r| r[ci].keys.get(&cmp.axis) == Some(&cmp.baseline));
            let what = metric.as_ref().map(|m| format!("{m}: ")).unwrap_or_default();
            specs.push(Spec {
                title: format!("{what}ratio against {base}"),
                y_label: format!("÷ {base}"),
                log_y: true,
                ratio: true,
                cols: cs.iter().copied().filter(|&ci| not_base(ci)).collect(),
            });
        }
    }
    let value = |ratio: bool, ri: usize, ci: usize| -> (Option<f64>, Option<f64>) {
        let e = &g.entries[ri][ci];
        match (ratio, cmp) {
            (true, Some(c)) => self::ratio(g, e, &c.axis, &c.baseline),
            _ => (e.ours, e.paper.as_ref().map(|p| p.value)),
        }
    };
    // Small multiples when a panel of every row group would list more series than fit.
    let split = photons.is_some()
        && groups.len() > 1
        && specs.iter().any(|sp| sp.cols.len() * (g.rows.len() / xs.len().max(1)) * 2 > MAX_SERIES);
    let panel_groups: Vec<Option<&str>> =
        if split { groups.iter().map(|grp| Some(grp.as_str())).collect() } else { vec![None] };
    for group in panel_groups {
        for sp in &specs {
            let series = series_of(&sp.cols, group, &|ri, ci| value(sp.ratio, ri, ci));
            if sp.ratio && series.iter().all(|s| s.points.is_empty()) {
                continue;
            }
            // A linear panel whose values span decades is drawn on a log axis, and says so.
            let wide = !sp.log_y && spans_decades(&series);
            panels.push(Panel {
                title: match group {
                    Some(grp) => format!("{grp} · {}", sp.title),
                    None => sp.title.clone(),
                },
                y_label: if wide { format!("{} (log scale)", sp.y_label) } else { sp.y_label.clone() },
                log_y: sp.log_y || wide,
                x_labels: x_labels.clone(),
                bars,
                unit_line: sp.ratio,
                series,
            });
        }
    }
    let m = &results.meta;
    Figure {
        title: config.table.title(),
        subtitle: format!(
            "{} · {} · {}{}",
            m.device,
            m.driver_info,
            m.date,
            if results.run.quick { " · quick run, not a measurement" } else { "" }
        ),
        panels,
    }
}

/// Ours and the paper's ratio of `e` against its baseline entry (the paper's only where both of
/// its values are comparable).
fn ratio(g: &Grid, e: &Entry, axis: &str, baseline: &str) -> (Option<f64>, Option<f64>) {
    if e.keys.get(axis).map(String::as_str) == Some(baseline) {
        return (None, None);
    }
    let Some(b) = g.baseline_of(e, axis, baseline) else { return (None, None) };
    let ours = e.ours.zip(b.ours).filter(|(_, y)| *y != 0.0).map(|(x, y)| x / y);
    let paper = match (&e.paper, &b.paper) {
        (Some(x), Some(y)) if x.comparable() && y.comparable() && y.value != 0.0 => Some(x.value / y.value),
        _ => None,
    };
    (ours, paper)
}
