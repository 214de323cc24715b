//! `<config>.md` (laid out like the paper's table, ours beside the paper's, ratios of ratios
//! where the config compares along an axis), `<config>.csv` (one row per cell and metric) and
//! `<config>.svg` (the papers' line charts: values against photon count).

use crate::config::Config;
use crate::results::Results;
use crate::svg::{Chart, Series};
use crate::table::{display, format_value, grid, unit, Grid};
use std::fmt::Write as _;

fn header_of(axes: &[String], keys: &[String]) -> String {
    axes.iter().zip(keys).map(|(a, k)| display(a, k)).collect::<Vec<_>>().join(" · ")
}

pub fn markdown(config: &Config, results: &Results) -> String {
    let g = grid(config, results);
    let has_paper = g.entries.iter().flatten().any(|e| e.paper.is_some());
    let m = &results.meta;
    let r = &results.run;
    let mut s = String::new();
    let _ = writeln!(s, "# {}, Table {}\n", config.table.paper, config.table.number);
    let _ = writeln!(s, "> {}\n", config.table.caption);
    if r.quick {
        let _ =
            writeln!(s, "**Quick run (`--quick`): small sizes and few frames, a smoke test, not a measurement.**\n");
    }
    if r.validation {
        let _ = writeln!(s, "**Validation layers were on: these times are not measurements.**\n");
    }
    let _ = writeln!(
        s,
        "- **Device:** {} ({}), driver {} {}, Vulkan {}\n- **CPU:** {}\n- **Commit:** {} · **date:** {} · \
         **config:** `{}` (hash {})",
        m.device,
        m.device_type,
        m.driver_name,
        m.driver_info,
        m.vulkan_version,
        m.cpu,
        m.commit,
        m.date,
        results.config.file,
        results.config.hash
    );
    let _ = writeln!(
        s,
        "- **Run:** {} warm-up + {} measured frames per cell; light path {}, camera path {}, object path {} \
         ({} frames per loop). Times are medians over the measured frames; fps is 1000 / mean frame time.",
        r.warmup_frames, r.measured_frames, r.light_path, r.camera_path, r.object_path, r.period_frames
    );
    if !m.quirks.is_empty() {
        let _ = writeln!(s, "- **Device quirks worked around:** {}", m.quirks.join("; "));
    }
    if let Some(line) = steal_line(results) {
        let _ = writeln!(s, "{line}");
    }
    let _ = writeln!(s);
    // The table: for each column, ours then the paper's.
    let mut head = g.row_axes.iter().map(|a| a.to_string()).collect::<Vec<_>>();
    for c in &g.cols {
        let h = header_of(&g.col_axes, c);
        if has_paper {
            head.push(format!("{h} (ours)"));
            head.push("paper".into());
        } else {
            head.push(h);
        }
    }
    let _ = writeln!(s, "| {} |", head.join(" | "));
    let _ = writeln!(s, "|{}", head.iter().map(|_| "---|").collect::<String>());
    for (ri, row) in g.rows.iter().enumerate() {
        let mut cells: Vec<String> = g.row_axes.iter().zip(row).map(|(a, k)| display(a, k)).collect();
        for e in &g.entries[ri] {
            cells.push(format_value(&e.kind, e.ours));
            if has_paper {
                cells.push(paper_value(&e.kind, e.paper));
            }
        }
        let _ = writeln!(s, "| {} |", cells.join(" | "));
    }
    if let Some(line) = units_line(config.metrics.iter().map(|m| (m.label.as_str(), m.kind.as_str()))) {
        let _ = writeln!(s, "\n{line}");
    }
    ratios(&mut s, config, &g, has_paper);
    let mut notes = config.table.notes.clone();
    if m.driver_name.to_lowercase().contains("llvmpipe") || m.device.to_lowercase().contains("llvmpipe") {
        notes.push(
            "lavapipe runs every pass serially on the CPU: its times are CPU time, fine for ratios between \
             techniques on this machine, never comparable with GPU numbers. Its timestamps miss the draws that \
             stream out with rasterization discarded (the `xfb` hierarchical traversal): their work falls \
             outside every timestamp pair, so those passes read near zero; `frame_ms` (host wall time) counts it."
                .into(),
        );
    }
    if !notes.is_empty() {
        let _ = writeln!(s, "\n## Notes\n");
        for n in notes {
            let _ = writeln!(s, "- {n}");
        }
    }
    let _ = writeln!(s, "\n![plot]({}.svg)\n", results.config.name);
    let _ = writeln!(
        s,
        "Regenerate: `causticlab bench {}{}`; raw samples in `{}.json`, one row per cell and metric in `{}.csv`.",
        results.config.file,
        if r.quick { " --quick" } else { "" },
        results.config.name,
        results.config.name
    );
    s
}

/// The unit of every column: `Values in ms.` when all metrics share one, else each unit with the
/// metrics (by label) in it, e.g. ``Values: `Gather`, `Frame` in ms; `processed` in points.``.
/// `None` when no metric has a unit (quality tables).
fn units_line<'a>(metrics: impl Iterator<Item = (&'a str, &'a str)>) -> Option<String> {
    let mut groups: Vec<(&str, Vec<&str>)> = vec![];
    for (label, kind) in metrics {
        let u = unit(kind);
        match groups.iter_mut().find(|(g, _)| *g == u) {
            Some((_, labels)) => labels.push(label),
            None => groups.push((u, vec![label])),
        }
    }
    match groups.as_slice() {
        [] | [("", _)] => None,
        [(u, _)] => Some(format!("Values in {u}.")),
        _ => {
            let parts: Vec<String> = groups
                .iter()
                .map(|(u, labels)| {
                    let names = labels.iter().map(|l| format!("`{l}`")).collect::<Vec<_>>().join(", ");
                    if u.is_empty() {
                        format!("{names} unitless")
                    } else {
                        format!("{names} in {u}")
                    }
                })
                .collect();
            Some(format!("Values: {}.", parts.join("; ")))
        }
    }
}

/// Ratios against the baseline of `layout.compare`: ours, the paper's, and ours ÷ the paper's
/// (1.0 = the same relative cost as in the paper).
fn ratios(s: &mut String, config: &Config, g: &Grid, has_paper: bool) {
    let Some(cmp) = &config.layout.compare else { return };
    let _ = writeln!(s, "\n## Ratios against {} `{}`\n", cmp.axis, display(&cmp.axis, &cmp.baseline));
    let _ = writeln!(s, "| {} | {} | ours | paper | ours ÷ paper |", g.row_axes.join(" · "), g.col_axes.join(" · "));
    let _ = writeln!(s, "|---|---|---|---|---|");
    for (ri, row) in g.rows.iter().enumerate() {
        for (ci, col) in g.cols.iter().enumerate() {
            let e = &g.entries[ri][ci];
            if e.keys.get(&cmp.axis) == Some(&cmp.baseline) {
                continue;
            }
            let Some(b) = g.baseline_of(e, &cmp.axis, &cmp.baseline) else { continue };
            let ratio = |x: Option<f64>, y: Option<f64>| match (x, y) {
                (Some(x), Some(y)) if y != 0.0 => Some(x / y),
                _ => None,
            };
            let ours = ratio(e.ours, b.ours);
            let paper = ratio(e.paper, b.paper);
            if ours.is_none() && paper.is_none() {
                continue;
            }
            let f = |v: Option<f64>| v.map(|v| format!("{v:.2}")).unwrap_or_else(|| "–".into());
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} |",
                header_of(&g.row_axes, row),
                header_of(&g.col_axes, col),
                f(ours),
                if has_paper { f(paper) } else { "–".into() },
                f(ratio(ours, paper))
            );
        }
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

pub fn csv(config: &Config, results: &Results) -> String {
    let mut s = String::from(
        "config,device,scene,technique,photons,lights,resolution,lighting,metric,kind,value,min,max,paper\n",
    );
    let num = |v: Option<f64>| v.map(|v| format!("{v}")).unwrap_or_default();
    for c in &results.cells {
        for m in &config.metrics {
            let Some(v) = c.metrics.get(&m.label) else { continue };
            let mut keys: std::collections::BTreeMap<String, String> =
                ["scene", "technique", "photons", "lights", "resolution", "lighting"]
                    .iter()
                    .map(|a| (a.to_string(), c.cell.key(a)))
                    .collect();
            keys.insert("metric".into(), m.label.clone());
            let paper = crate::paper::value(config, &keys);
            let fields = [
                results.config.name.clone(),
                results.meta.device.clone(),
                c.cell.key("scene"),
                c.cell.key("technique"),
                c.cell.key("photons"),
                c.cell.key("lights"),
                c.cell.key("resolution"),
                c.cell.key("lighting"),
                m.label.clone(),
                m.kind.clone(),
                num(v.value),
                num(v.min),
                num(v.max),
                num(paper),
            ];
            let _ = writeln!(s, "{}", fields.iter().map(|f| csv_field(f)).collect::<Vec<_>>().join(","));
        }
    }
    s
}

/// Values against photon count (photons² on a log2 axis), one solid line per table column and
/// other row axis, the paper's values dashed in the same colour. A table whose columns cross
/// the metrics with another axis (techniques × passes, as Wyman 2008 Table 3) gets a panel per
/// metric, each technique keeping its colour, rather than one chart of 30-odd lines.
pub fn plot(config: &Config, results: &Results) -> String {
    let g = grid(config, results);
    let photons_row = g.row_axes.iter().position(|a| a == "photons");
    let metric_col = g.col_axes.iter().position(|a| a == "metric");
    let panelled = metric_col.is_some() && g.col_axes.len() > 1 && config.metrics.len() > 1;
    let x_of = |ri: usize, row: &[String]| -> f64 {
        match photons_row {
            Some(p) => row[p].parse::<f64>().map(|n| n * n).unwrap_or(f64::NAN),
            None => ri as f64 + 1.0,
        }
    };
    let mut ticks: Vec<(f64, String)> = vec![];
    for (ri, row) in g.rows.iter().enumerate() {
        let label = match photons_row {
            Some(p) => display("photons", &row[p]),
            None => header_of(&g.row_axes, row),
        };
        let x = x_of(ri, row);
        if !ticks.iter().any(|(t, _)| *t == x) {
            ticks.push((x, label));
        }
    }
    // Series = columns (less the metric when panelled) x the row axes other than photons.
    let panel_names: Vec<String> =
        if panelled { config.metrics.iter().map(|m| m.label.clone()).collect() } else { vec![String::new()] };
    let mut panels: Vec<Vec<Series>> = vec![vec![]; panel_names.len()];
    let mut colours: Vec<String> = vec![];
    for (ri, row) in g.rows.iter().enumerate() {
        let others: Vec<String> = g
            .row_axes
            .iter()
            .zip(row)
            .enumerate()
            .filter(|(i, _)| photons_row.is_some() && Some(*i) != photons_row)
            .map(|(_, (a, k))| display(a, k))
            .collect();
        for (ci, col) in g.cols.iter().enumerate() {
            let (panel, axes, keys): (usize, Vec<String>, Vec<String>) = match metric_col.filter(|_| panelled) {
                Some(m) => (
                    panel_names.iter().position(|n| *n == col[m]).unwrap_or(0),
                    g.col_axes.iter().enumerate().filter(|(i, _)| *i != m).map(|(_, a)| a.clone()).collect(),
                    col.iter().enumerate().filter(|(i, _)| *i != m).map(|(_, k)| k.clone()).collect(),
                ),
                None => (0, g.col_axes.clone(), col.clone()),
            };
            let mut name = header_of(&axes, &keys);
            if !others.is_empty() {
                name = format!("{} · {name}", others.join(" · "));
            }
            let colour = match colours.iter().position(|n| *n == name) {
                Some(i) => i,
                None => {
                    colours.push(name.clone());
                    colours.len() - 1
                }
            };
            let e = &g.entries[ri][ci];
            let x = x_of(ri, row);
            let series = &mut panels[panel];
            for (paper, v) in [(false, e.ours), (true, e.paper)] {
                let label = if paper { format!("{name} (paper)") } else { name.clone() };
                let idx = match series.iter().position(|s| s.label == label) {
                    Some(i) => i,
                    None => {
                        series.push(Series { label, points: vec![], dashed: paper, colour: Some(colour) });
                        series.len() - 1
                    }
                };
                if let Some(v) = v {
                    series[idx].points.push((x, v));
                }
            }
        }
    }
    let kinds: Vec<&str> = config.metrics.iter().map(|m| unit(&m.kind)).collect();
    let y_label = match kinds.first() {
        Some(u) if !u.is_empty() && kinds.iter().all(|k| k == u) => u.to_string(),
        _ => "value".into(),
    };
    let title = format!("{}, Table {}", config.table.paper, config.table.number);
    let subtitle = format!("{} · {} · {}", results.meta.device, results.meta.driver_info, results.meta.date);
    let charts: Vec<Chart> = panels
        .into_iter()
        .zip(&panel_names)
        .map(|(mut series, panel)| {
            // Drop paper series the paper has no value for.
            series.retain(|s| !s.dashed || !s.points.is_empty());
            Chart {
                title: panel.clone(),
                subtitle: String::new(),
                x_label: if photons_row.is_some() { "photons".into() } else { g.row_axes.join(" · ") },
                y_label: y_label.clone(),
                x_log2: photons_row.is_some(),
                x_tick_labels: ticks.clone(),
                y_log: config.table.plot_log_y,
                series,
            }
        })
        .collect();
    match charts.as_slice() {
        [one] if !panelled => crate::svg::render(&Chart { title, subtitle, ..one.clone() }),
        _ => crate::svg::render_panels(&title, &subtitle, &charts),
    }
}

/// Cells above this CPU steal are named in the table's header.
const NOTABLE_STEAL: f64 = 0.10;

/// How much CPU the hypervisor took while the cells ran, and which cells lost most: on a
/// software device their times are inflated by about 1 / (1 - steal).
fn steal_line(results: &Results) -> Option<String> {
    let mut steal: Vec<(f64, String)> =
        results.cells.iter().filter_map(|c| Some((c.cpu_steal?, short(&c.cell)))).collect();
    if steal.is_empty() {
        return None;
    }
    steal.sort_by(|a, b| a.0.total_cmp(&b.0));
    let pct = |v: f64| format!("{:.0}%", v * 100.0);
    let median = steal[steal.len() / 2].0;
    let mut line = format!(
        "- **Host CPU steal** (CPU time the hypervisor gave to other guests while a cell's frames ran): median {}, \
         max {}",
        pct(median),
        pct(steal[steal.len() - 1].0)
    );
    let notable: Vec<String> =
        steal.iter().rev().filter(|(v, _)| *v > NOTABLE_STEAL).map(|(v, d)| format!("{d} ({})", pct(*v))).collect();
    if !notable.is_empty() {
        let shown = notable.len().min(5);
        let more = if notable.len() > shown { format!(" and {} more", notable.len() - shown) } else { String::new() };
        line.push_str(&format!(
            ". Above {}, times run long by about 1 / (1 − steal): {}{more}",
            pct(NOTABLE_STEAL),
            notable[..shown].join("; ")
        ));
    }
    Some(line)
}

fn short(cell: &crate::plan::Cell) -> String {
    format!("{} · {} · {}²", cell.key("scene"), cell.key("technique"), cell.key("photons"))
}

/// A paper's value as the paper prints it (the config holds it verbatim): 3.6 stays 3.6, 8.0 stays
/// 8.0 (TOML keeps no trailing zeros beyond that).
/// Counts keep their thousands separators.
fn paper_value(kind: &str, v: Option<f64>) -> String {
    match (kind, v) {
        ("photons_emitted" | "splats_drawn" | "photons_processed", _) | (_, None) => format_value(kind, v),
        (_, Some(v)) if v.fract() == 0.0 => format!("{v:.1}"),
        (_, Some(v)) => format!("{v}"),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn paper_values_print_as_the_paper_prints_them() {
        assert_eq!(super::paper_value("fps", Some(3.6)), "3.6");
        assert_eq!(super::paper_value("pass_ms", Some(861.0)), "861.0");
        assert_eq!(super::paper_value("pass_ms", Some(0.02)), "0.02");
        assert_eq!(super::paper_value("photons_processed", Some(262144.0)), "262,144");
        assert_eq!(super::paper_value("fps", None), "–");
    }

    #[test]
    fn units_line_names_the_unit_of_every_metric() {
        let line = |m: &[(&'static str, &'static str)]| super::units_line(m.iter().copied());
        assert_eq!(line(&[("a", "pass_ms"), ("b", "frame_ms")]).as_deref(), Some("Values in ms."));
        assert_eq!(line(&[("rel", "rel_rmse"), ("flux", "flux_ratio")]), None);
        // hcm_paths: times and a photon count in one table.
        assert_eq!(
            line(&[("Traversal", "pass_ms"), ("Frame", "frame_ms"), ("processed", "photons_processed")]).as_deref(),
            Some("Values: `Traversal`, `Frame` in ms; `processed` in points.")
        );
        assert_eq!(
            line(&[("fps", "fps"), ("rel", "rel_rmse")]).as_deref(),
            Some("Values: `fps` in fps; `rel` unitless.")
        );
    }
}
